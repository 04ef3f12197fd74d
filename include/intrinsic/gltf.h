// glTF 2.0 documents in and out (docs/formats.md "glTF"). Reading merges the
// triangles of every mesh primitive (lists, strips, fans; Draco-compressed
// ones decoded) into one MeshData at world scale, so an atlas sizes its
// charts by the area a viewer sees; the parsed document is kept beside it
// (MeshFile, MeshDocument::gltf). Writing puts the atlas back into that
// same document as one more texture coordinate set, splitting vertices at
// the seams and copying every other attribute, leaves everything else
// (nodes, materials, animations, skins, extensions...) as it was, and drops
// the data nothing references any more (intrinsic/atlas_files.h).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "intrinsic/io.h"
#include "intrinsic/mesh_data.h"
#include "intrinsic/mesh_document.h"

namespace intrinsic {

// .gltf (JSON, buffers in data URIs or files beside it) or .glb. Refuses with
// Error(Input) naming the file and the JSON path of the offending object, e.g.
// "x.gltf: /meshes/0/primitives/0/indices: index 71 out of range (24 vertices)".
// A mesh drawn by several nodes appears once, placed by its first instance
// (scene graph walked from the default scene's roots, then the other scenes',
// then any other parentless node, depth first). External buffer files are
// read relative to `path`'s folder. read_gltf_file keeps the document beside
// the mesh; read_gltf is the mesh alone.
MeshFile read_gltf_file(const std::string& path, const ReadOptions& options = {});
MeshData read_gltf(const std::string& path, const ReadOptions& options = {});
// The same from bytes in memory; external buffer files are refused (there is
// no folder to read them from). `name` is used for messages.
MeshFile read_gltf_file_from_memory(const std::string& bytes, const std::string& name,
                                    const ReadOptions& options = {});
MeshData read_gltf_from_memory(const std::string& bytes, const std::string& name, const ReadOptions& options = {});

// What a document-backed input holds (MeshDocument::gltf; all 0 otherwise):
// for reports, which say what was charted and what was carried along untouched.
struct SceneSummary {
  int meshes = 0;        // glTF meshes (after InstanceMode::Unique's copies)
  int instances = 0;     // nodes drawing a mesh
  int materials = 0, images = 0, cameras = 0, lights = 0;
  int skipped_primitives = 0;  // points and lines: kept in the document, not charted
};
SceneSummary scene_summary(const MeshDocument& document);

// The document's TEXCOORD_<set> as the mesh's own texture coordinates
// (file.mesh's TC one row per merged vertex, in our convention v up:
// (u, 1 - v); FTC = F), e.g. to re-pack them (AtlasOptions::pack_only).
// Error(Input) naming the primitive when one lacks the set; Error(Usage)
// without a document.
void read_gltf_texcoords(MeshFile& file, int set);

// Where each merged vertex and face came from (Error(Usage) without a
// document).
struct GltfProvenance {
  std::vector<int> vertex_mesh, vertex_primitive, vertex_index;  // per merged vertex: its source vertex
  std::vector<int> face_mesh, face_primitive;                    // per merged face
};
GltfProvenance gltf_provenance(const MeshFile& file);

}  // namespace intrinsic
