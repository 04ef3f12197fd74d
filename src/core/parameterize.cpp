// The one-call fixed-boundary map (paper section 4.1), a thin wrapper over
// Parameterizer, plus the boundary positions and the area and scaling
// helpers it shares.
#include "intrinsic/parameterize.h"

#include <cmath>

#include "core/natural_map.h"
#include "intrinsic/assemble.h"
#include <chrono>
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
    case BoundaryShape::Natural: return {};  // handled by natural_map
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

namespace {

// The weight of the conformal energy in the method's interior rows: the
// factor of the area term under HoleRule::Natural (0: no such term).
double conformal_part(const WeightOptions& w) {
  switch (w.method) {
    case Method::Conformal: return 1.0;
    case Method::Mixed: return w.lambda;
    default: return 0.0;
  }
}

void finish_scale(ParamResult& result, const Mesh& mesh, const ParamOptions& o) {
  if (o.boundary == BoundaryShape::Given) {
    result.scale = "given";
  } else if (o.scale == ScaleMode::Unit) {
    // The circle and square live in [-1, 1]^2: map that box onto [0, 1]^2
    // exactly (a bounding-box fit would depend on where the vertices fall).
    for (int v = 0; v < mesh.V.rows(); ++v)
      if (mesh.topology.is_used[v]) result.UV.row(v) = 0.5 * result.UV.row(v) + Eigen::RowVector2d(0.5, 0.5);
    result.scale = "unit";
  } else {
    scale_to_surface_area(result.UV, mesh);
    result.scale = "surface";
  }
}

}  // namespace

std::string hole_rule_name(HoleRule r) {
  switch (r) {
    case HoleRule::Fill: return "fill";
    case HoleRule::Free: return "free";
    case HoleRule::Natural: return "natural";
  }
  return "?";
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

namespace {

// Fixed outer loop, natural condition (E_D - A terms scaled by the conformal
// part of the weights) on the hole loops: the 2n x 2n pinned system.
ParamResult natural_holes_map(const Mesh& mesh, const ParamOptions& o, const std::vector<FixedVertex>& fixed,
                              double area_weight) {
  const auto t_assemble = std::chrono::steady_clock::now();
  const Topology& t = mesh.topology;
  const int n = static_cast<int>(mesh.V.rows());
  ParamResult result;
  result.holes = "natural";
  std::vector<char> is_used(t.is_used.begin(), t.is_used.end());
  const SparseMatrix K = assemble_weight_matrix(mesh.V, mesh.F, o.weights);
  std::vector<std::vector<int>> holes;
  for (size_t k = 1; k < t.component_loops[0].size(); ++k) holes.push_back(t.boundary_loops[t.component_loops[0][k]]);
  const SparseMatrix Q = block_diagonal2(K) - area_weight * area_hessian(n, holes);
  result.timings.assemble_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t_assemble).count();
  const PinnedSolution s = solve_pinned(Q, fixed, is_used, o.solver, is_symmetric(o.weights), o.max_residual);
  result.UV = s.UV;
  result.solver = s.solver;
  result.residual = s.residual;
  result.free_vertices = s.free_vertices;
  result.fixed_vertices = s.fixed_vertices;
  result.factorizations = s.factorizations;
  result.iterations = s.iterations;
  result.timings.factor_ms = s.factor_ms;
  result.timings.solve_ms = s.solve_ms;
  finish_scale(result, mesh, o);
  return result;
}

}  // namespace

ParamResult parameterize(const Mesh& mesh, const ParamOptions& o) {
  const Topology& t = mesh.topology;
  if (t.num_components != 1)
    throw_usage("parameterize takes one connected component; this mesh has " + std::to_string(t.num_components));
  if (t.component_loops[0].empty()) throw_input("the surface is closed (no boundary)");
  if (o.boundary == BoundaryShape::Natural) return natural_map(mesh, o);
  if (!o.pins.empty()) throw_usage("pins apply to the natural boundary only (use given boundary positions instead)");
  const bool has_holes = t.component_loops[0].size() > 1;
  const double area_weight = conformal_part(o.weights);
  if (has_holes && o.holes == HoleRule::Natural && area_weight != 0)
    return natural_holes_map(mesh, o, boundary_positions(mesh, o), area_weight);
  // Fill and free holes (and natural holes without a conformal term, which
  // are free) go through the Parameterizer.
  ParamResult r = Parameterizer(mesh, o).solve();
  r.holes = !has_holes ? "none"
            : o.holes == HoleRule::Natural ? "free (method has no conformal term)"
                                           : hole_rule_name(o.holes);
  return r;
}

}  // namespace intrinsic
