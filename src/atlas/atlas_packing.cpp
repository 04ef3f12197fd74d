// Packing (issue 13, "packing"): every chart already has UV area = 3D area
// (one texel density for all); each is turned to its smallest bounding box
// (whose side lies on a convex hull edge), then a quarter turn when taller
// than wide; the boxes are shelf-packed (core/shelf_packing) with a gap of
// `padding` texels, and the layout is fitted into [0,1]^2 by one similarity.
#include <algorithm>
#include <cmath>

#include "atlas/atlas_internal.h"
#include "core/shelf_packing.h"

namespace intrinsic::detail {
namespace {

// Andrew's monotone chain; counter-clockwise, no repeated point.
std::vector<Eigen::Vector2d> convex_hull(const MatrixX2d& UV) {
  std::vector<Eigen::Vector2d> p(UV.rows());
  for (int i = 0; i < UV.rows(); ++i) p[i] = UV.row(i).transpose();
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (p.size() < 3) return p;
  std::vector<Eigen::Vector2d> h(2 * p.size());
  size_t k = 0;
  auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

// Rotates the chart to its smallest box (then wider than tall) and moves its corner to the origin.
void orient_chart(FlatChart& chart) {
  const std::vector<Eigen::Vector2d> hull = convex_hull(chart.UV);
  double best_area = INFINITY, best_angle = 0;
  for (size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d e = hull[(i + 1) % hull.size()] - hull[i];
    if (e.norm() == 0) continue;
    const double a = -std::atan2(e.y(), e.x());
    const Eigen::Rotation2Dd R(a);
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(INFINITY), hi = -lo;
    for (const Eigen::Vector2d& q : hull) lo = lo.cwiseMin(R * q), hi = hi.cwiseMax(R * q);
    const double area = (hi - lo).prod();
    if (area < best_area * (1 - 1e-12)) best_area = area, best_angle = a;
  }
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(best_angle).toRotationMatrix();
  chart.UV = chart.UV * R.transpose();
  Eigen::Vector2d size = chart.UV.colwise().maxCoeff() - chart.UV.colwise().minCoeff();
  chart.summary.rotated = size.y() > size.x();
  if (chart.summary.rotated) {
    chart.UV.col(0).swap(chart.UV.col(1));
    chart.UV.col(0) *= -1;  // a quarter turn (orientation kept)
  }
  chart.UV.rowwise() -= chart.UV.colwise().minCoeff();
}

}  // namespace

double pack_charts(std::vector<FlatChart>& charts, const AtlasOptions& options, int& overlapping) {
  overlapping = 0;
  if (charts.empty()) return 0;
  std::vector<Eigen::Vector2d> sizes;
  double uv_area = 0;
  for (FlatChart& c : charts) {
    orient_chart(c);
    sizes.push_back(c.UV.colwise().maxCoeff().transpose());
    uv_area += c.summary.area_3d;
  }
  // The gap is `padding` texels of the final square, whose size depends on the gap: a few rounds.
  double gap = 0, side = 0;
  std::vector<Eigen::Vector2d> corner;
  for (int round = 0; round < 4; ++round) {
    corner = pack_shelves(sizes, Eigen::Vector2d::Constant(gap / 2), gap);
    Eigen::Vector2d hi = Eigen::Vector2d::Zero();
    for (size_t i = 0; i < charts.size(); ++i) hi = hi.cwiseMax(corner[i] + sizes[i]);
    side = hi.maxCoeff() + gap / 2;
    gap = options.padding * side / options.resolution;
    if (options.padding == 0) break;
  }
  for (size_t i = 0; i < charts.size(); ++i)
    for (size_t j = i + 1; j < charts.size(); ++j)
      if ((corner[i].array() < (corner[j] + sizes[j]).array()).all() &&
          (corner[j].array() < (corner[i] + sizes[i]).array()).all())
        ++overlapping;
  for (size_t i = 0; i < charts.size(); ++i) {
    charts[i].UV.rowwise() += corner[i].transpose();
    charts[i].UV /= side;
    charts[i].UV = charts[i].UV.cwiseMax(0.0).cwiseMin(1.0);  // rounding only
  }
  return uv_area / (side * side);
}

}  // namespace intrinsic::detail
