// The one-call fixed-boundary map (paper section 4.1), a thin wrapper over
// Parameterizer, and the area and scaling helpers shared with it.
#include "intrinsic/parameterize.h"

#include <cmath>

#include "intrinsic/parameterizer.h"

namespace intrinsic {

double parameter_area(const MatrixX3i& F, const MatrixX2d& UV) {
  double area = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector2d a = UV.row(F(f, 0)), b = UV.row(F(f, 1)), c = UV.row(F(f, 2));
    area += 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
  }
  return area;
}

double surface_area(const MatrixX3d& V, const MatrixX3i& F) {
  double area = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

void fit_unit_square(MatrixX2d& UV, const std::vector<char>& used) {
  Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (int v = 0; v < UV.rows(); ++v)
    if (used[v]) {
      lo = lo.cwiseMin(UV.row(v).transpose());
      hi = hi.cwiseMax(UV.row(v).transpose());
    }
  const double extent = (hi - lo).maxCoeff();
  if (!(extent > 0)) return;
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  for (int v = 0; v < UV.rows(); ++v)
    if (used[v]) UV.row(v) = ((UV.row(v).transpose() - centre) / extent + Eigen::Vector2d(0.5, 0.5)).transpose();
}

void scale_to_surface_area(MatrixX2d& UV, const Mesh& mesh) {
  const double a_param = std::abs(parameter_area(mesh.F, UV));
  const double a_surface = surface_area(mesh.V, mesh.F);
  if (!(a_param > 0)) return;
  const double s = std::sqrt(a_surface / a_param);
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  int count = 0;
  for (int v = 0; v < UV.rows(); ++v)
    if (mesh.topology.is_used[v]) { centroid += UV.row(v).transpose(); ++count; }
  centroid /= std::max(count, 1);
  for (int v = 0; v < UV.rows(); ++v)
    if (mesh.topology.is_used[v]) UV.row(v) = (centroid + s * (UV.row(v).transpose() - centroid)).transpose();
}

ParamResult parameterize(const Mesh& mesh, const ParamOptions& o) { return Parameterizer(mesh, o).solve(); }

}  // namespace intrinsic
