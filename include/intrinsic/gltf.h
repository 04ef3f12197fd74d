// glTF 2.0 documents in and out (docs/formats.md "glTF"). Reading merges the
// triangles of every mesh primitive (lists, strips, fans; Draco-compressed
// ones decoded) into one MeshData at world scale, so an atlas sizes its
// charts by the area a viewer sees; the parsed document rides along in
// MeshData::gltf. Writing puts the atlas back into that same document as one
// more texture coordinate set, splitting vertices at the seams and copying
// every other attribute, leaves everything else (nodes, materials,
// animations, skins, extensions...) as it was, and drops the data nothing
// references any more.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "intrinsic/atlas.h"
#include "intrinsic/io.h"
#include "intrinsic/mesh_data.h"

namespace intrinsic {

// .gltf (JSON, buffers in data URIs or files beside it) or .glb. Refuses with
// Error(Input) naming the file and the JSON path of the offending object, e.g.
// "x.gltf: /meshes/0/primitives/0/indices: index 71 out of range (24 vertices)".
// A mesh drawn by several nodes appears once, placed by its first instance
// (scene graph walked from the default scene's roots, then the other scenes',
// then any other parentless node, depth first). External buffer files are
// read relative to `path`'s folder.
MeshData read_gltf(const std::string& path, const ReadOptions& options = {});
// The same from bytes in memory; external buffer files are refused (there is
// no folder to read them from). `name` is used for messages.
MeshData read_gltf_from_memory(const std::string& bytes, const std::string& name, const ReadOptions& options = {});

// What a document-backed input holds (MeshData::gltf; all 0 otherwise): for
// reports, which say what was charted and what was carried along untouched.
struct SceneSummary {
  int meshes = 0;        // glTF meshes (after InstanceMode::Unique's copies)
  int instances = 0;     // nodes drawing a mesh
  int materials = 0, images = 0, cameras = 0, lights = 0;
  int skipped_primitives = 0;  // points and lines: kept in the document, not charted
};
SceneSummary scene_summary(const MeshData& data);

// The document's TEXCOORD_<set> as the mesh's own texture coordinates
// (TC one row per merged vertex, in our convention v up: (u, 1 - v); FTC =
// F), e.g. to re-pack them (AtlasOptions::pack_only). Error(Input) naming
// the primitive when one lacks the set; Error(Usage) without a document.
void read_gltf_texcoords(MeshData& data, int set);

// Where each merged vertex and face came from (MeshData::gltf must be set).
struct GltfProvenance {
  std::vector<int> vertex_mesh, vertex_primitive, vertex_index;  // per merged vertex: its source vertex
  std::vector<int> face_mesh, face_primitive;                    // per merged face
};
GltfProvenance gltf_provenance(const MeshData& data);

struct GltfWriteOptions {
  // The TEXCOORD_n set the atlas goes to: -1 = the next free set of each
  // primitive; n = that set in every primitive (an existing set is replaced;
  // a set that would leave a gap is refused with Error(Usage)).
  int texcoord_set = -1;
  // Replacing a set that a texture of the primitive's material reads is
  // refused with Error(Usage) unless this is true.
  bool replace_used_set = false;
  // Drop the accessors, buffer views and buffer bytes that nothing
  // references after the rewrite (the primitives' old data), so that a
  // document does not grow with every atlas written into it.
  bool prune = true;
  // An image the input names but that cannot be found (from the input's
  // folder, or by its file name there) is Error(Input) unless this is true;
  // then its URI is written as it was and listed in missing_images.
  bool allow_missing_images = false;
};

// What write_gltf_atlas did besides the atlas.
struct GltfWriteResult {
  bool pruned = false;  // unreferenced accessors, views and bytes dropped
  int accessors_dropped = 0, views_dropped = 0;
  std::int64_t bytes_dropped = 0;
  // Set when pruning was asked for but not done: the document uses an
  // extension this writer does not know, which could reference accessors
  // or buffer views, so everything was kept.
  std::string note;
  // Images written beside a .gltf output (copies of the input's files that
  // would not resolve from the output's folder), and the URIs written
  // although no file was found (allow_missing_images).
  std::vector<std::string> files;
  std::vector<std::string> missing_images;
  // When images the output no longer uses (replaced by a texture transfer)
  // were dropped: per image index before the drop, its index after (-1:
  // dropped). Empty when none was.
  std::vector<int> image_index;
};

// Writes `data`'s glTF document back with the atlas `result` (computed on
// `data`) as a new TEXCOORD set: .glb or .gltf (buffer embedded as a data URI)
// by the extension of `path`. Every triangle primitive becomes an indexed
// TRIANGLES list (faces in order, each with the document's winding even where
// the atlas reoriented it) whose vertices are split where the atlas has a seam, every
// other attribute and morph target copied per vertex; all buffers are merged
// into one. Atomic: nothing is written when anything is refused.
GltfWriteResult write_gltf_atlas(const std::string& path, const MeshData& data, const AtlasResult& result,
                                 const GltfWriteOptions& options = {});

// write_atlas_file (io.h) with the choice of UV set for a glTF input
// (ignored for other inputs and for .obj output) and allow_missing_images
// (every output). Returns the files written beside the output (images, .mtl)
// and the images left missing.
GltfWriteResult write_atlas_file(const std::string& path, const MeshData& m, const AtlasResult& r,
                                 const GltfWriteOptions& gltf_options);

}  // namespace intrinsic
