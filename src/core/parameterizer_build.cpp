// Parameterizer construction (paper sections 4.1, 4.2; docs/maths.md §2-§4):
// choose the fixed unknowns, close or free the holes, assemble, eliminate,
// factor once (its ordering and symbolic analysis computed beside the
// assembly: solve/ordering_ahead.h), and place the boundary in output coordinates.
#include <cmath>
#include <new>
#include <system_error>

#include "core/failure_diagnosis.h"
#include "core/hole_fill.h"
#include "core/natural_system.h"
#include "core/parameterizer_impl.h"
#include "weights/assemble.h"
#include "solve/ordering_ahead.h"
#include "weights/assemble_stages.h"

namespace intrinsic {

void Parameterizer::Impl::build(const std::vector<FixedVertex>& given) {
  if (natural) build_natural(given);
  else build_fixed(given);
}

void Parameterizer::Impl::build_fixed(const std::vector<FixedVertex>& given) {
  const auto t_assemble = std::chrono::steady_clock::now();
  n = static_cast<int>(mesh->V.rows());
  fixed = given;  // until placed: named by a failure's diagnosis
  std::vector<char> is_fixed(n, 0), is_used(mesh->topology.is_used.begin(), mesh->topology.is_used.end());
  for (const FixedVertex& fv : given) is_fixed[fv.vertex] = 1;
  filled_holes = 0;
  SparseMatrix K;
  std::shared_ptr<detail::AnalysisAhead> ahead;
  // K's pattern first, its free block handed to the ordering thread, then
  // the values into it: the faces' adjacency is counted once for both.
  auto assemble = [&](const MatrixX3d& V, const MatrixX3i& F) {
    detail::weight_matrix_pattern(F, static_cast<int>(V.rows())).swap(K);
    ahead = analyse_ahead(K, is_fixed, is_used);
    detail::assemble_weight_values(V, F, o.weights, K);
  };
  // Only a surface with holes is copied to be filled (at 1M vertices the
  // copy of V and F is 48 MB and a good part of the assembly time).
  if (o.holes == HoleRule::Fill && mesh->topology.component_loops[0].size() > 1) {
    const detail::FilledSurface s = detail::fill_holes(*mesh, is_fixed);
    filled_holes = s.filled;
    is_fixed.resize(s.V.rows(), 0);
    is_used.resize(s.V.rows(), 1);
    assemble(s.V, s.F);
  } else {
    assemble(mesh->V, mesh->F);
  }
  factor(std::move(K), is_fixed, is_used, is_symmetric(o.weights), t_assemble, std::move(ahead));
  UB.resize(sys->known_count(), 2);
  for (const FixedVertex& fv : given) UB.row(p().fixed_index[fv.vertex]) = fv.uv.transpose();
  update_fixed_list();
}

void Parameterizer::Impl::build_natural(const std::vector<FixedVertex>& given) {
  const auto t_assemble = std::chrono::steady_clock::now();
  const Topology& t = mesh->topology;
  n = static_cast<int>(mesh->V.rows());
  fixed = given;
  filled_holes = 0;
  // Swapped in, not assigned: Eigen 3.4's SparseMatrix assignment copies
  // (168 MB at 1M vertices), even from a temporary.
  SparseMatrix Q;
  bool symmetric = true;
  if (natural_boundary) {
    assemble_natural_system(*mesh).swap(Q);  // every loop natural
  } else {
    const SparseMatrix K = assemble_weight_matrix(mesh->V, mesh->F, o.weights);
    std::vector<std::vector<int>> loops;
    for (size_t k = 1; k < t.component_loops[0].size(); ++k) loops.push_back(t.boundary_loops[t.component_loops[0][k]]);
    real_form_matrix(K, natural_hole_weight(o.weights) * area_coupling(n, loops)).swap(Q);
    symmetric = is_symmetric(o.weights);
  }
  std::vector<char> fixed2(2 * n, 0), used2(2 * n, 0);
  for (int v = 0; v < n; ++v) used2[v] = used2[n + v] = t.is_used[v];
  for (const FixedVertex& fv : given) fixed2[fv.vertex] = fixed2[n + fv.vertex] = 1;
  factor(std::move(Q), fixed2, used2, symmetric, t_assemble);
  UB.resize(sys->known_count(), 1);
  for (const FixedVertex& fv : given) set_fixed_uv(UB, fv.vertex, fv.uv);
  update_fixed_list();
}

// The ordering and symbolic analysis of the free block of K's pattern,
// started on another thread before the weights are assembled
// (solve/ordering_ahead.h: the same factorization, bit for bit), or null
// where the solver would not use it or the mesh is too small to gain.
std::shared_ptr<detail::AnalysisAhead> Parameterizer::Impl::analyse_ahead(const SparseMatrix& K_pattern,
                                                                          const std::vector<char>& is_fixed,
                                                                          const std::vector<char>& is_used) const {
#ifdef INTRINSIC_HAVE_SUITESPARSE
  try {
    if (detail::analysis_ahead_wanted(o.solver, static_cast<int>(is_fixed.size())))
      return std::make_shared<detail::AnalysisAhead>(detail::free_block_pattern(K_pattern, is_fixed, is_used));
  } catch (const std::system_error&) {
    // No thread to be had: the solver analyses A itself, as without this.
  } catch (const std::bad_alloc&) {
    // No room for the pattern's copy: likewise.
  }
#else
  (void)K_pattern;
  (void)is_fixed;
  (void)is_used;
#endif
  return nullptr;
}

// The natural layout's system is ill-conditioned (two pins only): its
// solves always refine (LinearSolver::set_ill_conditioned).
void Parameterizer::Impl::factor(SparseMatrix&& K, const std::vector<char>& is_fixed,
                                 const std::vector<char>& is_used, bool symmetric,
                                 std::chrono::steady_clock::time_point t_assemble,
                                 std::shared_ptr<detail::AnalysisAhead> ahead) {
  timings.assemble_ms = detail::elapsed_ms(t_assemble);
  const auto t_factor = std::chrono::steady_clock::now();
  sys.reset();
  try {
    detail::EliminatedSystem::Factoring how;
    how.kind = o.solver;
    how.symmetric = symmetric;
    how.ill_conditioned = natural;
    how.complex_form = natural && symmetric;  // docs/maths.md §3.6
    how.analysis_ahead = std::move(ahead);
    sys = std::make_unique<detail::EliminatedSystem>(std::move(K), is_fixed, is_used, how);
  } catch (const Error& e) {
    throw_diagnosed(e);
  }
  if (sys->factored()) ++factorizations;
  timings.factor_ms = detail::elapsed_ms(t_factor);
  have_X = false;
}

// docs/maths.md §2.4: circle and square go directly onto [0,1]^2; default
// pins fit the natural map into it; Surface scales about the origin.
detail::PlacementRule Parameterizer::Impl::initial_placement_rule() {
  const bool given = natural_boundary ? !o.pins.empty() : o.boundary == BoundaryShape::Given;
  if (given) {
    placement = Placement::Given;
    return detail::PlacementRule::AsSolved;
  }
  placement = o.scale == ScaleMode::Unit ? Placement::Unit : Placement::Surface;
  if (natural_boundary)  // Surface: the default pins sit at their 3D distance already
    return o.scale == ScaleMode::Unit ? detail::PlacementRule::FitUnitSquare : detail::PlacementRule::AsSolved;
  return o.scale == ScaleMode::Unit ? detail::PlacementRule::UnitBox : detail::PlacementRule::SurfaceArea;
}

// Places the boundary in output coordinates before any constraint is set,
// so constraints and the result share one frame. The maps commute with
// similarities of the fixed positions (rows of K sum to zero; E_D - A is
// invariant under them), so the unconstrained result equals solving first
// and placing after.
void Parameterizer::Impl::place_initially() {
  const detail::PlacementRule rule = initial_placement_rule();
  if (rule == detail::PlacementRule::AsSolved) return;
  const auto t_solve = std::chrono::steady_clock::now();
  X = solve_for(UB);
  timings.solve_ms = detail::elapsed_ms(t_solve);
  have_X = true;
  const MatrixX2d UV = rule == detail::PlacementRule::UnitBox ? MatrixX2d() : full_uv(X, UB);
  const std::vector<char> used(mesh->topology.is_used.begin(), mesh->topology.is_used.end());
  place(detail::placement(rule, mesh->V, mesh->F, UV, used));
  update_fixed_list();
}

HolesApplied Parameterizer::Impl::holes_applied() const {
  if (mesh->topology.component_loops[0].size() < 2) return HolesApplied::None;
  if (natural) return HolesApplied::Natural;  // natural boundary: every loop is natural
  switch (o.holes) {
    case HoleRule::Fill: return HolesApplied::Fill;
    case HoleRule::Free: return HolesApplied::Free;
    case HoleRule::Natural: return HolesApplied::FreeNoConformalTerm;
  }
  return HolesApplied::Free;
}

void Parameterizer::Impl::throw_diagnosed(const Error& e) const {
  if (e.kind() != ErrorKind::Numerical) throw e;
  const WeightOptions w = natural_boundary ? WeightOptions{} : o.weights;  // the natural map is conformal
  throw Error(ErrorKind::Numerical, e.what() + detail::likely_cause(*mesh, w, fixed));
}

}  // namespace intrinsic
