// Reading and writing meshes: OBJ, OFF, PLY (ASCII and binary, either
// endianness) and STL (read only, ASCII and binary, equal corners welded), each
// optionally gzip-compressed (detected from the bytes, not the name). Writers
// never leave a partial file: temporary file in the target directory, renamed.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "intrinsic/error.h"
#include "intrinsic/mesh_data.h"

namespace intrinsic {

struct ReadOptions {
  // Refuse files announcing or containing more than this many vertices or
  // faces, before allocating for them.
  std::int64_t max_vertices = 50'000'000;
  std::int64_t max_faces = 100'000'000;
};

// Throws Error(Input) naming file and line (or byte offset / element index in
// binary files) on anything malformed.
MeshData read_mesh(const std::string& path, const ReadOptions& options = {});
// Same, from bytes already in memory (used by fuzz targets and tests); the
// format is taken from `name`'s extension (".obj", ".off", ".ply", ".stl",
// optionally ".gz") and gzip is also recognised from the magic bytes.
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

// Atomically writes `contents` to `path` (temp file + rename). Shared by every
// writer in the project (JSON reports, PNG images, meshes).
void write_file_atomically(const std::string& path, const std::string& contents);
// The same for contents produced piece by piece: `produce` is called once
// with a sink and hands it the file's bytes in order (large files are then
// formatted and written at the same time, never held whole in memory). An
// exception from `produce` or the sink leaves no file behind.
using ByteSink = std::function<void(const char* data, std::size_t size)>;
void write_file_atomically(const std::string& path, const std::function<void(const ByteSink&)>& produce);

// For programs (the CLI calls it first thing; library code never installs
// handlers by itself): SIGINT, SIGTERM, SIGHUP and SIGQUIT delete the temporary
// files of writes in progress before taking their default action, and SIGXFSZ
// is ignored so that exceeding a file size limit fails the write (EFBIG,
// Error(Output)) instead of killing the process with the file half written.
void remove_temporary_files_on_signals();

}  // namespace intrinsic
