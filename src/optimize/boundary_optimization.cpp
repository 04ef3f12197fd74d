// L-BFGS over the boundary positions with the interior following the
// intrinsic map (paper section 5.2; docs/maths.md §8), gradients by adjoint
// solve or by the precomputed boundary responses, and a line search that
// refuses folds and boundary self-crossings. Every solve goes through the
// Parameterizer's eliminated system.
#include "intrinsic/boundary_optimization.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <deque>

#include "core/parameterizer_impl.h"
#include "weights/assemble.h"
#include "intrinsic/error.h"
#include "intrinsic/metrics.h"
#include "util/stopwatch.h"

namespace intrinsic {
using detail::ms_since;
namespace {

int count_flips(const MatrixX3i& F, const MatrixX2d& UV) {
  int flips = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::RowVector2d a = UV.row(F(f, 0)), b = UV.row(F(f, 1)), c = UV.row(F(f, 2));
    flips += ((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x())) > 0 ? 0 : 1;
  }
  return flips;
}

double orient(const Eigen::RowVector2d& a, const Eigen::RowVector2d& b, const Eigen::RowVector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// True when two boundary segments that share no vertex intersect. Sweep over
// x: segments sorted by their left end, compared only while they overlap in x.
}  // namespace

bool boundary_crosses(const std::vector<std::array<int, 2>>& segments, const MatrixX2d& UV) {
  struct Item { double lo, hi; int s; };
  std::vector<Item> items(segments.size());
  for (size_t s = 0; s < segments.size(); ++s) {
    const double x0 = UV(segments[s][0], 0), x1 = UV(segments[s][1], 0);
    items[s] = {std::min(x0, x1), std::max(x0, x1), static_cast<int>(s)};
  }
  std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) { return a.lo < b.lo; });
  for (size_t i = 0; i < items.size(); ++i) {
    const auto& si = segments[items[i].s];
    const Eigen::RowVector2d p = UV.row(si[0]), q = UV.row(si[1]);
    for (size_t j = i + 1; j < items.size() && items[j].lo <= items[i].hi; ++j) {
      const auto& sj = segments[items[j].s];
      if (si[0] == sj[0] || si[0] == sj[1] || si[1] == sj[0] || si[1] == sj[1]) continue;
      const Eigen::RowVector2d r = UV.row(sj[0]), t = UV.row(sj[1]);
      const double d1 = orient(p, q, r), d2 = orient(p, q, t), d3 = orient(r, t, p), d4 = orient(r, t, q);
      if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0) return true;
    }
  }
  return false;
}

namespace {

std::vector<char> loop_vertices(const Mesh& mesh) {
  std::vector<char> on_loop(mesh.V.rows(), 0);
  for (const auto& loop : mesh.topology.boundary_loops)
    for (int v : loop) on_loop[v] = 1;
  return on_loop;
}

// A Parameterizer with every loop vertex fixed at its position in `start`.
Parameterizer all_loops_fixed(const Mesh& mesh, const ParamOptions& base, const MatrixX2d& start) {
  ParamOptions o = base;
  o.boundary = BoundaryShape::Given;
  o.holes = HoleRule::Free;  // every hole is fixed: no rule applies
  o.pins.clear();
  o.given.clear();
  const std::vector<char> on_loop = loop_vertices(mesh);
  for (int v = 0; v < mesh.V.rows(); ++v)
    if (on_loop[v]) o.given.push_back({v, start.row(v).transpose()});
  return Parameterizer(mesh, o);
}

}  // namespace

struct BoundaryObjective::Impl {
  Parameterizer parameterizer;
  BoundaryEnergy energy;
  GradientRoute route;
  Eigen::MatrixXd R;  // responses A^{-1} K_IB, for GradientRoute::Responses
  std::vector<std::array<int, 2>> segments;
  Eigen::MatrixX2i edges;  // unique_edges(F), once
  int solves = 0, response_solves = 0;

  Impl(Parameterizer&& p, const BoundaryOptimizationOptions& o)
      : parameterizer(std::move(p)), energy(o.energy), route(o.route) {}
  const Mesh& mesh() const { return parameterizer.mesh(); }
  const detail::EliminatedSystem& sys() const { return *parameterizer.impl_->sys; }
  const Partition& p() const { return sys().partition(); }
  void compute_responses(double budget_bytes);
};

