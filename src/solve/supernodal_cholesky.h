// Supernodal Cholesky L L^T of a symmetric positive definite matrix
// (internal), the library's own numeric factorization on CHOLMOD's
// supernodal symbolic analysis (suitesparse.h: supernodal_analysis), using
// both cores: independent subtrees of the elimination tree on separate
// threads, then the top separators split in column blocks
// (supernodal_schedule.h). Left-looking: each supernode gathers the updates
// of its descendants (dsyrk/dgemm), in ascending order of descendant, then
// factors its panel (dpotrf/dtrsm). Row indices are 32-bit.
//
// Solves take several right-hand sides in one sweep (u and v of a map
// together: dtrsm/dgemm on n x 2 blocks), the subtrees again in parallel.
// Results do not depend on the thread count (bit for bit).
#pragma once

#if defined(INTRINSIC_HAVE_SUITESPARSE) && defined(INTRINSIC_HAVE_OPENBLAS)
#define INTRINSIC_HAVE_SUPERNODAL_CHOLESKY 1

#include <memory>

#include "intrinsic/linear_solver.h"

namespace intrinsic::detail {

class SupernodalCholesky {
 public:
  // threads: how many to use; 0 = the machine's cores.
  explicit SupernodalCholesky(int threads = 0);
  ~SupernodalCholesky();
  SupernodalCholesky(const SupernodalCholesky&) = delete;
  SupernodalCholesky& operator=(const SupernodalCholesky&) = delete;
  // False when A is not positive definite (a pivot not above zero) or the
  // analysis fails. A's lower triangle is read; its pattern must be symmetric.
  bool factor(const SparseMatrix& A);
  // A X = B. No refinement here (LinearSolver refines).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  double factor_nonzeros() const;  // stored entries of L (supernodal, with explicit zeros)
  double flops() const;            // of the numeric factorization, counted as CHOLMOD does
  double analyse_ms = 0, factor_ms = 0;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace intrinsic::detail

#endif
