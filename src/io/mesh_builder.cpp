// Conversion of parsed arrays to MeshData, and the limits all readers share.
#include "io/mesh_builder.h"

#include <algorithm>
#include <climits>

#include "intrinsic/error.h"

namespace intrinsic::io {

std::int64_t vertex_limit(const ReadOptions& opt) {
  return std::min<std::int64_t>(opt.max_vertices, INT_MAX);
}
std::int64_t face_limit(const ReadOptions& opt) {
  // Faces count triangles after fan triangulation, and the row count of F is
  // an Eigen index, but the per-triangle line table is a vector<int>: INT_MAX.
  return std::min<std::int64_t>(opt.max_faces, INT_MAX);
}

MeshData MeshBuilder::finish(const std::string& name) {
  if (xyz.empty()) throw_input(name + ": no vertices");
  if (tri.empty()) throw_input(name + ": no faces");
  MeshData m;
  const Eigen::Index nv = static_cast<Eigen::Index>(xyz.size() / 3);
  const Eigen::Index nf = static_cast<Eigen::Index>(tri.size() / 3);
  using RowX3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  using RowX2d = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;
  using RowX3i = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
  m.V = Eigen::Map<const RowX3d>(xyz.data(), nv, 3);
  m.F = Eigen::Map<const RowX3i>(tri.data(), nf, 3);
  if (!uv.empty() && tri_uv.size() == tri.size()) {
    m.TC = Eigen::Map<const RowX2d>(uv.data(), static_cast<Eigen::Index>(uv.size() / 2), 2);
    m.FTC = Eigen::Map<const RowX3i>(tri_uv.data(), nf, 3);
  }
  m.had_texcoords = had_texcoords || !uv.empty();
  m.face_line = std::move(line);
  m.path = name;
  return m;
}

}  // namespace intrinsic::io
