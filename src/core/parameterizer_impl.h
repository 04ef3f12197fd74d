// Parameterizer's kept state, shared with BoundaryEditor (which reads the
// partition, the blocks and the factorization to build impulse responses).
// Internal: not installed, not part of the API.
#pragma once

#include <chrono>
#include <memory>

#include "intrinsic/assemble.h"
#include "intrinsic/error.h"
#include "intrinsic/parameterizer.h"
#include "saddle_solve.h"

namespace intrinsic {
namespace detail {
inline double elapsed_ms(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace detail

struct Parameterizer::Impl {
  const Mesh* mesh = nullptr;
  ParamOptions o;
  int n = 0;  // original vertex count; filled-hole centres come after
  int filled_holes = 0;
  Partition p;
  SparseMatrix A, K_IB;
  std::unique_ptr<LinearSolver> solver;
  Eigen::MatrixXd UB;                // fixed positions, rows in p.fixed_vertices order
  std::vector<FixedVertex> fixed;    // the same as a list
  std::string scale;
  int factorizations = 0, constraint_setups = 0;
  StageTimings timings;

  std::vector<LinearConstraint> rows;
  std::vector<int> active, fixed_only;  // rows with free terms / only fixed terms
  SparseMatrix CB;                      // active rows' terms on fixed vertices
  detail::SaddleSolve saddle;

  bool have_X = false;
  Eigen::MatrixXd X, lambda;

  // Working surface (holes filled), partition, blocks, factorization.
  void build(const std::vector<FixedVertex>& given) {
    const auto t_assemble = std::chrono::steady_clock::now();
    const Topology& t = mesh->topology;
    n = static_cast<int>(mesh->V.rows());
    MatrixX3d V = mesh->V;
    MatrixX3i F = mesh->F;
    std::vector<char> is_fixed(n, 0), is_used(t.is_used.begin(), t.is_used.end());
    for (const FixedVertex& fv : given) is_fixed[fv.vertex] = 1;
    filled_holes = 0;
    if (o.holes == HoleRule::Fill) {
      std::vector<Eigen::Vector3i> fan;
      std::vector<Eigen::Vector3d> centres;
      for (size_t k = 1; k < t.component_loops[0].size(); ++k) {
        const std::vector<int>& loop = t.boundary_loops[t.component_loops[0][k]];
        bool all_fixed = true;
        for (int v : loop) all_fixed = all_fixed && is_fixed[v];
        if (all_fixed) continue;  // the user placed this hole
        Eigen::Vector3d c = Eigen::Vector3d::Zero();
        for (int v : loop) c += mesh->V.row(v).transpose();
        c /= static_cast<double>(loop.size());
        const int centre = n + static_cast<int>(centres.size());
        bool degenerate = false;
        std::vector<Eigen::Vector3i> faces;
        for (size_t i = 0; i < loop.size(); ++i) {
          const int a = loop[i], b = loop[(i + 1) % loop.size()];
          const Eigen::Vector3d xa = mesh->V.row(a), xb = mesh->V.row(b);
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
        filled_holes = static_cast<int>(centres.size());
      }
    }
    const SparseMatrix K = assemble_weight_matrix(V, F, o.weights);
    p = partition(static_cast<int>(V.rows()), is_fixed, is_used);
    split_matrix(K, p, A, K_IB);
    UB.resize(static_cast<int>(p.fixed_vertices.size()), 2);
    for (const FixedVertex& fv : given) UB.row(p.fixed_index[fv.vertex]) = fv.uv.transpose();
    update_fixed_list();
    timings.assemble_ms = detail::elapsed_ms(t_assemble);

    const auto t_factor = std::chrono::steady_clock::now();
    solver = std::make_unique<LinearSolver>(o.solver, is_symmetric(o.weights));
    if (A.rows() > 0) {
      solver->factor(A);
      ++factorizations;
    }
    timings.factor_ms = detail::elapsed_ms(t_factor);
    have_X = false;
  }

  void update_fixed_list() {
    fixed.resize(p.fixed_vertices.size());
    for (size_t k = 0; k < fixed.size(); ++k) fixed[k] = {p.fixed_vertices[k], UB.row(static_cast<int>(k)).transpose()};
  }

  int num_free() const { return static_cast<int>(A.rows()); }

  Eigen::MatrixXd solve_A(const Eigen::MatrixXd& B) const {
    if (B.rows() == 0) return B;
    return solver->solve(B);
  }

  // The solution's free part for right-hand side R (N x k) and active
  // constraint targets T (m x k): linear in both, which is what the
  // boundary editor's responses rely on.
  Eigen::MatrixXd solve_linear(const Eigen::MatrixXd& R, const Eigen::MatrixXd& T, Eigen::MatrixXd* l = nullptr) const {
    return saddle.apply(solve_A(R), T, l);
  }

  Eigen::MatrixXd active_targets() const {
    Eigen::MatrixXd T(static_cast<int>(active.size()), 2);
    for (size_t r = 0; r < active.size(); ++r) T.row(static_cast<int>(r)) = rows[active[r]].target.transpose();
    return T;
  }

  Eigen::MatrixXd solve_for(const Eigen::MatrixXd& ub, Eigen::MatrixXd* l = nullptr) const {
    Eigen::MatrixXd T = active_targets();
    if (T.rows() > 0) T -= CB * ub;
    return solve_linear(-(K_IB * ub), T, l);
  }

  // #V x 2: free vertices from x, fixed from ub, unused at (0, 0); filled
  // centres dropped.
  MatrixX2d full_uv(const Eigen::MatrixXd& x, const Eigen::MatrixXd& ub) const {
    MatrixX2d UV = MatrixX2d::Zero(n, 2);
    for (int v = 0; v < n; ++v) {
      if (p.free_index[v] >= 0) UV.row(v) = x.row(p.free_index[v]);
      else if (p.fixed_index[v] >= 0) UV.row(v) = ub.row(p.fixed_index[v]);
    }
    return UV;
  }

  void check_fixed_only(const Eigen::MatrixXd& ub) const {
    for (int k : fixed_only) {
      const LinearConstraint& c = rows[k];
      Eigen::Vector2d value = Eigen::Vector2d::Zero();
      std::string vertices;
      for (auto [v, w] : c.terms) {
        value += w * ub.row(p.fixed_index[v]).transpose();
        vertices += (vertices.empty() ? "" : ", ") + std::to_string(v);
      }
      const double tol = 1e-9 * std::max(1.0, c.target.cwiseAbs().maxCoeff());
      if ((value - c.target).cwiseAbs().maxCoeff() > tol)
        throw_input(c.label + " lies on fixed boundary vertices only (" + vertices + ") and asks for (" +
                    std::to_string(c.target.x()) + ", " + std::to_string(c.target.y()) +
                    "), but the boundary puts it at (" + std::to_string(value.x()) + ", " +
                    std::to_string(value.y()) + ")");
    }
  }

  void setup_constraints() {
    active.clear();
    fixed_only.clear();
    std::vector<Eigen::Triplet<double>> c_free, c_fixed;
    std::vector<std::string> labels;
    for (size_t k = 0; k < rows.size(); ++k) {
      bool has_free = false;
      for (auto [v, w] : rows[k].terms) has_free = has_free || p.free_index[v] >= 0;
      if (!has_free) { fixed_only.push_back(static_cast<int>(k)); continue; }
      const int r = static_cast<int>(active.size());
      for (auto [v, w] : rows[k].terms) {
        if (p.free_index[v] >= 0) c_free.emplace_back(r, p.free_index[v], w);
        else c_fixed.emplace_back(r, p.fixed_index[v], w);
      }
      active.push_back(static_cast<int>(k));
      labels.push_back(rows[k].label);
    }
    check_fixed_only(UB);
    const int m = static_cast<int>(active.size());
    SparseMatrix C(m, num_free());
    C.setFromTriplets(c_free.begin(), c_free.end());
    CB.resize(m, static_cast<int>(p.fixed_vertices.size()));
    CB.setFromTriplets(c_fixed.begin(), c_fixed.end());
    have_X = false;
    saddle.set([this](const Eigen::MatrixXd& B) { return solve_A(B); }, C, labels);
    if (m > 0) ++constraint_setups;
  }
};

}  // namespace intrinsic
