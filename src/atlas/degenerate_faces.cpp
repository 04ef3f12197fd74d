// Texture coordinates for the faces that take part in no solve (zero area or
// a repeated vertex), kept in the output so that every input face has UVs (see
// docs/maths.md §9.6). Each gets zero UV area, so it can neither flip nor
// overlap. Where possible it is laid along an edge of a face already placed
// (a chart's boundary edge, or a degenerate face placed before it): it then
// shares that UV edge, so it belongs to that chart's UV-connected component
// (what `metrics` calls a chart) instead of forming one of its own. Corners
// are compared as `metrics` compares them (src/metrics/uv_charts.cpp): same
// UV and same 3D position. A corner given another vertex's UV gets a copy of
// that row, so every row of UV still holds the corners of one vertex.
#include <array>
#include <map>
#include <set>

#include "atlas/atlas_internal.h"

namespace intrinsic::detail {
namespace {

using Position = std::array<double, 3>;

struct Surface {  // the output's vertices and faces
  const MatrixX3d& V;
  const MatrixX3i& F;
};

struct UvEdges {
  const Surface& mesh;
  int rows = 0;                 // rows of UV before the copies
  std::vector<Eigen::Vector2d> copies;
  std::vector<int> source;      // per copy: the row it copies
  std::map<std::pair<int, Position>, int> corner_id;
  std::map<std::pair<int, int>, int> count;              // UV edge (corner ids) -> faces using it
  std::map<std::pair<int, int>, std::vector<int>> on;  // vertex pair -> half-edges (3f + c) of placed faces

  Position at(int v) const { return {mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2)}; }
  // A corner as `metrics` sees it: the UV (a copy is its source's) and the position.
  int corner(int uv, int v) {
    if (uv >= rows) uv = source[uv - rows];
    return corner_id.emplace(std::make_pair(uv, at(v)), corner_id.size()).first->second;
  }
  // A new row with row `uv`'s coordinates, for a corner at another vertex:
  // every row of UV keeps the corners of one vertex (and those welded to it).
  int copy_of(const MatrixX2d& UV, int uv) {
    if (uv >= rows) uv = source[uv - rows];
    copies.push_back(UV.row(uv));
    source.push_back(uv);
    return rows + static_cast<int>(copies.size()) - 1;
  }
  static std::pair<int, int> key(int a, int b) { return {std::min(a, b), std::max(a, b)}; }
  int& uses(int ca, int cb) { return count[key(ca, cb)]; }
  void add(const MatrixX3i& FUV, int f) {
    for (int c = 0; c < 3; ++c) {
      const int d = (c + 1) % 3, a = mesh.F(f, c), b = mesh.F(f, d);
      const int ca = corner(FUV(f, c), a), cb = corner(FUV(f, d), b);
      if (ca != cb) ++uses(ca, cb);
      on[key(a, b)].push_back(3 * f + c);
    }
  }
};

// The UV row of face f's corner at vertex v.
int row_at(const Surface& m, const MatrixX3i& FUV, int f, int v) {
  for (int c = 0; c < 3; ++c)
    if (m.F(f, c) == v) return FUV(f, c);
  return -1;
}

// Lays face f along a placed face's UV edge on its edge c (vertices a, b):
// rows (ta, tb) there and, at its third vertex x, whichever of them makes a
// corner distinct from both. Only if that UV edge has exactly one face so
// far and f's two other UV edges none (metrics pairs an edge of exactly two faces).
bool lay_along(UvEdges& e, const MatrixX2d& UV, MatrixX3i& FUV, int f) {
  const Surface& m = e.mesh;
  for (int c = 0; c < 3; ++c) {
    const int a = m.F(f, c), b = m.F(f, (c + 1) % 3), x = m.F(f, (c + 2) % 3);
    const auto it = e.on.find(UvEdges::key(a, b));
    if (it == e.on.end()) continue;
    for (int h : it->second) {
      const int ta = row_at(m, FUV, h / 3, a), tb = row_at(m, FUV, h / 3, b);
      const int ca = e.corner(ta, a), cb = e.corner(tb, b);
      if (ca == cb || e.uses(ca, cb) != 1) continue;
      int tx = ta, cx = e.corner(ta, x);
      if (cx == ca || cx == cb) tx = tb, cx = e.corner(tb, x);
      if (cx == ca || cx == cb || e.uses(cb, cx) != 0 || e.uses(cx, ca) != 0) continue;
      FUV(f, c) = ta, FUV(f, (c + 1) % 3) = tb, FUV(f, (c + 2) % 3) = e.copy_of(UV, tx);
      e.add(FUV, f);
      return true;
    }
  }
  return false;
}

}  // namespace

void place_degenerate_faces(const MatrixX3d& V, const MatrixX3i& F, const std::vector<int>& face_chart, MatrixX2d& UV,
                            MatrixX3i& FUV, int zero_row) {
  const Surface mesh{V, F};
  const int nf = static_cast<int>(mesh.F.rows());
  std::vector<int> left;
  std::set<Position> near;  // positions of their vertices: only UV edges there can meet them
  UvEdges e{mesh, static_cast<int>(UV.rows()), {}, {}, {}, {}, {}};
  for (int f = 0; f < nf; ++f)
    if (face_chart[f] < 0) {
      left.push_back(f);
      for (int c = 0; c < 3; ++c) near.insert(e.at(mesh.F(f, c)));
    }
  if (left.empty()) return;
  std::vector<int> vertex_uv(mesh.V.rows(), -1);
  for (int f = 0; f < nf; ++f) {
    if (face_chart[f] < 0) continue;
    bool meets = false;
    for (int c = 0; c < 3; ++c) {
      if (vertex_uv[mesh.F(f, c)] < 0) vertex_uv[mesh.F(f, c)] = FUV(f, c);
      meets = meets || near.count(e.at(mesh.F(f, c)));
    }
    if (meets) e.add(FUV, f);
  }
  // Rounds: a face laid along another degenerate face needs that one placed first.
  for (bool progress = true; progress && !left.empty();) {
    progress = false;
    std::vector<int> still;
    for (int f : left)
      if (lay_along(e, UV, FUV, f)) progress = true;
      else still.push_back(f);
    left = std::move(still);
  }
  // The rest (e.g. all three corners at one point): collapsed onto a UV of one
  // of their vertices, a component of zero-area faces of its own.
  for (int f : left) {
    int uv = zero_row;
    for (int j = 2; j >= 0; --j)
      if (vertex_uv[mesh.F(f, j)] >= 0) uv = vertex_uv[mesh.F(f, j)];
    for (int j = 0; j < 3; ++j) FUV(f, j) = uv != zero_row && vertex_uv[mesh.F(f, j)] == uv ? uv : e.copy_of(UV, uv);
  }
  const int rows = e.rows;
  UV.conservativeResize(rows + static_cast<int>(e.copies.size()), 2);
  for (size_t k = 0; k < e.copies.size(); ++k) UV.row(rows + static_cast<int>(k)) = e.copies[k];
}

}  // namespace intrinsic::detail
