// View selection and framing for the 3D renders.
#include "render/camera.h"

#include <algorithm>
#include <cmath>

namespace intrinsic::render {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kMargin = 0.92;  // fraction of the smaller image side the sphere spans
}  // namespace

ViewDirection view_from_angles(double azimuth_deg, double elevation_deg) {
  const double az = azimuth_deg * kPi / 180, el = elevation_deg * kPi / 180;
  const Eigen::Vector3d eye(std::cos(el) * std::sin(az), -std::cos(el) * std::cos(az), std::sin(el));
  return {-eye, Eigen::Vector3d(std::cos(az), std::sin(az), 0)};
}

ViewDirection auto_view(const MatrixX3d& V, const MatrixX3i& F) {
  // Only the direction matters, so work in units of the largest coordinate:
  // cross products of huge (or tiny) coordinates then neither overflow nor
  // underflow.
  double s = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d)
        if (std::isfinite(V(F(f, k), d))) s = std::max(s, std::abs(V(F(f, k), d)));
  if (!(s > 0)) s = 1;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double total = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)) / s, b = V.row(F(f, 1)) / s, c = V.row(F(f, 2)) / s;
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (!n.allFinite()) continue;
    sum += n;
    total += n.norm();
  }
  // Cancelling normals (a closed or strongly curved surface) say nothing
  // about a good side, so fall back to a conventional three-quarter view.
  if (!(total > 0) || !(sum.norm() > 1e-3 * total) || !sum.allFinite())
    return view_from_angles(-30, 25);
  const Eigen::Vector3d f = -sum.normalized();
  const Eigen::Vector3d up = std::abs(f.z()) > 0.9 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ();
  return {f, f.cross(up).normalized()};
}

Camera make_camera(const MatrixX3d& V, const MatrixX3i& F, const ViewDirection& view, int width, int height) {
  Camera cam;
  cam.forward = view.forward.normalized();
  cam.right = (view.right - view.right.dot(cam.forward) * cam.forward).normalized();
  cam.up = cam.right.cross(cam.forward);

  // Bounding box of the vertices the faces use; its half-diagonal is a
  // bounding sphere, computed with hypot so extreme coordinates stay finite.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = Eigen::Vector3d::Constant(-INFINITY);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = V.row(F(f, k));
      if (!p.allFinite()) continue;
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  Eigen::Vector3d half = (hi / 2 - lo / 2);
  double radius = std::hypot(std::hypot(half.x(), half.y()), half.z());
  if (!(radius > 0) || !std::isfinite(radius)) {
    // A single point (or an overflowing extent): any positive scale shows it.
    radius = std::max({std::abs(lo.x()), std::abs(lo.y()), std::abs(lo.z()), 1.0});
    if (!std::isfinite(radius)) radius = 1;
  }
  cam.radius = radius;
  cam.centre = lo / radius + half / radius;
  cam.scale = 0.5 * kMargin * std::min(width, height);
  cam.cx = 0.5 * width;
  cam.cy = 0.5 * height;
  // Tighter: frame the extent of the projected vertices (a flat patch seen
  // from above, or a wide one from the side, would otherwise fill a small
  // part of the bounding sphere's disc), centred in the image.
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = V.row(F(f, k));
      if (!p.allFinite()) continue;
      const Eigen::Vector3d q = p / radius - cam.centre;
      const double x = q.dot(cam.right), y = q.dot(cam.up);
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  const double sx = x1 > x0 ? kMargin * width / (x1 - x0) : INFINITY;
  const double sy = y1 > y0 ? kMargin * height / (y1 - y0) : INFINITY;
  const double tight = std::min(sx, sy);
  if (std::isfinite(tight) && tight > 0) {
    cam.scale = tight;
    cam.cx = 0.5 * width - tight * (x0 / 2 + x1 / 2);
    cam.cy = 0.5 * height + tight * (y0 / 2 + y1 / 2);
  }
  return cam;
}

}  // namespace intrinsic::render
