// The one-call fixed-boundary map (paper section 4.1), a thin wrapper over
// Parameterizer, plus the boundary positions and the area and scaling
// helpers it shares.
#include "intrinsic/parameterize.h"

#include <cmath>

#include "intrinsic/error.h"
#include "intrinsic/parameterizer.h"

namespace intrinsic {

std::vector<FixedVertex> boundary_positions(const Mesh& mesh, const ParamOptions& o) {
  const Topology& t = mesh.topology;
  const std::vector<int>& outer = t.boundary_loops.at(t.component_loops.at(0).at(0));
  switch (o.boundary) {
    case BoundaryShape::Circle: return circle_boundary(mesh.V, outer, o.spacing);
    case BoundaryShape::Square: return square_boundary(mesh.V, outer, o.spacing);
    case BoundaryShape::Given: break;
  }
  std::vector<char> given(mesh.V.rows(), 0);
  for (const FixedVertex& fv : o.given) {
    if (fv.vertex < 0 || fv.vertex >= mesh.V.rows())
      throw_input("boundary position for vertex " + std::to_string(fv.vertex) + ", which does not exist");
    if (!t.is_used[fv.vertex])
      throw_input("boundary position for vertex " + std::to_string(fv.vertex) + ", which no face uses");
    given[fv.vertex] = 1;
  }
  int missing = 0, first_missing = -1;
  for (int v : outer)
    if (!given[v]) {
      if (missing++ == 0) first_missing = v;
    }
  if (missing > 0)
    throw_input("the boundary positions miss " + std::to_string(missing) + " of the " +
                std::to_string(outer.size()) + " outer-loop vertices, e.g. vertex " + std::to_string(first_missing));
  return o.given;
}

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
  // About the origin, so that maps sharing a fixed boundary still share it.
  UV *= std::sqrt(a_surface / a_param);
}

ParamResult parameterize(const Mesh& mesh, const ParamOptions& o) { return Parameterizer(mesh, o).solve(); }

}  // namespace intrinsic
