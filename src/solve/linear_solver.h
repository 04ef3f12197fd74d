// One sparse linear solver behind a small interface (internal; the public
// choice of backend is intrinsic/solver_kind.h): factor once, solve many
// right-hand sides (u and v together). Backends: our supernodal Cholesky on
// CHOLMOD's analysis (both cores), CHOLMOD supernodal Cholesky,
// a supernodal LU without pivoting on CHOLMOD's analysis (for the
// non-symmetric systems, whose pattern is still symmetric; checked by the
// residual, UMFPACK when it fails) and UMFPACK LU when SuiteSparse is built
// in, Eigen's simplicial Cholesky and SparseLU otherwise, and the paper's
// iterative choices (conjugate gradient for the symmetric conformal system,
// BiCGSTAB for the rest, both with a diagonal preconditioner) on request.
#pragma once

#include <Eigen/Sparse>
#include <memory>
#include <string>
#include <string_view>

#include "intrinsic/solver_kind.h"

namespace intrinsic {
namespace detail {
class AnalysisAhead;  // src/solve/ordering_ahead.h (internal)
}

using SparseMatrix = Eigen::SparseMatrix<double>;  // column-major, int indices

class LinearSolver {
 public:
  // `symmetric` says the matrix is symmetric (Cholesky applies if it is also
  // positive definite; Auto falls back to LU when Cholesky fails).
  LinearSolver(SolverKind kind, bool symmetric, double iterative_tolerance = 1e-12);
  ~LinearSolver();
  LinearSolver(LinearSolver&&) noexcept;
  LinearSolver& operator=(LinearSolver&&) noexcept;

  // Throws Error(Numerical) when the matrix is singular (or not positive
  // definite for an explicit Cholesky choice).
  void factor(const SparseMatrix& A);
  // The same, taking A over (no copy: the 1M-vertex natural system is 170 MB).
  void factor(SparseMatrix&& A);
  // Solves A X = B column by column with the kept factorization.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  // Solves A^T X = B (adjoint gradients); same factorization.
  Eigen::MatrixXd solve_transposed(const Eigen::MatrixXd& B) const;

  // Iterative refinement (CHOLMOD; docs/maths.md §10). By default a
  // CHOLMOD solve refines, at most 5 steps, only while the componentwise
  // backward error max_i |B - A X|_i / (|A| |X| + |B|)_i exceeds 16 ulps.
  // Declaring the system ill-conditioned (the natural map's, with only two
  // pinned vertices) makes every solve refine with residuals accumulated in
  // long double, at least one step and at most 5, stopping when the
  // correction is below 1e-12 of the solution or no longer halves.
  // The supernodal LU refines (at most 3 steps) while that backward error
  // exceeds 16 ulps, whatever this flag says. The supernodal Cholesky
  // refines (at most 5 steps) while it exceeds 16 ulps; on the complex form
  // it always refines, whatever this flag says (the complex form is only the
  // natural map's), with residuals exact to about twice double precision, at
  // least one step and at most 5, until the error left is below an ulp
  // (refinement_steps() counts them).
  // UMFPACK, Eigen's solvers and the iterative ones do not refine.
  void set_ill_conditioned(bool on);

  // Declares the matrix the real form [K -B; B K] of a Hermitian matrix
  // K + iB (the natural map's system in blocked ordering, docs/maths.md
  // §3.6). The supernodal Cholesky (Auto) and CHOLMOD then factor the
  // complex n x n form: half the unknowns to order and analyse and fewer
  // flops than the real 2n x 2n matrix. Solves still take and return the
  // real form. Checked exactly at factor(); a matrix without that structure
  // is factored as given. Other backends ignore it. The supernodal Cholesky
  // keeps only the complex form's lower triangle, not A (matrix() then
  // rebuilds A on first call; multiply() needs no rebuild).
  void set_complex_form(bool on);

  // An ordering and symbolic analysis of A's pattern computed ahead (on
  // another thread while A's values were assembled; internal,
  // src/solve/ordering_ahead.h). The next factor() gives it to the
  // supernodal backends, which use it when A's pattern is exactly the one
  // analysed and analyse A themselves otherwise: the factor is the same bit
  // for bit either way. Other backends ignore it.
  void set_analysis_ahead(std::shared_ptr<detail::AnalysisAhead> ahead);

  SolverKind kind() const;        // the backend actually used (never Auto after factor)
  std::string name() const;       // solver_name(kind())
  int factorizations() const;     // how many numeric factorizations so far
  int iterations() const;         // last iterative solve, 0 for direct
  int refinement_steps() const;   // last solve's refinement steps (complex form only; 0 otherwise)
  const SparseMatrix& matrix() const;
  // A X with the factored matrix A (a residual check), from the complex
  // form when A itself was not kept.
  Eigen::MatrixXd multiply(const Eigen::MatrixXd& X) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace intrinsic
