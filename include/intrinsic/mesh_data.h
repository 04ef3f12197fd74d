// Plain mesh data as read from a file: libigl-style Eigen matrices.
// V is #V x 3 positions, F is #F x 3 zero-based vertex indices (polygons
// already fan-triangulated). Optional texture coordinates TC (#TC x 2) with
// per-corner indices FTC (#F x 3), as OBJ stores them; for PLY u,v vertex
// properties FTC equals F.
// What an OBJ carries beyond that is kept too, so that writers can give it
// back (docs/formats.md, "OBJ"): normals with per-corner indices, the
// material libraries, and per face its material, group, object and smoothing
// group, as a small index into a table of names (nothing per face is
// allocated when the file has none of it). Every triangle of a polygon
// inherits the polygon's.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products, 2x2 inverses
#include <memory>
#include <string>
#include <vector>

namespace intrinsic {

struct GltfDocument;  // src/io/gltf_document.h (intrinsic/gltf.h)

using Eigen::MatrixX2d;
using Eigen::MatrixX3d;
using Eigen::MatrixX3i;

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

struct MeshData {
  MatrixX3d V;
  MatrixX3i F;
  MatrixX2d TC;   // empty when the file has no texture coordinates
  MatrixX3i FTC;  // #F x 3 when TC is present, else empty
  // For error messages: the 1-based source line of each face in text formats
  // (several triangles share the line of their polygon), or 0 for binary files.
  std::vector<int> face_line;
  std::string path;  // the file it came from, for messages
  // The file had texture coordinates (OBJ vt lines, PLY u, v), whether or
  // not they were kept in TC (an OBJ's are dropped unless every face indexes
  // them): an atlas written from this mesh replaces them.
  bool had_texcoords = false;

  // OBJ only (empty otherwise). Normals as written (`vn`, not renormalized),
  // and per corner the row of N, -1 for a corner written without one; FN is
  // empty when no corner has a normal.
  MatrixX3d N;
  MatrixX3i FN;
  std::vector<std::string> material_libraries;  // each `mtllib` line's text after the keyword, in file order
  FaceLabels materials;  // usemtl
  FaceLabels groups;     // g (the whole list of names on the line, as one label)
  FaceLabels objects;    // o
  FaceLabels smoothing;  // s ("off", "0", "1", ... as written)

  // Set when the mesh was read from a .gltf/.glb: the whole document, so that
  // write_atlas_file can write the atlas back into it (intrinsic/gltf.h).
  std::shared_ptr<const GltfDocument> gltf;

  bool has_uv() const { return TC.rows() > 0 && FTC.rows() == F.rows(); }
  bool has_normals() const { return N.rows() > 0 && FN.rows() == F.rows(); }
  // Anything an OBJ writer has to give back beyond positions and faces.
  bool has_obj_extras() const {
    return has_normals() || !material_libraries.empty() || !materials.empty() || !groups.empty() ||
           !objects.empty() || !smoothing.empty();
  }
};

}  // namespace intrinsic
