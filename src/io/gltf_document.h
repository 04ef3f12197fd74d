// The parsed glTF document that the reader keeps beside the merged mesh
// (MeshDocument::gltf) and write_gltf_atlas writes back: the JSON as it was, the
// bytes of every buffer, and where each merged vertex and face came from.
// Also the pieces the reader and writer share: JSON access that refuses
// with the JSON path, accessors (validated, densified with sparse values
// applied), base64.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "intrinsic/error.h"
#include "intrinsic/io.h"

namespace intrinsic {

struct GltfDocument {
  std::string name;  // the source file, for messages
  // Where the document's relative URIs (images) resolve: the source file's
  // folder ("." for the working directory); empty for bytes given in memory.
  std::string folder;
  nlohmann::json json;
  std::vector<std::string> buffers;  // each exactly its declared byteLength
  // A triangle primitive of the merged mesh: its vertices are
  // first_vertex..+vertex_count, its faces first_face..+face_count.
  struct Primitive {
    int mesh = 0, primitive = 0;
    int first_vertex = 0, vertex_count = 0, first_face = 0, face_count = 0;
  };
  std::vector<Primitive> primitives;
  std::vector<int> vertex_source;   // per merged vertex: its index in its primitive's attributes
  std::vector<int> face_primitive;  // per merged face: index into `primitives`
};

namespace gltf {

[[noreturn]] inline void fail(const std::string& name, const std::string& path, const std::string& what) {
  throw_input(name + ": " + path + ": " + what);
}

// JSON access that refuses wrong types with the path.
const nlohmann::json& array_at(const nlohmann::json& j, const char* key, const std::string& name,
                               const std::string& path);  // empty array when absent
std::int64_t integer(const nlohmann::json& j, const std::string& name, const std::string& path);
// j[key] as an index into an array of `size` (a missing key gives -1 when
// `optional`, else an error).
int index_at(const nlohmann::json& j, const char* key, std::size_t size, const std::string& name,
             const std::string& path, bool optional = false);
double number(const nlohmann::json& j, const std::string& name, const std::string& path);

// An accessor read whole: count elements of `components` values of
// `component` type, tightly packed in `bytes` (count * element_size), with its
// sparse substitutions already applied.
struct Accessor {
  int component = 0;   // 5120 BYTE .. 5126 FLOAT
  int components = 0;  // 1 SCALAR .. 16 MAT4
  std::string type;
  bool normalized = false;
  std::int64_t count = 0;
  int component_size = 0;
  int element_size() const { return component_size * components; }
  std::string bytes;
  // Component k of element i as a number (normalized integers mapped to
  // [0, 1] or [-1, 1] as the glTF spec says).
  double value(std::int64_t i, int k) const;
  // The same without normalization (integer values as stored).
  double raw(std::int64_t i, int k) const;
};

// Checks accessor `index` (bounds of its buffer view, sparse indices and
// values, component type) and reads it; refuses more than `max_count`
// elements before allocating.
Accessor read_accessor(const GltfDocument& doc, int index, std::int64_t max_count);

std::string base64_decode(const std::string& text, std::size_t begin, const std::string& name,
                          const std::string& path);
std::string base64_encode(const std::string& bytes);
// A URI's %XX escapes decoded (a file name beside a .gltf, e.g. "my%20tex.png").
std::string percent_decode(const std::string& s);

// Parses .gltf or .glb bytes: JSON, buffers (GLB chunk, data URIs, and files
// under `folder` when `files_allowed`), buffer views checked against them.
GltfDocument load_document(const std::string& bytes, const std::string& name, const std::string& folder,
                           bool files_allowed);

// gltf_draco.cpp: decodes every KHR_draco_mesh_compression primitive into
// plain accessors (a new buffer with a view per attribute and the indices),
// refusing a malformed stream with its JSON path.
void decode_draco(GltfDocument& doc);

// gltf_prune.cpp: drops the accessors, buffer views and bytes of `bin` (the
// document's one buffer) that nothing references any more, renumbering every
// reference. Leaves everything as it was when an extension it does not know
// is used (kept_because names it).
struct PruneOutcome {
  bool pruned = false;
  std::string kept_because;
  int accessors_dropped = 0, views_dropped = 0;
  std::int64_t bytes_dropped = 0;
};
PruneOutcome prune_unreferenced(nlohmann::json& j, std::string& bin);

// Drops the textures, images and samplers that `before` (the input
// document) references and `after` (the output) no longer does, e.g. the
// images a texture transfer replaced, renumbering the references. Returns
// per image of `after` its new index (-1: dropped); empty when nothing went.
// What the input carried unreferenced is kept.
std::vector<int> prune_replaced_textures(const nlohmann::json& before, nlohmann::json& after);

}  // namespace gltf

namespace io {
// read_mesh's glTF branch (gltf_reader.cpp): `bytes` of the file `name`;
// external buffer files are read beside it only when `files_allowed`.
MeshFile read_gltf(const std::string& bytes, const std::string& name, const ReadOptions& options, bool files_allowed);
// A loaded document as one mesh: every triangle primitive at world scale,
// with per-face material, mesh and node names and per-corner world normals
// (what an OBJ output gives back, MeshDocument::obj); the document is kept
// beside the mesh (MeshDocument::gltf).
MeshFile read_gltf_document(GltfDocument doc, const ReadOptions& options);
}  // namespace io
}  // namespace intrinsic
