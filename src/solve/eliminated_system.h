// A sparse system K U = 0 in which some unknowns are known (fixed boundary
// vertices, pins): the one place that partitions the unknowns, splits K into
// A = K_II and K_IB, factors A once, solves for the free unknowns and puts
// the pieces back together (docs/maths.md §2.3). The Parameterizer, the
// boundary editor, the boundary optimizer and the optimal-lambda search all
// solve through it.
#pragma once

#include <memory>
#include <vector>

#include "solve/partition.h"
#include "solve/linear_solver.h"

namespace intrinsic::detail {

class EliminatedSystem {
 public:
  // How A is factored (see LinearSolver).
  struct Factoring {
    SolverKind kind = SolverKind::Auto;
    bool symmetric = true;
    bool ill_conditioned = false;
    bool complex_form = false;  // K is a real form [K' -B; B K'] and the known unknowns come in pairs
    // A's ordering and analysis computed ahead (LinearSolver::set_analysis_ahead), or null.
    std::shared_ptr<AnalysisAhead> analysis_ahead;
  };
  // Partitions the unknowns of K (known where is_known, absent where not
  // is_used) and factors A.
  // K is released once split, before the factorization (peak memory).
  EliminatedSystem(SparseMatrix&& K, const std::vector<char>& is_known, const std::vector<char>& is_used,
                   const Factoring& how);

  const Partition& partition() const { return p_; }
  const SparseMatrix& A() const { return solver_.matrix(); }
  const SparseMatrix& K_IB() const { return K_IB_; }
  int free_count() const { return static_cast<int>(p_.free_vertices.size()); }
  int known_count() const { return static_cast<int>(p_.fixed_vertices.size()); }
  bool factored() const { return factored_; }
  const LinearSolver& solver() const { return solver_; }

  // The right-hand side -K_IB X_B for known values X_B (known_count x k).
  Eigen::MatrixXd rhs(const Eigen::MatrixXd& known) const { return -(K_IB_ * known); }
  // A^{-1} B and A^{-T} B with the kept factorization (B with no rows: B).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  Eigen::MatrixXd solve_transposed(const Eigen::MatrixXd& B) const;
  // max over columns of |A X + extra - B| / |B| (|..| if B = 0).
  double relative_residual(const Eigen::MatrixXd& X, const Eigen::MatrixXd& B, const Eigen::MatrixXd& extra) const;

  // Value of unknown k: from X (free) or X_B (known); 0 when unused.
  double value(int k, const Eigen::MatrixXd& X, const Eigen::MatrixXd& known, int column) const {
    if (p_.free_index[k] >= 0) return X(p_.free_index[k], column);
    if (p_.fixed_index[k] >= 0) return known(p_.fixed_index[k], column);
    return 0.0;
  }

 private:
  Partition p_;
  SparseMatrix K_IB_;  // A = K_II is kept by the solver
  LinearSolver solver_;
  bool factored_ = false;
};

}  // namespace intrinsic::detail
