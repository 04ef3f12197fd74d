// Every file format of the project. Reading and writing meshes: OBJ, OFF, PLY (ASCII and binary, either
// endianness), STL (read only, ASCII and binary, equal corners welded) and glTF 2.0 (.gltf/.glb: every
// triangle primitive merged at world scale, the document kept by read_mesh_file; intrinsic/gltf.h), each
// optionally gzip-compressed (detected from the bytes, not the name), and
// every other format assimp imports (FBX, Collada, 3DS, LWO, X, .blend...:
// supported_formats() lists them). Writers
// never leave a partial file: temporary file in the target directory, renamed.
// Then the side files (boundary positions, constraints). The atlas's own
// files (seams in, atlases out) are in intrinsic/atlas_files.h.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "intrinsic/choice.h"
#include "intrinsic/error.h"
#include "intrinsic/boundary.h"
#include "intrinsic/constraints.h"
#include "intrinsic/mesh_data.h"
#include "intrinsic/mesh_document.h"

namespace intrinsic {

// A mesh drawn by several nodes of a scene (glTF, and the formats read
// through assimp): Shared reads it once, placed by its first instance, and the
// nodes of a written document keep pointing at it (one chart layout for all:
// what a texture atlas wants); Unique gives each node a copy of the mesh, so
// each instance has charts of its own (what a lightmap wants).
enum class InstanceMode { Shared, Unique };
template <>
ChoiceTable<InstanceMode> choice_table<InstanceMode>();

struct ReadOptions {
  // Refuse files announcing or containing more than this many vertices or
  // faces, before allocating for them.
  std::int64_t max_vertices = 50'000'000;
  std::int64_t max_faces = 100'000'000;
  InstanceMode instances = InstanceMode::Shared;
};

// Throws Error(Input) naming file and line (or byte offset / element index in
// binary files) on anything malformed. The project's own readers take .obj,
// .off, .ply, .stl, .gltf and .glb; any other extension assimp imports goes
// through assimp (src/io/assimp_reader.cpp): every mesh at world scale (first
// instance of each), corners at equal positions welded, material, node and
// mesh names as per-face labels (materials, objects, groups), points and
// lines skipped; assimp's refusals become Error(Input) with the file named
// and assimp's message. An unknown extension is Error(Usage).
// read_mesh_file gives the geometry and the file's document beside it
// (intrinsic/mesh_document.h: an OBJ's normals and labels, a glTF document),
// which the atlas writers give back; read_mesh is its geometry alone.
MeshFile read_mesh_file(const std::string& path, const ReadOptions& options = {});
MeshData read_mesh(const std::string& path, const ReadOptions& options = {});
// Same, from bytes already in memory (used by fuzz targets and tests); the
// format is taken from `name`'s extension (".obj", ".off", ".ply", ".stl",
// ".gltf", ".glb", optionally ".gz") and gzip is also recognised from the
// magic bytes. A glTF document given in memory may not name buffer files.
MeshFile read_mesh_file_from_memory(const std::string& bytes, const std::string& name,
                                    const ReadOptions& options = {});
MeshData read_mesh_from_memory(const std::string& bytes, const std::string& name,
                               const ReadOptions& options = {});

struct WriteOptions {
  bool binary = false;  // PLY only
};

// Writes V, F and one UV per vertex (UV may be empty: no texture coordinates).
// Format from the extension: .obj, .ply or .glb (write_glb with the corners
// indexing UV like V; needs UV). Throws Error(Output) on failure,
// leaving no file behind.
void write_mesh(const std::string& path, const MatrixX3d& V, const MatrixX3i& F,
                const MatrixX2d& UV, const WriteOptions& options = {});

// glTF 2.0 binary (.glb) of a mesh with per-corner texture coordinates
// (FUV: #F x 3 rows of UV, as an atlas gives them), for engines and Blender.
// glTF attributes are per vertex, so a vertex is written once per distinct
// texture coordinate among its corners (split at seams), in order of first
// use by the faces; unreferenced vertices are left out. NORMAL is smoothed
// as modelling tools' "auto smooth": per corner, the area-weighted mean of
// the normals of the faces around its vertex within 60 degrees of its own
// face's, so a vertex is also split at hard edges. One mesh, one triangle
// primitive: POSITION (float32, with min/max), NORMAL, TEXCOORD_0 (float32,
// (u, 1 - v): glTF's texture origin is the top-left corner, ours the
// bottom-left), uint32 indices, faces in input order. Throws Error(Input) for
// an empty or inconsistent mesh or coordinates beyond float32, Error(Output)
// when writing fails; atomic.
void write_glb(const std::string& path, const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV,
               const MatrixX3i& FUV);

// What the project reads and writes (`intrinsic formats`): one row per
// extension, ours first, then assimp's in alphabetical order.
enum class FormatReader {
  None,    // not read (written only)
  Own,     // the project's own reader (line numbers in messages, stricter)
  Assimp,  // through assimp
};
struct FormatInfo {
  std::string extension;  // lower case with the dot: ".fbx"
  std::string name;       // "Wavefront OBJ", or the assimp importer's name
  FormatReader reader = FormatReader::None;
  bool gzip = false;         // also read gzip-compressed (".obj.gz")
  bool writes_mesh = false;  // write_mesh (`param`, `generate` outputs)
  bool writes_atlas = false; // write_atlas_file (`atlas` outputs)
};
std::vector<FormatInfo> supported_formats();

// Lower-case extension after stripping a trailing ".gz": "mesh.OBJ.gz" -> ".obj"
// ("" when there is none).
std::string mesh_extension(const std::string& path);

// The face cap that goes with a vertex cap: a manifold triangle mesh has about
// twice as many faces as vertices (4x leaves room for high genus and seams).
// It also bounds the gzip inflate cap, so a vertex cap limits memory.
std::int64_t faces_for_vertices(std::int64_t max_vertices);

// Side files that go with a mesh. Boundary files (src/io/boundary_file.cpp):
// reads lines "vertex_index u v", '#' comments, blank lines.
// Throws Error(Input) naming file and line for malformed lines, out-of-range
// or repeated vertices, non-finite values.
std::vector<FixedVertex> read_boundary_file(const std::string& path, int num_vertices);
std::vector<FixedVertex> parse_boundary_text(const std::string& text, const std::string& name, int num_vertices);

// The constraint file: {"points": [...], "lines": [...]}, either optional.
// A point is {"face": f, "bary": [b1, b2, b3], "uv": [u, v]} or
// {"vertex": i, "uv": [u, v]}; a line is {"path": [points without "uv"],
// "to": [[u0, v0], [u1, v1], ...]}. Unknown keys, wrong types and malformed
// JSON are refused with Error(Input) naming `name` and the JSON path, e.g.
// "c.json: points[2]: unknown key 'uvw'". Ranges are checked later, by
// resolve_constraints, against the mesh.
Constraints parse_constraints_json(const std::string& text, const std::string& name);
Constraints read_constraints_file(const std::string& path);

// Atomically writes `contents` to `path` (temp file + rename). Shared by every
// writer in the project (JSON reports, PNG images, meshes).
void write_file_atomically(const std::string& path, const std::string& contents);
// The same for contents produced piece by piece: `produce` is called once
// with a sink and hands it the file's bytes in order (large files are then
// formatted and written at the same time, never held whole in memory). An
// exception from `produce` or the sink leaves no file behind.
using ByteSink = std::function<void(const char* data, std::size_t size)>;
void write_file_atomically(const std::string& path, const std::function<void(const ByteSink&)>& produce);

// Writes each (path, bytes) atomically in order. If one fails, the files of
// this call written before it and every path in `written_before` are removed,
// then the error propagates: a failed run leaves no partial set of outputs.
void write_all(const std::vector<std::pair<std::string, std::string>>& files,
               const std::vector<std::string>& written_before = {});

// For programs (the CLI calls it first thing; library code never installs
// handlers by itself): SIGINT, SIGTERM, SIGHUP and SIGQUIT delete the temporary
// files of writes in progress before taking their default action, and SIGXFSZ
// is ignored so that exceeding a file size limit fails the write (EFBIG,
// Error(Output)) instead of killing the process with the file half written.
void remove_temporary_files_on_signals();

}  // namespace intrinsic
