// Re-indexing a mesh by texture coordinate.
#include "intrinsic/uv_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>
#include <vector>

#include "intrinsic/error.h"

namespace intrinsic {

UvMesh split_by_texcoord(const MeshData& data) {
  if (!data.has_uv()) throw_input(data.path + ": the mesh has no texture coordinates (OBJ vt or PLY u, v)");
  UvMesh m;
  m.V.setZero(data.TC.rows(), 3);
  m.F = data.FTC;
  std::vector<int> vertex_of(data.TC.rows(), -1);  // the vertex whose position row t holds
  // A coordinate used at several positions (an atlas collapsing a zero-area
  // face onto a neighbour's UV, or another tool's sharing) gets one row per
  // position, appended after the file's rows.
  std::map<std::pair<int, int>, int> extra;
  std::vector<int> extra_tc, extra_v;
  for (Eigen::Index f = 0; f < data.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int t = data.FTC(f, c), v = data.F(f, c);
      if (t < 0 || t >= data.TC.rows())
        throw_input(data.path + ": texture index out of range in face " + std::to_string(f));
      if (vertex_of[t] < 0) vertex_of[t] = v;
      if (vertex_of[t] == v || data.V.row(vertex_of[t]) == data.V.row(v)) continue;
      const auto [it, fresh] = extra.emplace(std::make_pair(t, v), static_cast<int>(data.TC.rows() + extra_tc.size()));
      if (fresh) extra_tc.push_back(t), extra_v.push_back(v);
      m.F(f, c) = it->second;
    }
  const Eigen::Index n = data.TC.rows(), k = static_cast<Eigen::Index>(extra_tc.size());
  m.V.resize(n + k, 3);
  m.UV.resize(n + k, 2);
  m.UV.topRows(n) = data.TC;
  m.V.topRows(n).setZero();  // rows no face uses stay at the origin
  for (Eigen::Index t = 0; t < n; ++t)
    if (vertex_of[t] >= 0) m.V.row(t) = data.V.row(vertex_of[t]);
  for (Eigen::Index i = 0; i < k; ++i) {
    m.V.row(n + i) = data.V.row(extra_v[i]);
    m.UV.row(n + i) = data.TC.row(extra_tc[i]);
  }
  m.input_vertices = data.V.rows();
  return m;
}

MatrixX2d unmirrored_uv(const UvMesh& m, const UvAtlasMetrics& atlas) {
  MatrixX2d UV = m.UV;
  std::vector<char> done(UV.rows(), 0);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int t = m.F(f, c);
      if (done[t]) continue;
      done[t] = 1;
      if (atlas.charts[atlas.face_chart[f]].mirrored) UV(t, 0) = -UV(t, 0);
    }
  return UV;
}

double seam_length(const UvMesh& m) {
  // (position a, position b, UV at a, UV at b) with a < b, sorted: the entries
  // of one edge are adjacent, and each distinct UV pair after its first is a seam.
  using Entry = std::array<double, 10>;
  std::vector<Entry> edges;
  edges.reserve(3 * static_cast<size_t>(m.F.rows()));
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      int a = m.F(f, c), b = m.F(f, (c + 1) % 3);
      if (!m.V.row(a).allFinite() || !m.V.row(b).allFinite() || !m.UV.row(a).allFinite() ||
          !m.UV.row(b).allFinite())
        continue;
      const auto pa = std::make_tuple(m.V(a, 0), m.V(a, 1), m.V(a, 2));
      const auto pb = std::make_tuple(m.V(b, 0), m.V(b, 1), m.V(b, 2));
      if (pa == pb) continue;
      if (pb < pa) std::swap(a, b);
      edges.push_back({m.V(a, 0), m.V(a, 1), m.V(a, 2), m.V(b, 0), m.V(b, 1), m.V(b, 2), m.UV(a, 0), m.UV(a, 1),
                       m.UV(b, 0), m.UV(b, 1)});
    }
  std::sort(edges.begin(), edges.end());
  double length = 0;
  for (size_t i = 1; i < edges.size(); ++i) {
    const Entry &e = edges[i], &p = edges[i - 1];
    if (std::equal(e.begin(), e.begin() + 6, p.begin()) && e != p)
      length += std::sqrt((e[0] - e[3]) * (e[0] - e[3]) + (e[1] - e[4]) * (e[1] - e[4]) + (e[2] - e[5]) * (e[2] - e[5]));
  }
  return length;
}

int small_charts(const UvMesh& m, const UvAtlasMetrics& atlas, int resolution, double min_texels) {
  double side = 1;
  if (!atlas.utilization_in_unit_square) {
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(INFINITY), hi = -lo;
    for (Eigen::Index f = 0; f < m.F.rows(); ++f)
      for (int c = 0; c < 3; ++c) {
        const Eigen::Vector2d u = m.UV.row(m.F(f, c));
        if (u.allFinite()) lo = lo.cwiseMin(u), hi = hi.cwiseMax(u);
      }
    side = (hi - lo).maxCoeff();
  }
  const double texels_per_area = side > 0 ? static_cast<double>(resolution) * resolution / (side * side) : 0;
  int n = 0;
  for (const UvChart& c : atlas.charts) n += !c.degenerate && c.uv_area * texels_per_area < min_texels;
  return n;
}

}  // namespace intrinsic