// R = A^{-1} K_IB, in blocks of columns to bound the dense workspace.
void BoundaryObjective::Impl::compute_responses(double budget_bytes) {
  const int free = sys().free_count(), fixed = sys().known_count();
  if (free == 0) return;
  const double bytes = 8.0 * free * fixed;
  if (bytes > budget_bytes)
    throw_usage("the boundary responses would take " + std::to_string(static_cast<long long>(bytes / (1 << 20))) +
                " MiB (" + std::to_string(fixed) + " boundary x " + std::to_string(free) +
                " free vertices), above the budget; use the adjoint route");
  R.resize(free, fixed);
  const int block = 64;
  for (int c0 = 0; c0 < fixed; c0 += block) {
    const int w = std::min(block, fixed - c0);
    R.middleCols(c0, w) = sys().solve(Eigen::MatrixXd(sys().K_IB().middleCols(c0, w)));
    response_solves += w;
  }
}

BoundaryObjective::BoundaryObjective(const Mesh& mesh, const BoundaryOptimizationOptions& o, const MatrixX2d& start)
    : BoundaryObjective(all_loops_fixed(mesh, o.base, start), o) {}

BoundaryObjective::BoundaryObjective(Parameterizer&& parameterizer, const BoundaryOptimizationOptions& o)
    : impl_(std::make_unique<Impl>(std::move(parameterizer), o)) {
  Impl& s = *impl_;
  for (const auto& loop : s.mesh().topology.boundary_loops)
    for (size_t k = 0; k < loop.size(); ++k) s.segments.push_back({loop[k], loop[(k + 1) % loop.size()]});
  s.edges = unique_edges(s.mesh().F);
  if (o.route == GradientRoute::Responses) s.compute_responses(o.responses_budget_bytes);
}

BoundaryObjective::~BoundaryObjective() = default;
BoundaryObjective::BoundaryObjective(BoundaryObjective&&) noexcept = default;

int BoundaryObjective::boundary_size() const { return impl_->sys().known_count(); }
const std::vector<int>& BoundaryObjective::boundary_vertices() const { return impl_->p().fixed_vertices; }
const std::vector<std::array<int, 2>>& BoundaryObjective::segments() const { return impl_->segments; }
int BoundaryObjective::solves() const { return impl_->solves; }
int BoundaryObjective::response_solves() const { return impl_->response_solves; }
int BoundaryObjective::factorizations() const { return impl_->parameterizer.factorizations(); }

ParamResult BoundaryObjective::final_map(const Eigen::VectorXd& x, ScaleMode scale) {
  Impl& s = *impl_;
  std::vector<FixedVertex> fixed(boundary_size());
  for (int b = 0; b < boundary_size(); ++b) fixed[b] = {boundary_vertices()[b], x.segment<2>(2 * b)};
  ParamResult r = s.parameterizer.solve_with_boundary(fixed);
  const std::vector<char> used(s.mesh().topology.is_used.begin(), s.mesh().topology.is_used.end());
  r.placement = scale == ScaleMode::Unit ? Placement::Unit : Placement::Surface;
  const detail::PlacementRule rule =
      scale == ScaleMode::Unit ? detail::PlacementRule::FitUnitSquare : detail::PlacementRule::AsSolved;
  detail::apply(detail::placement(rule, s.mesh().V, s.mesh().F, r.UV, used), r.UV, used);
  return r;
}

Eigen::VectorXd BoundaryObjective::boundary_of(const MatrixX2d& UV) const {
  Eigen::VectorXd x(2 * boundary_size());
  for (int b = 0; b < boundary_size(); ++b) x.segment<2>(2 * b) = UV.row(boundary_vertices()[b]).transpose();
  return x;
}

MatrixX2d BoundaryObjective::map(const Eigen::VectorXd& x) {
  Impl& s = *impl_;
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>> UB(x.data(), boundary_size(), 2);
  Eigen::MatrixXd UI;
  if (s.route == GradientRoute::Responses) {
    UI = -(s.R * UB);
  } else if (s.sys().free_count() > 0) {
    UI = s.sys().solve(s.sys().rhs(UB));
    ++s.solves;
  }
  MatrixX2d UV = MatrixX2d::Zero(s.mesh().V.rows(), 2);
  for (size_t i = 0; i < s.p().free_vertices.size(); ++i) UV.row(s.p().free_vertices[i]) = UI.row(i);
  for (int b = 0; b < boundary_size(); ++b) UV.row(s.p().fixed_vertices[b]) = UB.row(b);
  return UV;
}

