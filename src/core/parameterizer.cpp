// The kept-factorization parameterizer (paper sections 4.1, 4.2;
// docs/maths.md §2-§5), the one solve path of every mode: the public calls.
// Construction is in parameterizer_build.cpp, the solves in
// parameterizer_impl.cpp.
#include "intrinsic/parameterizer.h"

#include <chrono>
#include <cmath>

#include "core/natural_system.h"
#include "core/parameterizer_impl.h"
#include "intrinsic/error.h"

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

// The checks every mode shares; the mode's own ones follow in the helpers.
void check_options(const Mesh& mesh, const ParamOptions& o) {
  const Topology& t = mesh.topology;
  if (t.num_components != 1)
    throw_usage("parameterize takes one connected component; this mesh has " + std::to_string(t.num_components) +
                " (use parameterize_charts, or keep the largest component)");
  if (t.component_loops[0].empty())
    throw_input((mesh.path.empty() ? "" : mesh.path + ": ") +
                "the surface is closed (no boundary): use `intrinsic atlas` (library: atlas.h), which cuts it into disk charts");
  check_weights(o.weights);
  if (o.boundary == BoundaryShape::Natural) check_natural_method(o.weights);
  else if (!o.pins.empty())
    throw_usage("pins apply to the natural boundary only (use given boundary positions instead)");
}

}  // namespace

Parameterizer::Parameterizer(const Mesh& mesh, const ParamOptions& o) : impl_(std::make_unique<Impl>()) {
  check_options(mesh, o);
  Impl& s = *impl_;
  s.mesh = &mesh;
  s.o = o;
  s.natural_boundary = o.boundary == BoundaryShape::Natural;
  s.natural = s.natural_boundary || solves_natural_holes(mesh, o);
  s.holes = s.holes_applied();
  if (s.natural_boundary) s.pins = natural_pins(mesh, o);
  s.build(s.natural_boundary ? s.pins : fixed_positions(mesh, o));
  try {
    s.place_initially();
  } catch (const Error& e) {
    s.throw_diagnosed(e);
  }
}

Parameterizer::~Parameterizer() = default;
Parameterizer::Parameterizer(Parameterizer&&) noexcept = default;
Parameterizer& Parameterizer::operator=(Parameterizer&&) noexcept = default;

ParamResult Parameterizer::solve() {
  Impl& s = *impl_;
  try {
    if (!s.have_X) {
      const auto t_solve = std::chrono::steady_clock::now();
      s.X = s.solve_for(s.UB, &s.lambda);
      s.timings.solve_ms = detail::elapsed_ms(t_solve);
      s.have_X = true;
    }
    ParamResult r = s.result();
    if (r.free_vertices > 0) {
      if (!s.X.allFinite())
        throw_numerical(std::string("the solution has non-finite values: the system is singular or nearly so "
                                    "(look for coincident ") +
                        (s.natural_boundary ? "pins" : "boundary positions") + " or nearly degenerate faces)");
      r.residual = s.residual();
      if (!(r.residual <= s.o.max_residual))
        throw_numerical("the relative residual " + short_number(r.residual) + " of solver " + solvers_name(r.solvers) +
                        " exceeds " + short_number(s.o.max_residual) +
                        " (an iterative solver may not have converged; try --solver auto)");
    }
    r.UV = s.full_uv(s.X, s.UB);
    r.constraints = residuals(r.UV);
    return r;
  } catch (const Error& e) {
    s.throw_diagnosed(e);
  }
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
    same_set = same_set && s.p().fixed_index[fv.vertex] >= 0;
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
    s.placement = Placement::Given;
    s.setup_constraints();
  }
  return solve();
}

void Parameterizer::set_boundary_shape(BoundaryShape shape) {
  Impl& s = *impl_;
  auto swappable = [](BoundaryShape b) { return b == BoundaryShape::Circle || b == BoundaryShape::Square; };
  if (s.natural || !swappable(shape) || !swappable(s.o.boundary))
    throw_usage("only circle and square swap on the kept factorization (same fixed vertices, fixed layout)");
  if (shape == s.o.boundary) return;
  const ParamOptions old_options = s.o;
  const Eigen::MatrixXd old_UB = s.UB;
  const Placement old_placement = s.placement;
  try {
    s.o.boundary = shape;
    const std::vector<FixedVertex> fixed = boundary_positions(*s.mesh, s.o);
    if (fixed.size() != s.fixed.size()) throw_usage("the " + boundary_shape_name(shape) + " fixes other vertices");
    for (const FixedVertex& fv : fixed) {
      if (s.p().fixed_index[fv.vertex] < 0) throw_usage("the new boundary fixes other vertices");
      s.UB.row(s.p().fixed_index[fv.vertex]) = fv.uv.transpose();
    }
    s.have_X = false;
    // Placed before any constraint, as at construction: from the unconstrained map.
    const detail::PlacementRule rule = s.initial_placement_rule();
    if (rule != detail::PlacementRule::AsSolved) {
      MatrixX2d UV;
      if (rule != detail::PlacementRule::UnitBox) UV = s.full_uv(s.sys->solve(s.sys->rhs(s.UB)), s.UB);
      const std::vector<char> used(s.mesh->topology.is_used.begin(), s.mesh->topology.is_used.end());
      s.place(detail::placement(rule, s.mesh->V, s.mesh->F, UV, used));
    }
    s.check_fixed_only(s.UB);
    s.update_fixed_list();
  } catch (...) {
    s.o = old_options;
    s.UB = old_UB;
    s.placement = old_placement;
    s.have_X = false;
    throw;
  }
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
