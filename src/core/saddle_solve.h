// Lagrange-multiplier constraints on an already factored system (paper
// section 4.1, docs/maths.md §5). The augmented system
//
//   [ A  C^T ] [x]   [r]
//   [ C   0  ] [l] = [t]
//
// is solved by block elimination with A's kept factorization:
//   Z = A^{-1} C^T (m solves, once per constraint set),  S = C Z (m x m, dense),
//   x0 = A^{-1} r,  S l = C x0 - t,  x = x0 - Z l.
// This is the same saddle system (valid for non-symmetric A too), but adding,
// removing or retargeting constraints never refactors the sparse A, and the
// small dense S gives a rank-revealing test that names dependent rows.
//
// It knows nothing of meshes: the fixed-boundary Parameterizer passes the
// eliminated K_II (one matrix, u and v as two right-hand-side columns, C over
// the free vertices); the natural system (2n x 2n, u and v coupled) passes
// its own solve and C = blockdiag(C, C) with one column (parameterizer.h).
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

#include "solve/linear_solver.h"

namespace intrinsic::detail {

class SaddleSolve {
 public:
  using Solve = std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>;

  // Sets the rows C (m x N). Throws Error(Input) naming the likely rows when
  // they are linearly dependent given A (rank test on S).
  void set(const Solve& solve, const SparseMatrix& C, const std::vector<std::string>& labels);
  void clear();
  int rows() const { return static_cast<int>(C_.rows()); }
  const SparseMatrix& C() const { return C_; }

  // x for x0 = A^{-1} r (N x k) and targets T (m x k); the multipliers in
  // *lambda when asked.
  Eigen::MatrixXd apply(const Eigen::MatrixXd& x0, const Eigen::MatrixXd& T, Eigen::MatrixXd* lambda = nullptr) const;

 private:
  SparseMatrix C_;
  Eigen::MatrixXd Z_;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> S_;
};

}  // namespace intrinsic::detail
