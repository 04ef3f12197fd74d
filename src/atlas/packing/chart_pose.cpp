// Packing, step 1 (chart_pose.h): the smallest-box pose and the extra
// angles tried for charts that fill their box poorly.
#include "atlas/packing/chart_pose.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace intrinsic::detail::packing {

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

double smallest_box_angle(const MatrixX2d& UV, double& box_area) {
  const std::vector<Eigen::Vector2d> hull = convex_hull(UV);
  box_area = INFINITY;
  double best_angle = 0;
  for (size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d e = hull[(i + 1) % hull.size()] - hull[i];
    if (e.norm() == 0) continue;
    const double a = -std::atan2(e.y(), e.x());
    const Eigen::Rotation2Dd R(a);
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(INFINITY), hi = -lo;
    for (const Eigen::Vector2d& q : hull) lo = lo.cwiseMin(R * q), hi = hi.cwiseMax(R * q);
    const double area = (hi - lo).prod();
    if (area < box_area * (1 - 1e-12)) box_area = area, best_angle = a;
  }
  return best_angle;
}

MatrixX2d turned_to(const MatrixX2d& UV, double angle) {
  MatrixX2d T = UV;
  if (angle != 0) T = UV * Eigen::Rotation2Dd(angle).toRotationMatrix().transpose();
  if (!T.allFinite()) T.setZero();
  if (T.rows() > 0) T.rowwise() -= T.colwise().minCoeff();
  return T;
}

void orient_chart(FlatChart& chart) {
  double box_area = 0;
  chart.UV = turned_to(chart.UV, smallest_box_angle(chart.UV, box_area));
}

std::vector<double> pose_angles(const FlatChart& chart, double atlas_area, const PoseOptions& options) {
  std::vector<double> angles{0.0};
  if (options.extra_angles <= 0 || chart.UV.rows() < 3) return angles;
  if (chart.summary.area_3d < options.min_share * atlas_area) return angles;
  // The chart's own area over its box: a chart that fills its box (or its
  // hull does) has little room for another in its corners.
  const double box = (chart.UV.colwise().maxCoeff() - chart.UV.colwise().minCoeff()).prod();
  const double fill = box > 0 ? chart.summary.area_3d / box : 1;
  if (fill > options.max_fill) return angles;
  for (int k = 1; k <= options.extra_angles; ++k) angles.push_back(M_PI / 2 * k / (options.extra_angles + 1));
  return angles;
}

std::vector<std::vector<double>> all_pose_angles(const std::vector<FlatChart>& charts, double atlas_area,
                                                 const PoseOptions& options) {
  std::vector<std::vector<double>> angles(charts.size());
  std::vector<int> more;
  for (size_t c = 0; c < charts.size(); ++c) {
    angles[c] = pose_angles(charts[c], atlas_area, options);
    if (angles[c].size() > 1) more.push_back(static_cast<int>(c));
  }
  // The largest first (then the lower index: a total order, the same every run).
  std::stable_sort(more.begin(), more.end(),
                   [&](int a, int b) { return charts[a].summary.area_3d > charts[b].summary.area_3d; });
  for (size_t k = std::max(0, options.max_charts); k < more.size(); ++k) angles[more[k]].resize(1);
  return angles;
}

}  // namespace intrinsic::detail::packing