double BoundaryObjective::energy(const MatrixX2d& UV, Eigen::VectorXd* grad) {
  Impl& s = *impl_;
  MatrixX2d g;
  const double e = boundary_energy(s.mesh().V, s.mesh().F, s.edges, UV, s.energy, grad ? &g : nullptr);
  if (!grad || !std::isfinite(e)) return e;
  const Partition& p = s.p();
  Eigen::MatrixXd gI(p.free_vertices.size(), 2);
  for (size_t i = 0; i < p.free_vertices.size(); ++i) gI.row(i) = g.row(p.free_vertices[i]);
  Eigen::MatrixXd through;  // (dU_I/dU_B)^T dE/dU_I = -K_IB^T A^{-T} gI
  if (p.free_vertices.empty()) {
    through = Eigen::MatrixXd::Zero(boundary_size(), 2);
  } else if (s.route == GradientRoute::Responses) {
    through = -(s.R.transpose() * gI);
  } else {
    through = -(s.sys().K_IB().transpose() * s.sys().solve_transposed(gI));
    ++s.solves;
  }
  grad->resize(2 * boundary_size());
  for (int b = 0; b < boundary_size(); ++b)
    grad->segment<2>(2 * b) = (g.row(p.fixed_vertices[b]) + through.row(b)).transpose();
  return e;
}

namespace {

// Start: the intrinsic map of the chosen boundary at the surface's scale
// (the energies compare lengths and areas with the 3D ones). Its
// Parameterizer becomes the objective's when it already fixes every loop.
BoundaryObjective make_objective(const Mesh& mesh, const BoundaryOptimizationOptions& o, ParamResult& start_map) {
  ParamOptions start = o.base;
  if (start.boundary != BoundaryShape::Given) start.scale = ScaleMode::Surface;
  Parameterizer p(mesh, start);
  start_map = p.solve();
  const std::vector<char> on_loop = loop_vertices(mesh);
  const size_t loop_count = std::count(on_loop.begin(), on_loop.end(), 1);
  const bool every_loop_fixed = start.boundary != BoundaryShape::Natural && p.boundary().size() == loop_count &&
                                std::all_of(p.boundary().begin(), p.boundary().end(),
                                            [&](const FixedVertex& fv) { return on_loop[fv.vertex] != 0; });
  if (every_loop_fixed) {
    start_map.factorizations = 0;  // counted by the objective, which takes over its Parameterizer
    return BoundaryObjective(std::move(p), o);
  }
  return BoundaryObjective(mesh, o, start_map.UV);
}

// L-BFGS two-loop recursion: the descent direction for gradient g.
Eigen::VectorXd lbfgs_direction(const std::deque<Eigen::VectorXd>& S, const std::deque<Eigen::VectorXd>& Y,
                                const Eigen::VectorXd& g) {
  std::vector<double> a(S.size());
  Eigen::VectorXd q = g;
  for (int k = static_cast<int>(S.size()) - 1; k >= 0; --k) {
    a[k] = S[k].dot(q) / Y[k].dot(S[k]);
    q -= a[k] * Y[k];
  }
  q *= S.back().dot(Y.back()) / Y.back().squaredNorm();
  for (size_t k = 0; k < S.size(); ++k) q += S[k] * (a[k] - Y[k].dot(q) / Y[k].dot(S[k]));
  return -q;
}

struct Step {
  bool accepted = false;
  double alpha = 0, energy = 0;
  Eigen::VectorXd x;
  MatrixX2d UV;
};

// Backtracking from alpha: Armijo decrease, no new flips, no boundary
// crossing. The map is linear in the boundary (docs/maths.md §8.1), so the
// map of x + alpha d is UV + alpha D with D the map of d: one solve per line
// search, however many steps the fold barrier rejects (on max-planck-partial
// late iterations rejected 10-17 steps, each a solve, before this).
Step line_search(BoundaryObjective& map, const Mesh& mesh, const Eigen::VectorXd& x, const MatrixX2d& UV,
                 const Eigen::VectorXd& d, const Eigen::VectorXd& g, double e, double alpha, int flipped_initial,
                 bool crossing_initial) {
  Step s;
  const MatrixX2d D = map.map(d);
  for (int tries = 0; tries < 50 && !s.accepted; ++tries, alpha *= 0.5) {
    s.x = x + alpha * d;
    s.UV = UV + alpha * D;
    if (count_flips(mesh.F, s.UV) > flipped_initial) continue;
    if (!crossing_initial && boundary_crosses(map.segments(), s.UV)) continue;
    s.energy = map.energy(s.UV, nullptr);
    if (std::isfinite(s.energy) && s.energy <= e + 1e-4 * alpha * d.dot(g)) {
      s.accepted = true;
      s.alpha = alpha;
    }
  }
  return s;
}

}  // namespace

