// What every reader fills while parsing: flat growable arrays (cheap to append
// to), turned into the Eigen matrices of MeshData once at the end.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "intrinsic/io.h"
#include "intrinsic/mesh.h"

namespace intrinsic::io {

struct MeshBuilder {
  std::vector<double> xyz;        // 3 per vertex
  std::vector<double> uv;         // 2 per texture coordinate
  std::vector<int> tri;           // 3 per triangle
  std::vector<int> tri_uv;        // 3 per triangle, or empty
  std::vector<int> line;          // source line per triangle (0 for binary)
  bool had_texcoords = false;     // texture coordinates were read, even if dropped since (MeshData::had_texcoords)

  std::int64_t vertex_count() const { return static_cast<std::int64_t>(xyz.size() / 3); }
  std::int64_t triangle_count() const { return static_cast<std::int64_t>(tri.size() / 3); }

  // Checks the sizes every format shares ("no vertices", "no faces") and
  // builds the result.
  MeshData finish(const std::string& name);
};

// Format readers over a buffer already in memory (decompressed if needed).
// Only an OBJ carries more than geometry (its extras, mesh_document.h).
MeshFile read_obj(const char* data, std::size_t size, const std::string& name, const ReadOptions& opt);
MeshData read_off(const char* data, std::size_t size, const std::string& name, const ReadOptions& opt);
MeshData read_ply(const char* data, std::size_t size, const std::string& name, const ReadOptions& opt);
MeshData read_stl(const char* data, std::size_t size, const std::string& name, const ReadOptions& opt);

// Limits shared by readers: the options' caps, and the int range of MatrixX3i.
std::int64_t vertex_limit(const ReadOptions& opt);
std::int64_t face_limit(const ReadOptions& opt);

}  // namespace intrinsic::io
