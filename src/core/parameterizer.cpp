// The kept-factorization parameterizer (paper sections 4.1, 4.2): choose the
// fixed vertices, close or free the holes, eliminate, factor once; then any
// number of solves for new boundary positions and constraint targets.
#include "intrinsic/parameterizer.h"

#include <chrono>
#include <cmath>

#include "intrinsic/assemble.h"
#include "intrinsic/error.h"
#include "parameterizer_impl.h"

namespace intrinsic {
namespace {

// boundary_positions(), plus what it leaves to the solve: a vertex given
// twice, or a non-finite position.
std::vector<FixedVertex> fixed_positions(const Mesh& mesh, const ParamOptions& o) {
  if (o.boundary == BoundaryShape::Given) {
    std::vector<char> seen(mesh.V.rows(), 0);
    for (const FixedVertex& fv : o.given) {
      if (fv.vertex < 0 || fv.vertex >= mesh.V.rows()) continue;  // boundary_positions names it
      if (seen[fv.vertex]) throw_input("two boundary positions for vertex " + std::to_string(fv.vertex));
      if (!fv.uv.allFinite()) throw_input("non-finite boundary position for vertex " + std::to_string(fv.vertex));
      seen[fv.vertex] = 1;
    }
  }
  return boundary_positions(mesh, o);
}

}  // namespace


Parameterizer::Parameterizer(const Mesh& mesh, const ParamOptions& o) : impl_(std::make_unique<Impl>()) {
  const Topology& t = mesh.topology;
  if (t.num_components != 1)
    throw_usage("parameterize takes one connected component; this mesh has " + std::to_string(t.num_components));
  if (t.component_loops[0].empty()) throw_input("the surface is closed (no boundary)");
  if (o.weights.method == Method::Mixed && o.weights.lambda == 0 && o.weights.mu == 0)
    throw_usage("mixed method needs lambda and mu not both zero");
  if (!std::isfinite(o.weights.lambda) || !std::isfinite(o.weights.mu))
    throw_usage("lambda and mu must be finite");
  Impl& s = *impl_;
  s.mesh = &mesh;
  s.o = o;
  s.natural_boundary = o.boundary == BoundaryShape::Natural;
  s.natural = s.natural_boundary || solves_natural_holes(mesh, o);
  if (s.natural_boundary) {
    check_natural_method(o.weights);
    s.pins = natural_pins(mesh, o);
    s.build(s.pins);
    if (!o.pins.empty()) {  // the user's pins are output coordinates
      s.scale = "given";
      return;
    }
  } else {
    if (!o.pins.empty()) throw_usage("pins apply to the natural boundary only (use given boundary positions instead)");
    s.build(fixed_positions(mesh, o));
    if (o.boundary == BoundaryShape::Given) {
      s.scale = "given";
      return;
    }
  }
  // Place the shape in output coordinates now, so constraints (set later)
  // and the result share one frame. The map commutes with similarities of
  // the boundary (rows of K sum to zero), so the unconstrained result equals
  // solving first and scaling after.
  double scale = 0.5;
  Eigen::RowVector2d offset(0.5, 0.5);
  const auto t_solve = std::chrono::steady_clock::now();
  s.X = s.solve_for(s.UB);
  s.timings.solve_ms = detail::elapsed_ms(t_solve);
  if (s.natural_boundary) {
    // Default pins: as natural_map, fit [0, 1]^2 by a similarity (Unit) or
    // keep the pins at their 3D distance (Surface). The natural map commutes
    // with similarities of the pins (E_D - A is invariant under them), so
    // moving the pins now gives the unconstrained natural_map result.
    scale = 1.0;
    offset.setZero();
    s.scale = "surface";
    if (o.scale == ScaleMode::Unit) {
      s.scale = "unit";
      const MatrixX2d UV = s.full_uv(s.X, s.UB);
      Eigen::RowVector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
      for (int v = 0; v < UV.rows(); ++v)
        if (t.is_used[v]) {
          lo = lo.cwiseMin(UV.row(v));
          hi = hi.cwiseMax(UV.row(v));
        }
      const double extent = (hi - lo).maxCoeff();
      if (extent > 0) {
        scale = 1.0 / extent;
        offset = Eigen::RowVector2d(0.5, 0.5) - 0.5 * (lo + hi) / extent;
      }
    }
  } else if (o.scale == ScaleMode::Unit) {
    // The circle and square live in [-1, 1]^2: that box goes onto [0, 1]^2
    // exactly (a bounding-box fit would depend on where the vertices fall).
    s.scale = "unit";
  } else {
    s.scale = "surface";
    // About the origin, as scale_to_surface_area does, so that maps sharing
    // a fixed boundary still share it.
    const MatrixX2d UV = s.full_uv(s.X, s.UB);
    const double a_param = std::abs(parameter_area(mesh.F, UV));
    scale = a_param > 0 ? std::sqrt(surface_area(mesh.V, mesh.F) / a_param) : 1.0;
    offset.setZero();
  }
  s.place(scale, offset);
  s.update_fixed_list();
  s.have_X = true;
}

Parameterizer::~Parameterizer() = default;
Parameterizer::Parameterizer(Parameterizer&&) noexcept = default;
Parameterizer& Parameterizer::operator=(Parameterizer&&) noexcept = default;

ParamResult Parameterizer::solve() {
  Impl& s = *impl_;
  if (!s.have_X) {
    const auto t_solve = std::chrono::steady_clock::now();
    s.X = s.solve_for(s.UB, &s.lambda);
    s.timings.solve_ms = detail::elapsed_ms(t_solve);
    s.have_X = true;
  }
  ParamResult r;
  r.free_vertices = s.free_vertex_count();
  r.fixed_vertices = s.fixed_vertex_count();
  r.filled_holes = s.filled_holes;
  r.factorizations = s.factorizations;
  r.scale = s.scale;
  r.timings = s.timings;
  if (s.natural_boundary) {
    r.pins = s.pins;
    r.holes = s.mesh->topology.component_loops[0].size() > 1 ? "natural" : "none";
  } else if (s.natural) {
    r.holes = "natural";
  }
  if (r.free_vertices > 0) {
    r.solver = s.solver->name();
    r.iterations = s.solver->iterations();
    if (!s.X.allFinite())
      throw_numerical("the solution has non-finite values: the system is singular or nearly so "
                      "(look for coincident boundary positions or nearly degenerate faces)");
    const Eigen::MatrixXd rhs = -(s.K_IB * s.UB);
    Eigen::MatrixXd res = s.A * s.X - rhs;
    if (s.saddle.rows() > 0 && s.lambda.rows() == s.saddle.rows()) res += s.saddle.C().transpose() * s.lambda;
    for (int c = 0; c < res.cols(); ++c) {
      const double b = rhs.col(c).norm(), e = res.col(c).norm();
      r.residual = std::max(r.residual, b > 0 ? e / b : e);
    }
    if (!(r.residual <= s.o.max_residual))
      throw_numerical("the relative residual " + short_number(r.residual) + " of solver " + r.solver +
                      " exceeds " + short_number(s.o.max_residual) +
                      " (an iterative solver may not have converged; try --solver auto)");
  } else {
    r.solver = "none (every vertex is fixed)";
  }
  r.UV = s.full_uv(s.X, s.UB);
  r.constraints = residuals(r.UV);
  return r;
}

ParamResult Parameterizer::solve_with_boundary(const std::vector<FixedVertex>& fixed) {
  Impl& s = *impl_;
  bool same_set = fixed.size() == s.fixed.size();
  std::vector<char> seen(s.n, 0);
  for (const FixedVertex& fv : fixed) {
    if (fv.vertex < 0 || fv.vertex >= s.n)
      throw_input("boundary position for vertex " + std::to_string(fv.vertex) + ", which does not exist");
    if (seen[fv.vertex]) throw_input("two boundary positions for vertex " + std::to_string(fv.vertex));
    if (!fv.uv.allFinite()) throw_input("non-finite boundary position for vertex " + std::to_string(fv.vertex));
    seen[fv.vertex] = 1;
    same_set = same_set && s.p.fixed_index[fv.vertex] >= 0;
  }
  if (same_set) {
    Eigen::MatrixXd ub(s.UB.rows(), s.UB.cols());
    for (const FixedVertex& fv : fixed) s.set_fixed_uv(ub, fv.vertex, fv.uv);
    s.check_fixed_only(ub);
    s.UB = ub;
    s.update_fixed_list();
    s.have_X = false;
  } else {
    // Another set of fixed vertices changes K_II itself.
    if (s.natural_boundary) {  // new pins
      s.o.pins = fixed;
      s.pins = natural_pins(*s.mesh, s.o);
      s.build(s.pins);
    } else {
      s.o.boundary = BoundaryShape::Given;
      s.o.given = fixed;
      s.build(fixed_positions(*s.mesh, s.o));
    }
    s.scale = "given";
    s.setup_constraints();
  }
  return solve();
}

void Parameterizer::set_constraints(const Constraints& c) { set_constraints(resolve_constraints(*impl_->mesh, c)); }

void Parameterizer::set_constraints(std::vector<LinearConstraint> rows) {
  Impl& s = *impl_;
  s.rows = std::move(rows);
  try {
    s.setup_constraints();
  } catch (...) {
    s.rows.clear();
    s.setup_constraints();
    throw;
  }
}

void Parameterizer::set_constraint_targets(const std::vector<Eigen::Vector2d>& targets) {
  Impl& s = *impl_;
  if (targets.size() != s.rows.size())
    throw_usage(std::to_string(targets.size()) + " targets for " + std::to_string(s.rows.size()) + " constraints");
  const std::vector<LinearConstraint> old = s.rows;
  for (size_t k = 0; k < targets.size(); ++k) {
    if (!targets[k].allFinite()) throw_input(s.rows[k].label + ": non-finite target");
    s.rows[k].target = targets[k];
  }
  try {
    s.check_fixed_only(s.UB);
  } catch (...) {
    s.rows = old;
    throw;
  }
  s.have_X = false;
}

void Parameterizer::clear_constraints() { set_constraints(std::vector<LinearConstraint>{}); }

const std::vector<LinearConstraint>& Parameterizer::constraints() const { return impl_->rows; }

std::vector<ConstraintResidual> Parameterizer::residuals(const MatrixX2d& UV) const {
  std::vector<ConstraintResidual> out;
  for (const LinearConstraint& c : impl_->rows) {
    ConstraintResidual r;
    r.label = c.label;
    r.target = c.target;
    r.value = Eigen::Vector2d::Zero();
    for (auto [v, w] : c.terms) r.value += w * UV.row(v).transpose();
    r.residual = (r.value - r.target).norm();
    out.push_back(r);
  }
  return out;
}

const std::vector<FixedVertex>& Parameterizer::boundary() const { return impl_->fixed; }
const Mesh& Parameterizer::mesh() const { return *impl_->mesh; }
const ParamOptions& Parameterizer::options() const { return impl_->o; }
int Parameterizer::free_vertices() const { return impl_->free_vertex_count(); }
int Parameterizer::factorizations() const { return impl_->factorizations; }
int Parameterizer::constraint_setups() const { return impl_->constraint_setups; }

}  // namespace intrinsic
