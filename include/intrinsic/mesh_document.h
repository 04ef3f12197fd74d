// A mesh file as read: its geometry (MeshData, mesh_data.h) and, beside it,
// what the file carried beyond geometry, kept so that writers can give it
// back (docs/formats.md "OBJ", "glTF"). read_mesh_file (io.h) gives both;
// read_mesh gives the geometry alone, which is all the solvers and the atlas
// computation read.
// An OBJ's extras are its normals, material libraries and, per face, its
// material, group, object and smoothing group, as a small index into a table
// of names (nothing per face is allocated when the file has none of it);
// every triangle of a polygon inherits the polygon's. A glTF input (or an
// asset assimp reads, through glTF) fills the same from its document, so
// that an OBJ output keeps them; the whole document is kept too, so that a
// glTF output is that document with the atlas added (intrinsic/gltf.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "intrinsic/mesh_data.h"

namespace intrinsic {

struct GltfDocument;  // src/io/gltf_document.h: opaque outside the library

// One OBJ state statement (usemtl, g, o or s) as a per-face label: the
// distinct names in order of first appearance, and per face the index of the
// name in force when the face was read, -1 before the file's first statement
// of the kind. `of_face` is empty when no face follows such a statement.
struct FaceLabels {
  std::vector<std::string> names;  // as written after the keyword ("" for a bare keyword)
  std::vector<int> of_face;        // #F, or empty
  bool empty() const { return of_face.empty(); }
  // The label of face f, or nullptr when it has none.
  const std::string* of(int f) const {
    if (of_face.empty() || of_face[static_cast<std::size_t>(f)] < 0) return nullptr;
    return &names[static_cast<std::size_t>(of_face[static_cast<std::size_t>(f)])];
  }
};

// What an OBJ writer gives back beyond positions, texture coordinates and
// faces. Per-face and per-corner arrays follow the faces of the MeshData
// beside it.
struct ObjExtras {
  // Normals as written (`vn`, not renormalized; a glTF input's NORMAL in
  // world space), and per corner the row of N, -1 for a corner without one;
  // FN is empty when no corner has a normal.
  MatrixX3d N;
  MatrixX3i FN;
  std::vector<std::string> material_libraries;  // each `mtllib` line's text after the keyword, in file order
  FaceLabels materials;  // usemtl
  FaceLabels groups;     // g (the whole list of names on the line, as one label)
  FaceLabels objects;    // o
  FaceLabels smoothing;  // s ("off", "0", "1", ... as written)

  // Normals for every face of F (the faces they came with).
  bool has_normals(const MatrixX3i& F) const { return N.rows() > 0 && FN.rows() == F.rows(); }
  // Nothing for a writer to give back.
  bool empty() const {
    return FN.rows() == 0 && material_libraries.empty() && materials.empty() && groups.empty() &&
           objects.empty() && smoothing.empty();
  }
};

// Everything a file carried beyond its geometry.
struct MeshDocument {
  ObjExtras obj;
  // Set when the mesh was read from a .gltf/.glb (or through assimp): the
  // whole document, with the origin of every merged vertex and face, so that
  // write_atlas_file can write the atlas back into it. Shared: copies of a
  // MeshFile do not copy the document.
  std::shared_ptr<const GltfDocument> gltf;
};

// A mesh as read from a file: the geometry and, beside it, its document.
struct MeshFile {
  MeshData mesh;
  // Empty for a mesh that comes from no file: MeshFile{mesh} (the default
  // initializer lets that form leave it out).
  MeshDocument document = {};
};

}  // namespace intrinsic
