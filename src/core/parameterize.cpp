// The fixed-boundary member of the intrinsic family (paper section 4.1):
// choose fixed vertices, close or free the holes, eliminate, factor once,
// solve u and v together, check the residual, scale.
#include "intrinsic/parameterize.h"

#include <chrono>
#include <cmath>

#include "core/natural_map.h"
#include "intrinsic/assemble.h"
#include "intrinsic/error.h"

namespace intrinsic {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

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

ParamResult parameterize(const Mesh& mesh, const ParamOptions& o) {
  const Topology& t = mesh.topology;
  if (t.num_components != 1)
    throw_usage("parameterize takes one connected component; this mesh has " + std::to_string(t.num_components));
  if (t.component_loops[0].empty()) throw_input("the surface is closed (no boundary)");
  if (o.weights.method == Method::Mixed && o.weights.lambda == 0 && o.weights.mu == 0)
    throw_usage("mixed method needs lambda and mu not both zero");
  if (!std::isfinite(o.weights.lambda) || !std::isfinite(o.weights.mu))
    throw_usage("lambda and mu must be finite");
  if (o.boundary == BoundaryShape::Natural) return natural_map(mesh, o);
  if (!o.pins.empty()) throw_usage("pins apply to the natural boundary only (use given boundary positions instead)");

  ParamResult result;
  const auto t_assemble = std::chrono::steady_clock::now();
  const int n = static_cast<int>(mesh.V.rows());
  const std::vector<FixedVertex> fixed = boundary_positions(mesh, o);

  // Working copy of the surface, extended by one vertex per filled hole.
  MatrixX3d V = mesh.V;
  MatrixX3i F = mesh.F;
  std::vector<char> is_fixed(n, 0), is_used(t.is_used.begin(), t.is_used.end());
  for (const FixedVertex& fv : fixed) is_fixed[fv.vertex] = 1;
  const bool has_holes = t.component_loops[0].size() > 1;
  result.holes = has_holes ? hole_rule_name(o.holes) : "none";
  // The area term of E_D - A on the hole loops (the outer loop is fixed, so
  // its terms only reach fixed unknowns and drop out).
  const double area_weight = conformal_part(o.weights);
  const bool natural_holes = has_holes && o.holes == HoleRule::Natural && area_weight != 0;
  if (has_holes && o.holes == HoleRule::Natural && area_weight == 0) result.holes = "free (method has no conformal term)";
  if (o.holes == HoleRule::Fill) {
    std::vector<Eigen::Vector3i> fan;
    std::vector<Eigen::Vector3d> centres;
    for (size_t k = 1; k < t.component_loops[0].size(); ++k) {
      const std::vector<int>& loop = t.boundary_loops[t.component_loops[0][k]];
      bool all_fixed = true;
      for (int v : loop) all_fixed = all_fixed && is_fixed[v];
      if (all_fixed) continue;  // the user placed this hole
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (int v : loop) c += mesh.V.row(v).transpose();
      c /= static_cast<double>(loop.size());
      const int centre = n + static_cast<int>(centres.size());
      bool degenerate = false;
      std::vector<Eigen::Vector3i> faces;
      for (size_t i = 0; i < loop.size(); ++i) {
        const int a = loop[i], b = loop[(i + 1) % loop.size()];
        const Eigen::Vector3d xa = mesh.V.row(a), xb = mesh.V.row(b);
        const double twice = (xa - xb).cross(c - xb).norm();
        degenerate = degenerate || !(twice > 1e-12 * std::max((xa - xb).squaredNorm(), (c - xb).squaredNorm()));
        faces.emplace_back(b, a, centre);  // opposite to the boundary half-edge a->b
      }
      if (degenerate) continue;  // this hole stays free
      centres.push_back(c);
      fan.insert(fan.end(), faces.begin(), faces.end());
    }
    if (!centres.empty()) {
      V.conservativeResize(n + static_cast<int>(centres.size()), 3);
      for (size_t k = 0; k < centres.size(); ++k) V.row(n + static_cast<int>(k)) = centres[k].transpose();
      const int m = static_cast<int>(F.rows());
      F.conservativeResize(m + static_cast<int>(fan.size()), 3);
      for (size_t k = 0; k < fan.size(); ++k) F.row(m + static_cast<int>(k)) = fan[k].transpose();
      is_fixed.resize(V.rows(), 0);
      is_used.resize(V.rows(), 1);
      result.filled_holes = static_cast<int>(centres.size());
    }
  }

  const SparseMatrix K = assemble_weight_matrix(V, F, o.weights);
  if (natural_holes) {
    std::vector<std::vector<int>> holes;
    for (size_t k = 1; k < t.component_loops[0].size(); ++k) holes.push_back(t.boundary_loops[t.component_loops[0][k]]);
    const SparseMatrix Q = block_diagonal2(K) - area_weight * area_hessian(n, holes);
    result.timings.assemble_ms = ms_since(t_assemble);
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
  const Partition p = partition(static_cast<int>(V.rows()), is_fixed, is_used);
  SparseMatrix A, K_IB;
  split_matrix(K, p, A, K_IB);
  Eigen::MatrixXd UB(p.fixed_vertices.size(), 2);
  for (const FixedVertex& fv : fixed) UB.row(p.fixed_index[fv.vertex]) = fv.uv.transpose();
  const Eigen::MatrixXd rhs = -(K_IB * UB);
  result.free_vertices = static_cast<int>(p.free_vertices.size());
  result.fixed_vertices = static_cast<int>(p.fixed_vertices.size());
  result.timings.assemble_ms = ms_since(t_assemble);

  Eigen::MatrixXd X(0, 2);
  if (result.free_vertices > 0) {
    const auto t_factor = std::chrono::steady_clock::now();
    LinearSolver solver(o.solver, is_symmetric(o.weights));
    solver.factor(A);
    result.timings.factor_ms = ms_since(t_factor);
    const auto t_solve = std::chrono::steady_clock::now();
    X = solver.solve(rhs);
    result.timings.solve_ms = ms_since(t_solve);
    result.solver = solver.name();
    result.factorizations = solver.factorizations();
    result.iterations = solver.iterations();
    if (!X.allFinite())
      throw_numerical("the solution has non-finite values: the system is singular or nearly so "
                      "(look for coincident boundary positions or nearly degenerate faces)");
    for (int c = 0; c < 2; ++c) {
      const double b = rhs.col(c).norm();
      const double r = (A * X.col(c) - rhs.col(c)).norm();
      result.residual = std::max(result.residual, b > 0 ? r / b : r);
    }
    if (!(result.residual <= o.max_residual))
      throw_numerical("the relative residual " + std::to_string(result.residual) + " of solver " + result.solver +
                      " exceeds " + std::to_string(o.max_residual) +
                      " (an iterative solver may not have converged; try --solver auto)");
  } else {
    result.solver = "none (every vertex is fixed)";
  }

  result.UV = MatrixX2d::Zero(n, 2);
  for (int v = 0; v < n; ++v) {
    if (p.free_index[v] >= 0) result.UV.row(v) = X.row(p.free_index[v]);
    else if (p.fixed_index[v] >= 0) result.UV.row(v) = UB.row(p.fixed_index[v]);
  }
  finish_scale(result, mesh, o);
  return result;
}

}  // namespace intrinsic