BoundaryOptimizationResult optimize_boundary(const Mesh& mesh, const BoundaryOptimizationOptions& o) {
  if (o.max_iterations < 0) throw_usage("the number of iterations must not be negative");
  if (!(o.tolerance >= 0)) throw_usage("the tolerance must not be negative");
  BoundaryOptimizationResult result;
  const auto t_setup = std::chrono::steady_clock::now();
  ParamResult start;
  BoundaryObjective map = make_objective(mesh, o, start);
  Eigen::VectorXd x = map.boundary_of(start.UV), g;
  MatrixX2d UV = map.map(x);
  double e = map.energy(UV, &g);
  if (!std::isfinite(e))
    throw_numerical("the starting map has infinite energy (a flipped or collapsed triangle); "
                    "the symmetric Dirichlet energy needs a fold-free start");
  result.flipped_initial = count_flips(mesh.F, UV);
  const bool crossing_initial = boundary_crosses(map.segments(), UV);
  result.energy_history.push_back(e);
  result.setup_ms = ms_since(t_setup);

  const auto t_opt = std::chrono::steady_clock::now();
  std::deque<Eigen::VectorXd> S, Y;
  const double diam = (UV.colwise().maxCoeff() - UV.colwise().minCoeff()).norm();
  double scale_hint = g.norm() > 0 ? 0.01 * diam / g.norm() : 0;  // first step length for plain gradient steps
  result.stop_reason = "iteration limit";
  for (int it = 0; it < o.max_iterations; ++it) {
    if (g.norm() == 0) { result.stop_reason = "zero gradient"; break; }
    const bool quasi_newton = o.descent == Descent::LBFGS && !S.empty();
    Eigen::VectorXd d = quasi_newton ? lbfgs_direction(S, Y, g) : Eigen::VectorXd(-g);
    double alpha0 = quasi_newton ? 1 : scale_hint;
    if (d.dot(g) >= 0) { d = -g; alpha0 = scale_hint; S.clear(); Y.clear(); }
    const Step step = line_search(map, mesh, x, UV, d, g, e, alpha0, result.flipped_initial, crossing_initial);
    if (!step.accepted) { result.stop_reason = "line search found no admissible decrease"; break; }
    Eigen::VectorXd g_new;
    map.energy(step.UV, &g_new);
    const Eigen::VectorXd s = step.x - x, y = g_new - g;
    if (s.dot(y) > 1e-12 * s.norm() * y.norm()) {
      S.push_back(s);
      Y.push_back(y);
      if (static_cast<int>(S.size()) > o.lbfgs_memory) { S.pop_front(); Y.pop_front(); }
    }
    if (o.descent == Descent::GradientDescent) scale_hint = step.alpha * 2;  // let plain steps grow back
    const double decrease = (e - step.energy) / std::max(e, 1e-300);
    x = step.x;
    g = g_new;
    UV = step.UV;
    e = step.energy;
    ++result.iterations;
    result.energy_history.push_back(e);
    if (o.progress) o.progress(result.iterations, e);
    if (decrease < o.tolerance) { result.stop_reason = "relative decrease below tolerance"; break; }
  }
  result.optimize_ms = ms_since(t_opt);
  result.UV = UV;
  result.flipped_final = count_flips(mesh.F, UV);
  result.solves = map.solves();
  result.response_solves = map.response_solves();
  result.factorizations = start.factorizations + map.factorizations();
  result.map = map.final_map(x, o.base.scale);
  // Report what was asked and started from: the start's boundary and holes.
  result.map.boundary = start.boundary;
  result.map.spacing = start.spacing;
  result.map.holes = start.holes;
  result.map.filled_holes = start.filled_holes;
  result.map.pins = start.pins;
  result.map.factorizations = result.factorizations;
  return result;
}

}  // namespace intrinsic
