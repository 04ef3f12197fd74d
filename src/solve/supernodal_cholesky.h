// Supernodal Cholesky L L^T of a symmetric positive definite matrix, or
// L L^H of a Hermitian positive definite one (internal; one algorithm, two
// instantiations: double, and std::complex<double> for the natural map's
// complex form, complex_form.h), the library's own numeric factorization on CHOLMOD's
// supernodal symbolic analysis (suitesparse.h: supernodal_analysis), using
// both cores: independent subtrees of the elimination tree on separate
// threads, then the top separators split in column blocks
// (supernodal_schedule.h). Left-looking: each supernode gathers the updates
// of its descendants (dsyrk/dgemm), in ascending order of descendant, then
// factors its panel (dpotrf/dtrsm; zherk/zgemm/zpotrf/ztrsm with the
// adjoint in the complex case). Row indices are 32-bit.
//
// Solves take several right-hand sides in one sweep (u and v of a map
// together: dtrsm/dgemm on n x 2 blocks), the subtrees again in parallel.
// Results do not depend on the thread count (bit for bit).
#pragma once

#if defined(INTRINSIC_HAVE_SUITESPARSE) && defined(INTRINSIC_HAVE_OPENBLAS)
#define INTRINSIC_HAVE_SUPERNODAL_CHOLESKY 1

#include <complex>
#include <memory>

#include "intrinsic/linear_solver.h"

namespace intrinsic::detail {

template <class T>
class SupernodalCholeskyOf {
 public:
  using Sparse = Eigen::SparseMatrix<T>;
  using Dense = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
  // threads: how many to use; 0 = the machine's cores.
  explicit SupernodalCholeskyOf(int threads = 0);
  ~SupernodalCholeskyOf();
  SupernodalCholeskyOf(const SupernodalCholeskyOf&) = delete;
  SupernodalCholeskyOf& operator=(const SupernodalCholeskyOf&) = delete;
  // False when A is not positive definite (a pivot not above zero) or the
  // analysis fails. A's lower triangle is read. A real A must store both
  // triangles (the ordering reads its graph); a complex (Hermitian) one may
  // store its lower triangle only.
  bool factor(const Sparse& A);
  // A X = B. No refinement here (LinearSolver refines).
  Dense solve(const Dense& B) const;
  double factor_nonzeros() const;  // stored entries of L (supernodal, with explicit zeros)
  // Of the numeric factorization, counted as CHOLMOD does, in real flops
  // (a complex multiply-add is four real ones).
  double flops() const;
  double analyse_ms = 0, factor_ms = 0;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

using SupernodalCholesky = SupernodalCholeskyOf<double>;
using ComplexSupernodalCholesky = SupernodalCholeskyOf<std::complex<double>>;
extern template class SupernodalCholeskyOf<double>;
extern template class SupernodalCholeskyOf<std::complex<double>>;

}  // namespace intrinsic::detail

#endif
