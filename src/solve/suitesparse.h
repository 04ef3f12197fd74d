// Direct calls into CHOLMOD and UMFPACK (internal), through their 64-bit
// index interfaces (the 32-bit UMFPACK runs out of workspace near 3M
// unknowns), with a fill-reducing ordering chosen here rather than by their
// own analysis: CHOLMOD's default analysis tries METIS, which on a 1M mesh
// costs more than the factorization.
#pragma once

#ifdef INTRINSIC_HAVE_SUITESPARSE

#include <memory>
#include <string>
#include <vector>

#include "intrinsic/linear_solver.h"

namespace intrinsic::detail {

enum class Ordering {
  NestedDissection,  // level_set_nested_dissection (default)
  AMD,               // the library's own approximate minimum degree
  METIS,             // METIS node nested dissection (CHOLMOD only)
};
std::string ordering_name(Ordering o);

// What CholmodFactor factors.
enum class Structure {
  Real,          // the matrix as given
  ComplexPairs,  // its complex Hermitian form when it is [K -B; B K] (complex_form.h), else as given
};

// Supernodal Cholesky of a symmetric positive definite matrix (both
// triangles stored; the lower one is used).
class CholmodFactor {
 public:
  explicit CholmodFactor(Ordering ordering = Ordering::NestedDissection);
  ~CholmodFactor();
  CholmodFactor(const CholmodFactor&) = delete;
  CholmodFactor& operator=(const CholmodFactor&) = delete;
  // False when A is not positive definite. A must outlive the solves (they
  // refine with it).
  bool factor(const SparseMatrix& A, Structure structure = Structure::Real);
  bool complex() const;  // the complex form was factored
  double flops() const;  // of the numeric factorization, from the analysis
  // refine_always: iterative refinement until the correction is negligible
  // (ill-conditioned systems); otherwise only when the backward error is
  // above rounding level.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B, bool refine_always = false) const;
  double factor_nonzeros() const;  // nnz(L)
  double analyse_ms = 0, factor_ms = 0;  // split of factor(), for the bench

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Sparse LU with the symmetric strategy (diagonal pivots preferred, the
// ordering applied to rows and columns alike).
class UmfpackFactor {
 public:
  explicit UmfpackFactor(Ordering ordering = Ordering::NestedDissection);
  ~UmfpackFactor();
  UmfpackFactor(const UmfpackFactor&) = delete;
  UmfpackFactor& operator=(const UmfpackFactor&) = delete;
  // False when A is singular.
  bool factor(const SparseMatrix& A);
  // A X = B, or A^T X = B with the same factors.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B, bool transposed = false) const;
  double factor_nonzeros() const;  // nnz(L) + nnz(U)
  double flops() const;            // of the numeric factorization, as UMFPACK counts them
  double analyse_ms = 0, factor_ms = 0;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace intrinsic::detail

#endif
