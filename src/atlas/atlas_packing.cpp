// Packing (issue 13, "packing"): every chart already has UV area = 3D area
// (one texel density for all); each is turned to its smallest bounding box
// (whose side lies on a convex hull edge), then a quarter turn when taller
// than wide; the boxes are packed bottom-left on a skyline (tallest first;
// the strip width that gives the smallest square is chosen among a few) with
// a gap of `padding` texels, and the layout is fitted into [0,1]^2 by one
// similarity. (core/shelf_packing's shelves left about a fifth more empty
// space on the assets.)
#include <algorithm>
#include <cmath>

#include "atlas/atlas_internal.h"
#include <numeric>

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

// The angle that turns UV to its smallest axis-aligned box; `area` gets that box's area.
double smallest_box_angle(const MatrixX2d& UV, double& best_area) {
  const std::vector<Eigen::Vector2d> hull = convex_hull(UV);
  best_area = INFINITY;
  double best_angle = 0;
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
  return best_angle;
}

// Rotates the chart to its smallest box (then wider than tall) and moves its corner to the origin.
void orient_chart(FlatChart& chart) {
  double best_area = 0;
  const double best_angle = smallest_box_angle(chart.UV, best_area);
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

// Bottom-left skyline packing of boxes into a strip of width `width`:
// each box, in the given order, goes where its top is lowest (then leftmost).
// Returns the lower-left corners; `height` gets the strip height used.
std::vector<Eigen::Vector2d> skyline(const std::vector<Eigen::Vector2d>& sizes, const std::vector<int>& order,
                                     double width, double& height) {
  struct Segment {
    double x, y, w;
  };
  std::vector<Segment> sky{{0, 0, width}};
  std::vector<Eigen::Vector2d> corner(sizes.size());
  height = 0;
  for (int b : order) {
    const double w = sizes[b].x(), h = sizes[b].y();
    size_t best = sky.size();
    double best_y = INFINITY, base = 0;
    for (size_t i = 0; i < sky.size(); ++i) {
      if (sky[i].x + w > width * (1 + 1e-12)) break;
      double y = 0;
      for (size_t j = i; j < sky.size() && sky[j].x < sky[i].x + w; ++j) y = std::max(y, sky[j].y);
      if (y + h < best_y) best_y = y + h, best = i, base = y;
    }
    // The box sits exactly on the skyline (base), not at best_y - h, which
    // can round below it and overlap the box underneath by an ulp (fuzz_atlas
    // found this with padding 0).
    const double x = sky[best].x, y = base;
    corner[b] = Eigen::Vector2d(x, y);
    height = std::max(height, best_y);
    // Replace the covered part of the skyline by the box's top.
    std::vector<Segment> next;
    for (const Segment& s : sky) {
      if (s.x + s.w <= x || s.x >= x + w) {
        next.push_back(s);
        continue;
      }
      if (s.x < x) next.push_back({s.x, s.y, x - s.x});
      if (next.empty() || next.back().x + next.back().w <= x) next.push_back({x, best_y, w});
      if (s.x + s.w > x + w) next.push_back({x + w, s.y, s.x + s.w - x - w});
    }
    sky = std::move(next);
  }
  return corner;
}

// The strip width whose skyline packing fits the smallest square; `side` gets that square's side.
std::vector<Eigen::Vector2d> pack_square(const std::vector<Eigen::Vector2d>& sizes, double& side) {
  double area = 0, widest = 0;
  for (const Eigen::Vector2d& s : sizes) area += s.prod(), widest = std::max(widest, s.x());
  std::vector<int> order(sizes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return sizes[a].y() > sizes[b].y(); });
  std::vector<Eigen::Vector2d> best;
  side = INFINITY;
  for (int k = 0; k < 12; ++k) {
    const double width = std::max(widest, std::sqrt(area) * (1.0 + 0.04 * k));
    double height = 0;
    std::vector<Eigen::Vector2d> corner = skyline(sizes, order, width, height);
    double used = 0;
    for (size_t i = 0; i < sizes.size(); ++i) used = std::max(used, corner[i].x() + sizes[i].x());
    if (std::max(used, height) < side) side = std::max(used, height), best = std::move(corner);
  }
  return best;
}

}  // namespace

double square_fill(const FlatChart& chart) {
  double box = 0;
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(smallest_box_angle(chart.UV, box)).toRotationMatrix();
  const MatrixX2d turned = chart.UV * R.transpose();
  const double side = (turned.colwise().maxCoeff() - turned.colwise().minCoeff()).maxCoeff();
  return side > 0 ? chart.summary.area_3d / (side * side) : 1;
}

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
    std::vector<Eigen::Vector2d> padded = sizes;  // each box with the gap on its right and top
    for (Eigen::Vector2d& p : padded) p.array() += gap;
    corner = pack_square(padded, side);
    for (Eigen::Vector2d& c : corner) c.array() += gap / 2;
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
