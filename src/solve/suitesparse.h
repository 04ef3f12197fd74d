// Direct calls into CHOLMOD and UMFPACK (internal), through their 64-bit
// index interfaces (the 32-bit UMFPACK runs out of workspace near 3M
// unknowns), with a fill-reducing ordering chosen here rather than by their
// own analysis: CHOLMOD's default analysis tries METIS, which on a 1M mesh
// costs more than the factorization.
#pragma once

#ifdef INTRINSIC_HAVE_SUITESPARSE

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "solve/linear_solver.h"

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

// CHOLMOD's supernodal symbolic analysis of a symmetric pattern on the
// level-set nested dissection ordering, copied out with 32-bit row indices
// (the factor is freed at once): what the library's own numeric
// factorizations (supernodal_cholesky.h, supernodal_lu.h) work on.
// Supernodes are postordered, so each subtree is a contiguous range.
struct SupernodalSymbolic {
  int n = 0, nsuper = 0;
  std::vector<int> perm;             // perm[k]: the row and column of A eliminated k-th
  std::vector<int> super;            // first column of each supernode, and n
  std::vector<std::int64_t> pi, px;  // offsets of each supernode's row indices and values (nsrow x nscol)
  std::vector<int> rows;             // row indices (permuted numbering), supernode by supernode, ascending
  std::vector<int> super_of;         // the supernode of each column
  std::vector<int> parent;           // supernodal elimination tree (-1 at roots)
  double flops = 0, nonzeros = 0;    // CHOLMOD's counts for L's exact pattern (before amalgamation)
  int nscol(int s) const { return super[s + 1] - super[s]; }
  std::int64_t nsrow(int s) const { return pi[s + 1] - pi[s]; }
};
// CHOLMOD's relaxed amalgamation (cholmod_common nrelax, zrelax): a child
// supernode merges into its parent when the merged one has ns columns and
// a fraction z of explicit zeros with ns <= nrelax[0], or ns <= nrelax[1]
// and z < zrelax[0], or ns <= nrelax[2] and z < zrelax[1], or z < zrelax[2].
// Larger supernodes run faster BLAS but store and multiply the zeros. The
// default is CHOLMOD's; the complex factor chooses a tighter one
// (supernodal_cholesky.h).
struct SupernodeRelaxation {
  std::size_t nrelax[3] = {4, 16, 48};
  double zrelax[3] = {0.8, 0.1, 0.05};
};
// False when CHOLMOD cannot (out of memory); A must be compressed and its
// pattern symmetric (of each pair (i, j), (j, i) the entry read is the one
// below the diagonal of the permuted matrix). A 0 x 0 matrix gives no
// supernodes.
bool supernodal_analysis(const SparseMatrix& A, SupernodalSymbolic& out, const SupernodeRelaxation& relax = {});
// The same on a permutation computed beforehand (order[k]: the row and
// column of A eliminated k-th, e.g. level_set_nested_dissection(A) computed
// while something else ran); CHOLMOD may postorder it, so out.perm is the
// permutation to use.
bool supernodal_analysis(const SparseMatrix& A, const std::vector<int>& order, SupernodalSymbolic& out,
                         const SupernodeRelaxation& relax = {});

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
