// Elimination of known unknowns and the kept factorization (docs/maths.md
// §2.3): K_II x = -K_IB x_B.
#include "solve/eliminated_system.h"

#include <algorithm>

namespace intrinsic::detail {

EliminatedSystem::EliminatedSystem(SparseMatrix&& K, const std::vector<char>& is_known,
                                   const std::vector<char>& is_used, const Factoring& how)
    : solver_(how.kind, how.symmetric) {
  p_ = intrinsic::partition(static_cast<int>(K.rows()), is_known, is_used);
  SparseMatrix A;
  split_matrix(K, p_, A, K_IB_);
  SparseMatrix().swap(K);  // frees it (Eigen 3.4: assigning an empty matrix keeps the storage)
  solver_.set_ill_conditioned(how.ill_conditioned);
  // The free unknowns keep K's order, u's before v's: with u and v of a
  // vertex known together, A is again a real form.
  solver_.set_complex_form(how.complex_form);
  solver_.set_analysis_ahead(how.analysis_ahead);
  if (A.rows() > 0) {
    solver_.factor(std::move(A));
    factored_ = true;
  }
}

Eigen::MatrixXd EliminatedSystem::solve(const Eigen::MatrixXd& B) const {
  if (B.rows() == 0) return B;
  return solver_.solve(B);
}

Eigen::MatrixXd EliminatedSystem::solve_transposed(const Eigen::MatrixXd& B) const {
  if (B.rows() == 0) return B;
  return solver_.solve_transposed(B);
}

double EliminatedSystem::relative_residual(const Eigen::MatrixXd& X, const Eigen::MatrixXd& B,
                                           const Eigen::MatrixXd& extra) const {
  Eigen::MatrixXd res = solver_.multiply(X) - B;  // A() would rebuild the natural map's real form
  if (extra.size() > 0) res += extra;
  double worst = 0;
  for (int c = 0; c < res.cols(); ++c) {
    const double b = B.col(c).norm(), e = res.col(c).norm();
    worst = std::max(worst, b > 0 ? e / b : e);
  }
  return worst;
}

}  // namespace intrinsic::detail
