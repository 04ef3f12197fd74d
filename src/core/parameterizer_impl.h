// Parameterizer's kept state, shared with BoundaryEditor (which reads the
// partition, the blocks and the factorization to build impulse responses).
// Internal: not installed, not part of the API.
#pragma once

#include <chrono>
#include <memory>

#include "intrinsic/assemble.h"
#include "intrinsic/error.h"
#include "intrinsic/parameterizer.h"
#include "natural_map.h"
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

  // Natural layout (SPEC section 3, natural_map.h): the 2n x 2n system with
  // blocked unknowns (u_v at index v, v_v at n + v) and one right-hand-side
  // column; the partition, A, K_IB, UB (a column) and X are over those 2n
  // unknowns, and each constraint gives a u row and a v row with the same
  // weights (C = blockdiag(C, C)). Used for the natural boundary (the fixed
  // unknowns are the pins) and for natural holes with a conformal term (the
  // fixed unknowns are the outer loop). No holes are filled in this layout.
  bool natural = false;
  bool natural_boundary = false;
  std::vector<FixedVertex> pins;  // natural boundary: the pins as given (or the default pair), before placing

  void build_natural(const std::vector<FixedVertex>& given) {
    const auto t_assemble = std::chrono::steady_clock::now();
    const Topology& t = mesh->topology;
    n = static_cast<int>(mesh->V.rows());
    filled_holes = 0;
    SparseMatrix Q;
    bool symmetric = true;
    if (natural_boundary) {
      Q = assemble_natural_system(*mesh);  // every loop natural
    } else {
      const SparseMatrix K = assemble_weight_matrix(mesh->V, mesh->F, o.weights);
      std::vector<std::vector<int>> holes;
      for (size_t k = 1; k < t.component_loops[0].size(); ++k) holes.push_back(t.boundary_loops[t.component_loops[0][k]]);
      Q = block_diagonal2(K) - natural_hole_weight(o.weights) * area_hessian(n, holes);
      symmetric = is_symmetric(o.weights);
    }
    std::vector<char> fixed2(2 * n, 0), used2(2 * n, 0);
    for (int v = 0; v < n; ++v) used2[v] = used2[n + v] = t.is_used[v];
    for (const FixedVertex& fv : given) fixed2[fv.vertex] = fixed2[n + fv.vertex] = 1;
    p = partition(2 * n, fixed2, used2);
    split_matrix(Q, p, A, K_IB);
    UB.resize(static_cast<int>(p.fixed_vertices.size()), 1);
    for (const FixedVertex& fv : given) set_fixed_uv(UB, fv.vertex, fv.uv);
    update_fixed_list();
    timings.assemble_ms = detail::elapsed_ms(t_assemble);

    const auto t_factor = std::chrono::steady_clock::now();
    solver = std::make_unique<LinearSolver>(o.solver, symmetric);
    solver->set_ill_conditioned(true);  // two pins only
    if (A.rows() > 0) {
      solver->factor(A);
      ++factorizations;
    }
    timings.factor_ms = detail::elapsed_ms(t_factor);
    have_X = false;
  }

  // Position of fixed vertex v in ub (either layout).
  Eigen::Vector2d fixed_uv(const Eigen::MatrixXd& ub, int v) const {
    if (natural) return {ub(p.fixed_index[v], 0), ub(p.fixed_index[n + v], 0)};
    return ub.row(p.fixed_index[v]).transpose();
  }
  void set_fixed_uv(Eigen::MatrixXd& ub, int v, const Eigen::Vector2d& uv) const {
    if (natural) {
      ub(p.fixed_index[v], 0) = uv.x();
      ub(p.fixed_index[n + v], 0) = uv.y();
    } else {
      ub.row(p.fixed_index[v]) = uv.transpose();
    }
  }

  // uv -> scale * uv + offset on the fixed positions and the current solution.
  void place(double scale, const Eigen::RowVector2d& offset) {
    if (!natural) {
      UB = (scale * UB).rowwise() + offset;
      X = (scale * X).rowwise() + offset;
      return;
    }
    for (int k = 0; k < UB.rows(); ++k) UB(k, 0) = scale * UB(k, 0) + offset(p.fixed_vertices[k] >= n ? 1 : 0);
    for (int k = 0; k < X.rows(); ++k) X(k, 0) = scale * X(k, 0) + offset(p.free_vertices[k] >= n ? 1 : 0);
  }

  int free_vertex_count() const { return natural ? num_free() / 2 : num_free(); }
  int fixed_vertex_count() const { return static_cast<int>(fixed.size()); }

  // Working surface (holes filled), partition, blocks, factorization.
  void build(const std::vector<FixedVertex>& given) {
    if (natural) {
      build_natural(given);
      return;
    }
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
    fixed.clear();
    for (int v : p.fixed_vertices)
      if (!natural || v < n) fixed.push_back({v, fixed_uv(UB, v)});
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

  Eigen::MatrixXd solve_for(const Eigen::MatrixXd& ub, Eigen::MatrixXd* l = nullptr) const {
    Eigen::MatrixXd T = active_targets();
    if (T.rows() > 0) T -= CB * ub;
    return solve_linear(-(K_IB * ub), T, l);
  }

  // #V x 2: free vertices from x, fixed from ub, unused at (0, 0); filled
  // centres dropped.
  MatrixX2d full_uv(const Eigen::MatrixXd& x, const Eigen::MatrixXd& ub) const {
    MatrixX2d UV = MatrixX2d::Zero(n, 2);
    if (natural) {
      for (int v = 0; v < n; ++v)
        for (int c = 0; c < 2; ++c) {
          const int k = c * n + v;
          if (p.free_index[k] >= 0) UV(v, c) = x(p.free_index[k], 0);
          else if (p.fixed_index[k] >= 0) UV(v, c) = ub(p.fixed_index[k], 0);
        }
      return UV;
    }
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
        value += w * fixed_uv(ub, v);
        vertices += (vertices.empty() ? "" : ", ") + std::to_string(v);
      }
      const double tol = 1e-9 * std::max(1.0, c.target.cwiseAbs().maxCoeff());
      if ((value - c.target).cwiseAbs().maxCoeff() > tol)
        throw_input(c.label + " lies on " + (natural_boundary ? "pinned" : "fixed boundary") + " vertices only (" +
                    vertices + ") and asks for (" +
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
      active.push_back(static_cast<int>(k));
    }
    // Natural layout: the u rows (over unknowns v), then the v rows (n + v).
    const int m = static_cast<int>(active.size()), blocks = natural ? 2 : 1;
    for (int b = 0; b < blocks; ++b)
      for (int r = 0; r < m; ++r) {
        const LinearConstraint& c = rows[active[r]];
        for (auto [v, w] : c.terms) {
          const int k = b * n + v, row = b * m + r;
          if (p.free_index[k] >= 0) c_free.emplace_back(row, p.free_index[k], w);
          else c_fixed.emplace_back(row, p.fixed_index[k], w);
        }
        labels.push_back(natural ? c.label + (b == 0 ? " (u)" : " (v)") : c.label);
      }
    check_fixed_only(UB);
    SparseMatrix C(blocks * m, num_free());
    C.setFromTriplets(c_free.begin(), c_free.end());
    CB.resize(blocks * m, static_cast<int>(p.fixed_vertices.size()));
    CB.setFromTriplets(c_fixed.begin(), c_fixed.end());
    have_X = false;
    saddle.set([this](const Eigen::MatrixXd& B) { return solve_A(B); }, C, labels);
    if (m > 0) ++constraint_setups;
  }
};

}  // namespace intrinsic
