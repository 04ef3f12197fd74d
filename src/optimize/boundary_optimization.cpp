// L-BFGS over the boundary positions with the interior following the
// intrinsic map (paper section 5.2), gradients by adjoint solve or by the
// precomputed boundary responses, and a line search that refuses folds and
// boundary self-crossings.
#include "intrinsic/boundary_optimization.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <array>
#include <deque>

#include "intrinsic/assemble.h"
#include "intrinsic/error.h"
#include "intrinsic/metrics.h"

namespace intrinsic {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

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

BoundaryObjective::BoundaryObjective(const Mesh& mesh, const BoundaryOptimizationOptions& o,
                                     BoundaryOptimizationResult& stats)
    : mesh_(mesh), o_(o), stats_(stats), solver_(o.base.solver, is_symmetric(o.base.weights)) {
  const int n = static_cast<int>(mesh.V.rows());
  std::vector<char> fixed(n, 0);
  for (const auto& loop : mesh.topology.boundary_loops)
    for (int v : loop) fixed[v] = 1;
  for (size_t l = 0; l < mesh.topology.boundary_loops.size(); ++l) {
    const auto& loop = mesh.topology.boundary_loops[l];
    for (size_t k = 0; k < loop.size(); ++k) segments_.push_back({loop[k], loop[(k + 1) % loop.size()]});
  }
  edges_ = unique_edges(mesh.F);
  p_ = partition(n, fixed, std::vector<char>(mesh.topology.is_used.begin(), mesh.topology.is_used.end()));
  const SparseMatrix K = assemble_weight_matrix(mesh.V, mesh.F, o.base.weights);
  split_matrix(K, p_, A_, K_IB_);
  if (!p_.free_vertices.empty()) {
    solver_.factor(A_);
    stats_.factorizations = solver_.factorizations();
  }
  if (o.route == GradientRoute::Responses && !p_.free_vertices.empty()) {
    const double bytes = 8.0 * p_.free_vertices.size() * p_.fixed_vertices.size();
    if (bytes > o.responses_budget_bytes)
      throw_usage("the boundary responses would take " + std::to_string(static_cast<long long>(bytes / (1 << 20))) +
                  " MiB (" + std::to_string(p_.fixed_vertices.size()) + " boundary x " +
                  std::to_string(p_.free_vertices.size()) + " free vertices), above the budget; use the adjoint route");
    // R = A^{-1} K_IB, in blocks of columns to bound the dense workspace.
    R_.resize(p_.free_vertices.size(), p_.fixed_vertices.size());
    const int block = 64;
    for (int c0 = 0; c0 < K_IB_.cols(); c0 += block) {
      const int w = std::min<int>(block, static_cast<int>(K_IB_.cols()) - c0);
      const Eigen::MatrixXd rhs = Eigen::MatrixXd(K_IB_.middleCols(c0, w));
      R_.middleCols(c0, w) = solver_.solve(rhs);
      stats_.response_solves += w;
    }
  }
}

Eigen::VectorXd BoundaryObjective::boundary_of(const MatrixX2d& UV) const {
  Eigen::VectorXd x(2 * boundary_size());
  for (int b = 0; b < boundary_size(); ++b) x.segment<2>(2 * b) = UV.row(p_.fixed_vertices[b]).transpose();
  return x;
}

MatrixX2d BoundaryObjective::map(const Eigen::VectorXd& x) {
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>> UB(x.data(), boundary_size(), 2);
  Eigen::MatrixXd UI;
  if (o_.route == GradientRoute::Responses) {
    UI = -(R_ * UB);
  } else if (!p_.free_vertices.empty()) {
    UI = solver_.solve(-(K_IB_ * UB));
    ++stats_.solves;
  }
  MatrixX2d UV = MatrixX2d::Zero(mesh_.V.rows(), 2);
  for (size_t i = 0; i < p_.free_vertices.size(); ++i) UV.row(p_.free_vertices[i]) = UI.row(i);
  for (int b = 0; b < boundary_size(); ++b) UV.row(p_.fixed_vertices[b]) = UB.row(b);
  return UV;
}

double BoundaryObjective::energy(const MatrixX2d& UV, Eigen::VectorXd* grad) {
  MatrixX2d g;
  const double e = boundary_energy(mesh_.V, mesh_.F, edges_, UV, o_.energy, grad ? &g : nullptr);
  if (!grad || !std::isfinite(e)) return e;
  Eigen::MatrixXd gI(p_.free_vertices.size(), 2);
  for (size_t i = 0; i < p_.free_vertices.size(); ++i) gI.row(i) = g.row(p_.free_vertices[i]);
  Eigen::MatrixXd through;  // (dU_I/dU_B)^T dE/dU_I = -K_IB^T A^{-T} gI
  if (p_.free_vertices.empty()) {
    through = Eigen::MatrixXd::Zero(boundary_size(), 2);
  } else if (o_.route == GradientRoute::Responses) {
    through = -(R_.transpose() * gI);
  } else {
    through = -(K_IB_.transpose() * solver_.solve_transposed(gI));
    ++stats_.solves;
  }
  grad->resize(2 * boundary_size());
  for (int b = 0; b < boundary_size(); ++b)
    grad->segment<2>(2 * b) = (g.row(p_.fixed_vertices[b]) + through.row(b)).transpose();
  return e;
}

BoundaryOptimizationResult optimize_boundary(const Mesh& mesh, const BoundaryOptimizationOptions& o) {
  if (o.max_iterations < 0) throw_usage("the number of iterations must not be negative");
  if (!(o.tolerance >= 0)) throw_usage("the tolerance must not be negative");
  BoundaryOptimizationResult result;
  const auto t_setup = std::chrono::steady_clock::now();
  // Start from the intrinsic map of the chosen boundary at the surface's
  // scale (the energies compare lengths and areas with the 3D ones).
  ParamOptions start = o.base;
  if (start.boundary != BoundaryShape::Given) start.scale = ScaleMode::Surface;
  const MatrixX2d UV0 = parameterize(mesh, start).UV;
  BoundaryObjective map(mesh, o, result);
  Eigen::VectorXd x = map.boundary_of(UV0);
  MatrixX2d UV = map.map(x);
  Eigen::VectorXd g;
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
  double scale_hint = 0;  // first step length for plain gradient steps
  {
    const double diam = (UV.colwise().maxCoeff() - UV.colwise().minCoeff()).norm();
    scale_hint = g.norm() > 0 ? 0.01 * diam / g.norm() : 0;
  }
  result.stop_reason = "iteration limit";
  for (int it = 0; it < o.max_iterations; ++it) {
    if (g.norm() == 0) { result.stop_reason = "zero gradient"; break; }
    // L-BFGS two-loop recursion (or the gradient itself).
    Eigen::VectorXd d = -g;
    double alpha0 = scale_hint;
    if (o.descent == Descent::LBFGS && !S.empty()) {
      std::vector<double> a(S.size());
      Eigen::VectorXd q = g;
      for (int k = static_cast<int>(S.size()) - 1; k >= 0; --k) {
        a[k] = S[k].dot(q) / Y[k].dot(S[k]);
        q -= a[k] * Y[k];
      }
      q *= S.back().dot(Y.back()) / Y.back().squaredNorm();
      for (size_t k = 0; k < S.size(); ++k) q += S[k] * (a[k] - Y[k].dot(q) / Y[k].dot(S[k]));
      d = -q;
      alpha0 = 1;
    }
    if (d.dot(g) >= 0) { d = -g; alpha0 = scale_hint; S.clear(); Y.clear(); }
    // Backtracking: Armijo decrease, no new flips, no boundary crossing.
    double alpha = alpha0, e_new = e;
    Eigen::VectorXd x_new, g_new;
    MatrixX2d UV_new;
    bool accepted = false;
    for (int tries = 0; tries < 50 && !accepted; ++tries, alpha *= 0.5) {
      x_new = x + alpha * d;
      UV_new = map.map(x_new);
      if (count_flips(mesh.F, UV_new) > result.flipped_initial) continue;
      if (!crossing_initial && boundary_crosses(map.segments(), UV_new)) continue;
      e_new = map.energy(UV_new, nullptr);
      if (std::isfinite(e_new) && e_new <= e + 1e-4 * alpha * d.dot(g)) accepted = true;
    }
    if (!accepted) { result.stop_reason = "line search found no admissible decrease"; break; }
    alpha *= 2;  // undo the last halving of the loop
    map.energy(UV_new, &g_new);
    const Eigen::VectorXd s = x_new - x, y = g_new - g;
    if (s.dot(y) > 1e-12 * s.norm() * y.norm()) {
      S.push_back(s);
      Y.push_back(y);
      if (static_cast<int>(S.size()) > o.lbfgs_memory) { S.pop_front(); Y.pop_front(); }
    }
    if (o.descent == Descent::GradientDescent) scale_hint = alpha * 2;  // let plain steps grow back
    const double decrease = (e - e_new) / std::max(e, 1e-300);
    x = x_new;
    g = g_new;
    UV = UV_new;
    e = e_new;
    ++result.iterations;
    result.energy_history.push_back(e);
    if (o.progress) o.progress(result.iterations, e);
    if (decrease < o.tolerance) { result.stop_reason = "relative decrease below tolerance"; break; }
  }
  result.optimize_ms = ms_since(t_opt);
  result.UV = UV;
  result.flipped_final = count_flips(mesh.F, UV);
  return result;
}

}  // namespace intrinsic
