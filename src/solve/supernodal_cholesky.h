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

#include "solve/linear_solver.h"
#include "solve/suitesparse.h"

namespace intrinsic::detail {

// The complex factor's amalgamation, tighter than CHOLMOD's default: chosen
// by nnz(L), flops and numeric time at 300k and 1M vertices
// (docs/performance.md#the-natural-map-a-complex-hermitian-factor;
// complex_cholesky_bench --relax). Up
// to 4 columns always merge (as CHOLMOD's); beyond that only with under 5%
// (up to 32 columns) or 1% explicit zeros. CHOLMOD's up to 16 columns with
// 80% zeros made 13% of L's 83M entries at 1M vertices explicit zeros, for
// no measurable speed.
inline const SupernodeRelaxation kComplexRelaxation = {{4, 4, 32}, {0.8, 0.05, 0.01}};

template <class T>
class SupernodalCholeskyOf {
 public:
  using Sparse = Eigen::SparseMatrix<T>;
  using Dense = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
  // threads: how many to use; 0 = the machine's cores.
  explicit SupernodalCholeskyOf(int threads = 0);
  // The supernode amalgamation of the analysis (suitesparse.h). By default
  // CHOLMOD's for double; tighter for complex entries, which cost 16 bytes
  // each (docs/performance.md#the-natural-map-a-complex-hermitian-factor):
  // kComplexRelaxation.
  void set_relaxation(const SupernodeRelaxation& relax);
  ~SupernodalCholeskyOf();
  SupernodalCholeskyOf(const SupernodalCholeskyOf&) = delete;
  SupernodalCholeskyOf& operator=(const SupernodalCholeskyOf&) = delete;
  // False when A is not positive definite (a pivot not above zero) or the
  // analysis fails. A's lower triangle is read. A real A must store both
  // triangles (the ordering reads its graph); a complex (Hermitian) one may
  // store its lower triangle only.
  // `analysed`: A's analysis computed beforehand with the default
  // relaxation (solve/ordering_ahead.h), moved from; null to analyse A here.
  bool factor(const Sparse& A, SupernodalSymbolic* analysed = nullptr);
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
