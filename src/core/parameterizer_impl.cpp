// Parameterizer's solves (docs/maths.md §2.3, §3, §5): right-hand sides from
// the fixed positions, constraints by block elimination, unpacking into
// per-vertex UVs, and the one place a ParamResult is filled.
#include "core/parameterizer_impl.h"

#include <algorithm>

namespace intrinsic {

Eigen::Vector2d Parameterizer::Impl::fixed_uv(const Eigen::MatrixXd& ub, int v) const {
  if (natural) return {ub(p().fixed_index[v], 0), ub(p().fixed_index[n + v], 0)};
  return ub.row(p().fixed_index[v]).transpose();
}

void Parameterizer::Impl::set_fixed_uv(Eigen::MatrixXd& ub, int v, const Eigen::Vector2d& uv) const {
  if (natural) {
    ub(p().fixed_index[v], 0) = uv.x();
    ub(p().fixed_index[n + v], 0) = uv.y();
  } else {
    ub.row(p().fixed_index[v]) = uv.transpose();
  }
}

// uv -> scale * uv + offset on the fixed positions and the current solution.
void Parameterizer::Impl::place(const detail::Similarity& s) {
  if (!natural) {
    UB = (s.scale * UB).rowwise() + s.offset;
    if (have_X) X = (s.scale * X).rowwise() + s.offset;
    return;
  }
  for (int k = 0; k < UB.rows(); ++k) UB(k, 0) = s.scale * UB(k, 0) + s.offset(p().fixed_vertices[k] >= n ? 1 : 0);
  if (have_X)
    for (int k = 0; k < X.rows(); ++k) X(k, 0) = s.scale * X(k, 0) + s.offset(p().free_vertices[k] >= n ? 1 : 0);
}

void Parameterizer::Impl::update_fixed_list() {
  fixed.clear();
  for (int v : p().fixed_vertices)
    if (!natural || v < n) fixed.push_back({v, fixed_uv(UB, v)});
}

// The solution's free part for right-hand side R (N x k) and active
// constraint targets T (m x k): linear in both, which is what the boundary
// editor's responses rely on.
Eigen::MatrixXd Parameterizer::Impl::solve_linear(const Eigen::MatrixXd& R, const Eigen::MatrixXd& T,
                                                  Eigen::MatrixXd* l) const {
  return saddle.apply(sys->solve(R), T, l);
}

Eigen::MatrixXd Parameterizer::Impl::active_targets() const {
  const int m = static_cast<int>(active.size());
  if (natural) {  // u rows, then v rows
    Eigen::MatrixXd T(2 * m, 1);
    for (int r = 0; r < m; ++r) {
      T(r, 0) = rows[active[r]].target.x();
      T(m + r, 0) = rows[active[r]].target.y();
    }
    return T;
  }
  Eigen::MatrixXd T(m, 2);
  for (int r = 0; r < m; ++r) T.row(r) = rows[active[r]].target.transpose();
  return T;
}

Eigen::MatrixXd Parameterizer::Impl::solve_for(const Eigen::MatrixXd& ub, Eigen::MatrixXd* l) const {
  Eigen::MatrixXd T = active_targets();
  if (T.rows() > 0) T -= CB * ub;
  return solve_linear(sys->rhs(ub), T, l);
}

// #V x 2: free vertices from x, fixed from ub, unused at (0, 0); filled
// centres dropped.
MatrixX2d Parameterizer::Impl::full_uv(const Eigen::MatrixXd& x, const Eigen::MatrixXd& ub) const {
  MatrixX2d UV(n, 2);
  for (int v = 0; v < n; ++v)
    for (int c = 0; c < 2; ++c)
      UV(v, c) = natural ? sys->value(c * n + v, x, ub, 0) : sys->value(v, x, ub, c);
  return UV;
}

void Parameterizer::Impl::check_fixed_only(const Eigen::MatrixXd& ub) const {
  for (int k : fixed_only) {
    const LinearConstraint& c = rows[k];
    Eigen::Vector2d value = Eigen::Vector2d::Zero();
    std::string vertices;
    for (auto [v, w] : c.terms) {
      value += w * fixed_uv(ub, v);
      vertices += (vertices.empty() ? "" : ", ") + std::to_string(v);
    }
    const double tol = 1e-9 * std::max(1.0, c.target.cwiseAbs().maxCoeff());
    if ((value - c.target).cwiseAbs().maxCoeff() > tol)
      throw_input(c.label + " lies on " + (natural_boundary ? "pinned" : "fixed boundary") + " vertices only (" +
                  vertices + ") and asks for (" + std::to_string(c.target.x()) + ", " +
                  std::to_string(c.target.y()) + "), but the boundary puts it at (" + std::to_string(value.x()) +
                  ", " + std::to_string(value.y()) + ")");
  }
}

void Parameterizer::Impl::setup_constraints() {
  active.clear();
  fixed_only.clear();
  for (size_t k = 0; k < rows.size(); ++k) {
    const bool has_free = std::any_of(rows[k].terms.begin(), rows[k].terms.end(),
                                      [&](const auto& t) { return p().free_index[t.first] >= 0; });
    (has_free ? active : fixed_only).push_back(static_cast<int>(k));
  }
  // Natural layout: the u rows (over unknowns v), then the v rows (n + v).
  std::vector<Eigen::Triplet<double>> c_free, c_fixed;
  std::vector<std::string> labels;
  const int m = static_cast<int>(active.size()), blocks = natural ? 2 : 1;
  for (int b = 0; b < blocks; ++b)
    for (int r = 0; r < m; ++r) {
      const LinearConstraint& c = rows[active[r]];
      for (auto [v, w] : c.terms) {
        const int k = b * n + v, row = b * m + r;
        if (p().free_index[k] >= 0) c_free.emplace_back(row, p().free_index[k], w);
        else c_fixed.emplace_back(row, p().fixed_index[k], w);
      }
      labels.push_back(natural ? c.label + (b == 0 ? " (u)" : " (v)") : c.label);
    }
  check_fixed_only(UB);
  SparseMatrix C(blocks * m, num_free());
  C.setFromTriplets(c_free.begin(), c_free.end());
  CB.resize(blocks * m, sys->known_count());
  CB.setFromTriplets(c_fixed.begin(), c_fixed.end());
  have_X = false;
  saddle.set([this](const Eigen::MatrixXd& B) { return sys->solve(B); }, C, labels);
  if (m > 0) ++constraint_setups;
}

double Parameterizer::Impl::residual() const {
  Eigen::MatrixXd extra;
  if (saddle.rows() > 0 && lambda.rows() == saddle.rows()) extra = saddle.C().transpose() * lambda;
  return sys->relative_residual(X, sys->rhs(UB), extra);
}

ParamResult Parameterizer::Impl::result() const {
  ParamResult r;
  r.weights = o.weights;
  r.boundary = o.boundary;
  r.spacing = o.spacing;
  r.placement = placement;
  r.holes = holes;
  r.free_vertices = free_vertex_count();
  r.fixed_vertices = static_cast<int>(fixed.size());
  r.filled_holes = filled_holes;
  r.factorizations = factorizations;
  r.timings = timings;
  if (natural_boundary) r.pins = pins;
  if (r.free_vertices > 0) {
    r.solvers = {sys->solver().kind()};
    r.iterations = sys->solver().iterations();
  }
  return r;
}

}  // namespace intrinsic
