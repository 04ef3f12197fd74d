// The atlas's own files: seams files read (edges to cut), and atlases
// written: OBJ with its material files, the one-mesh .glb, and a glTF input's
// own document with the atlas added as a TEXCOORD set (docs/formats.md).
// The writers take the input as a MeshFile (mesh_document.h): what they give
// back of it besides the atlas (normals, labels, materials, the glTF
// document) is its document; a mesh without one is MeshFile{mesh}.
// Above io (which reads and writes meshes) and the atlas (which computes
// AtlasResult); implemented in src/atlas/files/.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "intrinsic/atlas.h"
#include "intrinsic/gltf.h"
#include "intrinsic/io.h"
#include "intrinsic/mesh_data.h"
#include "intrinsic/mesh_document.h"

namespace intrinsic {

// Seams files (src/atlas/files/seams_file.cpp): one edge `i j` per line, 0-based
// vertex indices in input order, `#` comments. Throws Error(Input) naming the
// file and line for a malformed line, an out-of-range index, a pair that is
// not an edge of `mesh` (find_seam_problem), and for a file with no edge.
std::vector<SeamEdge> parse_seams_text(const std::string& text, const std::string& name, const MeshData& mesh);
std::vector<SeamEdge> read_seams_file(const std::string& path, const MeshData& mesh);

// Atlases (src/atlas/files/atlas_files.cpp). The OBJ: the input's vertices in input
// order, one `vt` per atlas UV, the result's faces (the input's, reoriented
// ones reversed) `f v/vt` (seams only through the per-corner texture
// coordinates), and what the input's document holds for an OBJ (normals as
// `f v/vt/vn`, mtllib, usemtl, g, o, s); atomically, with the material files
// its mtllib needs beside it (docs/formats.md "OBJ materials travel with the
// output").
void write_atlas_obj(const std::string& path, const MeshFile& input, const AtlasResult& r);
// The same OBJ naming exactly `mtllib`, files the caller writes itself.
void write_atlas_obj_naming(const std::string& path, const MeshFile& input, const AtlasResult& r,
                            const std::vector<std::string>& mtllib);
// The atlas in the format the extension names: .obj (write_atlas_obj), or
// .glb/.gltf: the input's own glTF document with the atlas added when the
// input has one (write_gltf_atlas, intrinsic/gltf.h), else write_glb's
// one-mesh file (vertices split at seams). check_atlas_output throws
// Error(Usage) for any other extension, before anything is written.
void check_atlas_output(const std::string& path);
void write_atlas_file(const std::string& path, const MeshFile& input, const AtlasResult& r);

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
  OptionSpelling spelling = OptionSpelling::Keyword;  // how messages name these options
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

// Writes `input`'s glTF document back with the atlas `result` (computed on
// input.mesh) as a new TEXCOORD set: .glb or .gltf (buffer embedded as a data URI)
// by the extension of `path`. Every triangle primitive becomes an indexed
// TRIANGLES list (faces in order, each with the document's winding even where
// the atlas reoriented it) whose vertices are split where the atlas has a seam, every
// other attribute and morph target copied per vertex; all buffers are merged
// into one. Atomic: nothing is written when anything is refused.
GltfWriteResult write_gltf_atlas(const std::string& path, const MeshFile& input, const AtlasResult& result,
                                 const GltfWriteOptions& options = {});

// write_atlas_file (io.h) with the choice of UV set for a glTF input
// (ignored for other inputs and for .obj output) and allow_missing_images
// (every output). Returns the files written beside the output (images, .mtl)
// and the images left missing.
GltfWriteResult write_atlas_file(const std::string& path, const MeshFile& input, const AtlasResult& r,
                                 const GltfWriteOptions& gltf_options);

}  // namespace intrinsic
