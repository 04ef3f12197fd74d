// Charts, per-chart flips and utilization of any UV atlas (ours or another tool's;
// docs/maths.md §9 "Atlases"): what `intrinsic metrics` reports for our atlases
// and for other tools' outputs (triangle soups with vertices split at seams).
// A chart is a set of faces connected through UV edges: two faces sharing two
// corners. Corners are texture coordinates, identified when both their UV and
// their 3D position are equal, so soups that repeat coordinates per face still
// form charts. Orientation is judged per chart: a chart laid out mirrored as a
// whole is reported as such, apart from triangles folded against their own
// chart. Components made only of zero-area faces are flagged degenerate and
// counted apart from the charts.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

#include "intrinsic/metrics.h"
#include "mesh/degenerate_face.h"

namespace intrinsic {
namespace {

// Per texture coordinate, a representative of those with the same UV and
// position (non-finite ones stand alone: NaN has no order to sort by).
std::vector<int> canonical_corners(const MatrixX3d& PT, const MatrixX2d& UV) {
  const int n = static_cast<int>(UV.rows());
  std::vector<int> order, canon(n);
  std::iota(canon.begin(), canon.end(), 0);
  for (int t = 0; t < n; ++t)
    if (UV.row(t).allFinite() && PT.row(t).allFinite()) order.push_back(t);
  auto key = [&](int t) { return std::make_tuple(UV(t, 0), UV(t, 1), PT(t, 0), PT(t, 1), PT(t, 2), t); };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  for (size_t i = 1; i < order.size(); ++i) {
    const int t = order[i], p = order[i - 1];
    if (UV.row(t) == UV.row(p) && PT.row(t) == PT.row(p)) canon[t] = canon[p];
  }
  return canon;
}

// Half-edges (3f + c, from corner c to c + 1) of faces sharing a UV edge,
// paired when exactly two faces share it (more: the edge joins nothing, as a
// non-manifold edge in a chart would make orientation meaningless).
std::vector<std::pair<int, int>> uv_edge_pairs(const MatrixX3i& T) {
  const int m = static_cast<int>(T.rows());
  std::vector<std::tuple<int, int, int>> he;
  he.reserve(3 * static_cast<size_t>(m));
  for (int f = 0; f < m; ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = T(f, c), b = T(f, (c + 1) % 3);
      if (a != b) he.emplace_back(std::min(a, b), std::max(a, b), 3 * f + c);
    }
  std::sort(he.begin(), he.end());
  std::vector<std::pair<int, int>> pairs;
  for (size_t i = 0; i < he.size();) {
    size_t j = i;
    while (j < he.size() && std::get<0>(he[j]) == std::get<0>(he[i]) && std::get<1>(he[j]) == std::get<1>(he[i])) ++j;
    if (j - i == 2) pairs.emplace_back(std::get<2>(he[i]), std::get<2>(he[i + 1]));
    i = j;
  }
  return pairs;
}

// Charts by breadth-first search over paired edges; `listing` is each face's
// listing relative to the chart's first face (+1 same, -1 reversed), from the
// direction each shared edge is traversed in.
void label_charts(const MatrixX3i& T, std::vector<int>& chart, std::vector<int>& listing, int& count) {
  const int m = static_cast<int>(T.rows());
  std::vector<int> across(3 * static_cast<size_t>(m), -1);
  for (const auto& [h, k] : uv_edge_pairs(T)) across[h] = k, across[k] = h;
  chart.assign(m, -1);
  listing.assign(m, 1);
  count = 0;
  std::vector<int> queue;
  for (int s = 0; s < m; ++s) {
    if (chart[s] >= 0) continue;
    chart[s] = count;
    queue.assign(1, s);
    for (size_t q = 0; q < queue.size(); ++q) {
      const int f = queue[q];
      for (int c = 0; c < 3; ++c) {
        const int k = across[3 * f + c];
        if (k < 0 || chart[k / 3] >= 0) continue;
        const int g = k / 3;
        const bool same_direction = T(f, c) == T(g, k % 3);
        listing[g] = same_direction ? -listing[f] : listing[f];
        chart[g] = count;
        queue.push_back(g);
      }
    }
    ++count;
  }
}

// Utilization over [0,1]^2 or the bounding square, and over the bounding box.
void utilization(const MatrixX3i& FT, const MatrixX2d& UV, UvAtlasMetrics& r) {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (int f = 0; f < FT.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const double u = UV(FT(f, c), 0), v = UV(FT(f, c), 1);
      if (!std::isfinite(u) || !std::isfinite(v)) continue;
      x0 = std::min(x0, u), y0 = std::min(y0, v), x1 = std::max(x1, u), y1 = std::max(y1, v);
    }
  if (!(x1 >= x0 && y1 >= y0)) return;
  r.utilization_in_unit_square = x0 >= 0 && y0 >= 0 && x1 <= 1 && y1 <= 1;
  const double side = std::max(x1 - x0, y1 - y0);
  const double square = r.utilization_in_unit_square ? 1.0 : side * side;
  if (square > 0) r.utilization = r.uv_area / square;
  if ((x1 - x0) * (y1 - y0) > 0) r.utilization_bbox = r.uv_area / ((x1 - x0) * (y1 - y0));
}

}  // namespace

UvAtlasMetrics uv_atlas_metrics(const MatrixX3d& PT, const MatrixX3i& FT, const MatrixX2d& UV) {
  const int m = static_cast<int>(FT.rows());
  const std::vector<int> canon = canonical_corners(PT, UV);
  MatrixX3i T(m, 3);
  for (int f = 0; f < m; ++f)
    for (int c = 0; c < 3; ++c) T(f, c) = canon[FT(f, c)];
  UvAtlasMetrics r;
  std::vector<int> listing;
  int count = 0;
  label_charts(T, r.face_chart, listing, count);
  r.charts.resize(count);
  std::vector<int> sign(m, 0), majority(count, 0);
  std::vector<double> oriented_area(count, 0);
  std::vector<char> degenerate(m, 0);
  for (int f = 0; f < m; ++f) {
    UvChart& ch = r.charts[r.face_chart[f]];
    const Eigen::Vector2d a = UV.row(FT(f, 0)), b = UV.row(FT(f, 1)), c = UV.row(FT(f, 2));
    const double area2 = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    const Eigen::Vector3d x0 = PT.row(FT(f, 0)), x1 = PT.row(FT(f, 1)), x2 = PT.row(FT(f, 2));
    ++ch.faces;
    ch.area_3d += 0.5 * (x1 - x0).cross(x2 - x0).norm();
    if (std::isfinite(area2)) ch.uv_area += 0.5 * std::abs(area2), r.uv_area += 0.5 * std::abs(area2);
    degenerate[f] = detail::degenerate_face(PT, FT, f);
    r.degenerate_faces += degenerate[f];
    sign[f] = (a.allFinite() && b.allFinite() && c.allFinite()) ? orient2d_sign(a, b, c) * listing[f] : 0;
    if (!degenerate[f]) majority[r.face_chart[f]] += listing[f];  // zero-area faces do not vote
    if (std::isfinite(area2)) oriented_area[r.face_chart[f]] += 0.5 * std::abs(area2) * sign[f];
  }
  // The chart's own listing is its majority (of faces with area); its UV
  // orientation the sign of its oriented area in that listing.
  std::vector<int> chart_sign(count);
  for (int k = 0; k < count; ++k) r.charts[k].degenerate = true;
  for (int f = 0; f < m; ++f)
    if (!degenerate[f]) r.charts[r.face_chart[f]].degenerate = false;
  for (int k = 0; k < count; ++k) {
    r.degenerate_charts += r.charts[k].degenerate;
    const int listed = majority[k] >= 0 ? 1 : -1;
    chart_sign[k] = oriented_area[k] >= 0 ? 1 : -1;
    r.charts[k].mirrored = chart_sign[k] * listed < 0;
    r.mirrored_charts += r.charts[k].mirrored;
  }
  r.face_folded.assign(m, 0);
  for (int f = 0; f < m; ++f) {
    const int k = r.face_chart[f];
    if (r.charts[k].mirrored) ++r.mirrored_faces;
    if (degenerate[f]) continue;
    if (sign[f] == 0) ++r.charts[k].collapsed, ++r.collapsed_triangles, r.face_folded[f] = 1;
    else if (sign[f] != chart_sign[k]) ++r.charts[k].flipped, ++r.flipped_triangles, r.face_folded[f] = 1;
  }
  r.face_overlapping = overlapping_uv_triangles(FT, UV, &r.overlapping_pairs_within_charts,
                                                &r.overlapping_pairs_between_charts, &r.face_chart);
  for (char h : r.face_overlapping) r.overlapping_triangles += h;
  utilization(FT, UV, r);
  return r;
}

}  // namespace intrinsic
