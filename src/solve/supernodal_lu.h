// Supernodal LU without pivoting on the Cholesky pattern (internal).
//
// The authalic and mixed systems are not symmetric, but their sparsity
// pattern is the mesh Laplacian's, which is symmetric. An LU without
// pivoting of P^T A P then has L with exactly the pattern of the Cholesky
// factor and U with its transpose, so CHOLMOD's symbolic analysis (its
// supernodes, on the same fill-reducing ordering as the conformal system)
// serves both, and the numeric work is dense BLAS-3 on the same panels:
// twice the Cholesky flops, none of UMFPACK's frontal bookkeeping.
//
// Without pivoting this is stable when A is diagonally dominant (by rows or
// by columns: the growth factor is at most 2), which the authalic matrix is
// when its weights are positive. Other matrices (negative weights from
// obtuse angles, zero diagonals) may hit a tiny pivot, which factor()
// reports, or a large growth, which only a residual shows: LinearSolver
// checks every solve's residual and falls back to UMFPACK (pivoting) when
// iterative refinement cannot bring it to rounding level.
#pragma once

#if defined(INTRINSIC_HAVE_SUITESPARSE) && defined(INTRINSIC_HAVE_OPENBLAS)
#define INTRINSIC_HAVE_SUPERNODAL_LU 1

#include <memory>
#include <vector>

#include "solve/linear_solver.h"

namespace intrinsic::detail {

struct SupernodalSymbolic;  // solve/suitesparse.h

class SupernodalLU {
 public:
  // threads: how many run independent subtrees of the elimination tree
  // (supernodal_schedule.h) and share the column blocks of the wide top
  // supernodes, in the factorization and in the solves; 0 = the machine's
  // cores. The results (factors and solutions) do not depend on it.
  explicit SupernodalLU(int threads = 0);
  ~SupernodalLU();
  SupernodalLU(const SupernodalLU&) = delete;
  SupernodalLU& operator=(const SupernodalLU&) = delete;
  // False when a pivot is zero, not finite or below 1e-14 of the largest
  // entry of its column of A (the matrix needs pivoting). A's pattern must
  // be symmetric (the values need not be): also false when an entry falls
  // outside the factor's pattern or lacks the mirror it is read through.
  // `analysed`: A's analysis computed beforehand (solve/ordering_ahead.h),
  // moved from; null to analyse A here.
  bool factor(const SparseMatrix& A, SupernodalSymbolic* analysed = nullptr);
  // A X = B, or A^T X = B with the same factors. No refinement here.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B, bool transposed = false) const;
  double factor_nonzeros() const;  // stored entries of L and U (supernodal, with their explicit zeros)
  double flops() const;            // of the numeric factorization
  // Top supernodes wide enough to be factored in column blocks shared by
  // the threads (a property of the analysis, not of the thread count).
  int split_supernodes() const;
  // Flops of the top supernodes (after the subtrees), and of those the ones
  // that run on one thread whatever the thread count (narrow supernodes and
  // the LUs of the diagonal blocks): what limits the speedup on 2 cores.
  double top_flops() const;
  double serial_flops() const;
  // L's panels then U's, as stored: for tests that compare factorizations
  // bit for bit.
  std::vector<double> factor_values() const;
  double analyse_ms = 0, factor_ms = 0;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace intrinsic::detail

#endif
