// Backends of LinearSolver. The supernodal Cholesky and LU, CHOLMOD and UMFPACK get the
// level-set nested dissection ordering (solve/ordering.h) instead of their
// own analysis: CHOLMOD's default tries METIS, which on meshes costs more
// than the factorization it saves, and AMD fills more on large meshes.
#include "solve/linear_solver.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <variant>
#include <vector>

#include "intrinsic/error.h"
#include "intrinsic/choice.h"
#include "util/parallel_for.h"

#ifdef INTRINSIC_HAVE_SUITESPARSE
#include "solve/complex_form.h"
#include "solve/ordering_ahead.h"
#include "solve/suitesparse.h"
#include "solve/supernodal_cholesky.h"
#include "solve/supernodal_lu.h"
#endif

namespace intrinsic {

std::string solver_name(SolverKind k) { return choice_name(k); }

SolverKind parse_solver(const std::string& name) { return parse_solver(name, "solver"); }

SolverKind parse_solver(const std::string& name, std::string_view label) {
  const SolverKind k = parse_choice<SolverKind>(name, label);
  if (!solver_available(k))
    throw_usage("solver '" + name + "' is not available in this build (SuiteSparse was not found)");
  return k;
}

bool solver_available(SolverKind k) {
#if defined(INTRINSIC_HAVE_SUPERNODAL_LU) && defined(INTRINSIC_HAVE_SUPERNODAL_CHOLESKY)
  (void)k;
  return true;
#elif defined(INTRINSIC_HAVE_SUITESPARSE)
  return k != SolverKind::SupernodalLU && k != SolverKind::SupernodalCholesky;
#else
  return k != SolverKind::Cholmod && k != SolverKind::Umfpack && k != SolverKind::SupernodalLU &&
         k != SolverKind::SupernodalCholesky;
#endif
}

namespace {

using EigenLLT = Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>>;
using EigenLU = Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>>;
using CG = Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper, Eigen::DiagonalPreconditioner<double>>;
using BiCG = Eigen::BiCGSTAB<SparseMatrix, Eigen::DiagonalPreconditioner<double>>;
#ifdef INTRINSIC_HAVE_SUITESPARSE
using Cholmod = detail::CholmodFactor;
using Umfpack = detail::UmfpackFactor;
#endif

// Componentwise backward error max_i |r|_i / (|op(A)| |x| + |b|)_i of one
// column x of op(A) X = B (op(A) = A^T when transposed), with r = b - op(A) x
// written: one pass over A for both the residual and the scale.
double column_backward_error(const SparseMatrix& A, bool transposed, const double* x, const double* b, double* r) {
  const Eigen::Index n = A.rows();
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* value = A.valuePtr();
  std::vector<double> scale(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    r[i] = b[i];
    scale[i] = std::abs(b[i]);
  }
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    if (transposed) {  // row j of A^T: a gather, summed in A's storage order
      double rj = r[j], sj = scale[j];
      for (int k = outer[j]; k < outer[j + 1]; ++k) {
        const double t = value[k] * x[inner[k]];
        rj -= t;
        sj += std::abs(t);
      }
      r[j] = rj;
      scale[j] = sj;
    } else {
      const double xj = x[j];
      for (int k = outer[j]; k < outer[j + 1]; ++k) {
        const double t = value[k] * xj;
        r[inner[k]] -= t;
        scale[inner[k]] += std::abs(t);
      }
    }
  }
  double omega = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (scale[i] > 0) omega = std::max(omega, std::abs(r[i]) / scale[i]);
    else if (r[i] != 0 || std::isnan(r[i])) omega = std::numeric_limits<double>::infinity();
  return omega;
}

// The largest column_backward_error over the columns of X, with R = B -
// op(A) X. Large systems have each column on its own thread (the solves
// have two, u and v): a column's sums are in the same order whatever runs
// it, so R and the answer do not depend on the threads. A 1M-vertex
// authalic solve evaluates this twice (one refinement step).
double backward_error(const SparseMatrix& A, bool transposed, const Eigen::MatrixXd& X, const Eigen::MatrixXd& B,
                      Eigen::MatrixXd& R) {
  R.resize(B.rows(), B.cols());
  const Eigen::Index columns = B.cols();
  std::vector<double> omega(columns, 0.0);
  const int parts = A.nonZeros() >= 200000 ? detail::parallel_parts(columns, 1) : 1;
  detail::parallel_for_parts(columns, parts, [&](int, std::int64_t begin, std::int64_t end) {
    for (std::int64_t c = begin; c < end; ++c)
      omega[c] = column_backward_error(A, transposed, X.col(c).data(), B.col(c).data(), R.col(c).data());
  });
  double worst = 0;
  for (double w : omega) worst = std::max(worst, w);
  return worst;
}

}  // namespace

struct LinearSolver::Impl {
  SolverKind requested;
  bool symmetric;
  double tolerance;
  bool ill_conditioned = false;
  bool complex_form = false;
  std::shared_ptr<detail::AnalysisAhead> ahead;  // for the next factor() only
#ifdef INTRINSIC_HAVE_SUITESPARSE
  // Taken from `ahead` by factor() when A's pattern is the one analysed;
  // the first supernodal backend moves from it, so it is reset after use.
  std::unique_ptr<detail::SupernodalSymbolic> analysed_ahead;
#endif
  SparseMatrix A;
  SolverKind used = SolverKind::Auto;
  int factorizations = 0;
  mutable int iterations = 0;
  mutable int refinement_steps = 0;  // of the last complex-form solve
  mutable std::unique_ptr<LinearSolver> transposed;  // lazily, for adjoint solves
  std::unique_ptr<EigenLLT> llt;
  std::unique_ptr<EigenLU> lu;
  std::unique_ptr<CG> cg;
  std::unique_ptr<BiCG> bicg;
#ifdef INTRINSIC_HAVE_SUITESPARSE
  std::unique_ptr<Cholmod> cholmod;
  std::unique_ptr<Umfpack> umfpack;
#endif
#ifdef INTRINSIC_HAVE_SUPERNODAL_LU
  std::unique_ptr<detail::SupernodalLU> slu;
  // Set once a solve found the supernodal LU inaccurate: from then on
  // `umfpack` (built under the mutex) answers every solve.
  mutable std::mutex fallback_mutex;
  mutable std::atomic<bool> fell_back{false};
  mutable std::unique_ptr<Umfpack> fallback;
  Eigen::MatrixXd supernodal_solve(const Eigen::MatrixXd& B, bool transposed) const;
#endif
#ifdef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  std::unique_ptr<detail::SupernodalCholesky> schol;
  Eigen::MatrixXd cholesky_solve(const Eigen::MatrixXd& B) const;
  // The complex form's factor, and the lower triangle of M = K + iB kept for
  // the refinement instead of A (which is then empty; matrix() rebuilds it
  // on request into `rebuilt`).
  std::unique_ptr<detail::ComplexSupernodalCholesky> zchol;
  detail::ComplexSparse M_lower;
  mutable SparseMatrix rebuilt;
  std::unique_ptr<std::once_flag> rebuilt_once = std::make_unique<std::once_flag>();
  Eigen::MatrixXd complex_cholesky_solve(const Eigen::MatrixXd& B) const;

  // The natural map's complex form on our complex supernodal Cholesky,
  // given M's lower triangle only. The real form is freed before the
  // factorization (at 1M vertices 176 MB, twice M's lower triangle) and
  // rebuilt from M only if the factorization fails, for CHOLMOD to try as
  // before. 1: factored; 0: not positive
  // definite; -1: A is not a real form (nothing changed).
  int try_complex_cholesky() {
    {
      detail::ComplexSparse M;
      if (!detail::hermitian_from_real_form(A, M)) return -1;
      detail::ComplexSparse(M.triangularView<Eigen::Lower>()).swap(M_lower);  // assigning would copy it
    }
    SparseMatrix().swap(A);  // frees (Eigen 3.4: assigning an empty matrix keeps the storage)
    zchol = std::make_unique<detail::ComplexSupernodalCholesky>();
    if (zchol->factor(M_lower)) {
      used = SolverKind::SupernodalCholesky;
      return 1;
    }
    zchol.reset();
    A = detail::real_form_from_hermitian(detail::ComplexSparse(M_lower.selfadjointView<Eigen::Lower>()));
    detail::ComplexSparse().swap(M_lower);
    return 0;
  }
#endif

  // Ours for Auto and an explicit choice, the natural map's complex form
  // included (complex_form: L L^H of the n x n Hermitian form). Auto leaves
  // other ill-conditioned systems to CHOLMOD and its long-double refinement.
  // False when A is not positive definite.
  bool try_supernodal_cholesky() {
#ifdef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
    if (complex_form && (requested == SolverKind::Auto || requested == SolverKind::SupernodalCholesky)) {
      const int complex = try_complex_cholesky();
      if (complex >= 0) return complex == 1;
    }
    const bool wanted = requested == SolverKind::SupernodalCholesky ||
                        (requested == SolverKind::Auto && !complex_form && !ill_conditioned);
    if (!wanted) return false;
    schol = std::make_unique<detail::SupernodalCholesky>();
    const bool factored = schol->factor(A, analysed_ahead.get());
    analysed_ahead.reset();  // moved from: a later backend analyses A itself
    if (factored) { used = SolverKind::SupernodalCholesky; return true; }
    schol.reset();
#endif
    return false;
  }

  bool try_cholesky() {
#ifdef INTRINSIC_HAVE_SUITESPARSE
    if (try_supernodal_cholesky()) return true;
    if (requested == SolverKind::SupernodalCholesky) return false;
    if (requested != SolverKind::EigenLLT) {
      cholmod = std::make_unique<Cholmod>();
      const auto structure = complex_form ? detail::Structure::ComplexPairs : detail::Structure::Real;
      if (cholmod->factor(A, structure)) { used = SolverKind::Cholmod; return true; }
      cholmod.reset();
      return false;
    }
#endif
    llt = std::make_unique<EigenLLT>();
    llt->compute(A);
    if (llt->info() == Eigen::Success) { used = SolverKind::EigenLLT; return true; }
    llt.reset();
    return false;
  }

  bool try_lu() {
#ifdef INTRINSIC_HAVE_SUPERNODAL_LU
    // Not for an explicit UMFPACK or Eigen LU; a failed factorization
    // (a pivot that needs pivoting) goes on to UMFPACK.
    if (requested == SolverKind::Auto || requested == SolverKind::SupernodalLU) {
      slu = std::make_unique<detail::SupernodalLU>();
      const bool factored = slu->factor(A, analysed_ahead.get());
      analysed_ahead.reset();
      if (factored) { used = SolverKind::SupernodalLU; return true; }
      slu.reset();
    }
#endif
#ifdef INTRINSIC_HAVE_SUITESPARSE
    if (requested != SolverKind::EigenLU) {
      umfpack = std::make_unique<Umfpack>();
      if (umfpack->factor(A)) { used = SolverKind::Umfpack; return true; }
      umfpack.reset();
      return false;
    }
#endif
    lu = std::make_unique<EigenLU>();
    lu->compute(A);
    if (lu->info() == Eigen::Success) { used = SolverKind::EigenLU; return true; }
    lu.reset();
    return false;
  }
};

LinearSolver::LinearSolver(SolverKind kind, bool symmetric, double tolerance)
    : impl_(std::make_unique<Impl>()) {
  impl_->requested = kind;
  impl_->symmetric = symmetric;
  impl_->tolerance = tolerance;
}
LinearSolver::~LinearSolver() = default;
LinearSolver::LinearSolver(LinearSolver&&) noexcept = default;
LinearSolver& LinearSolver::operator=(LinearSolver&&) noexcept = default;

void LinearSolver::factor(const SparseMatrix& A) { factor(SparseMatrix(A)); }

void LinearSolver::factor(SparseMatrix&& matrix) {
  Impl& s = *impl_;
  // Eigen 3.4's SparseMatrix has no move assignment (std::move copies) and
  // assigning an empty matrix keeps the storage: swaps take the caller's
  // matrix and free the previous one (at 1M vertices the natural map's
  // real form is 168 MB).
  SparseMatrix().swap(s.A);
  s.A.swap(matrix);
  s.A.makeCompressed();
  const SparseMatrix& A = s.A;
  s.transposed.reset();
  s.llt.reset(); s.lu.reset(); s.cg.reset(); s.bicg.reset();
#ifdef INTRINSIC_HAVE_SUITESPARSE
  s.cholmod.reset(); s.umfpack.reset();
#endif
#ifdef INTRINSIC_HAVE_SUPERNODAL_LU
  s.slu.reset(); s.fallback.reset(); s.fell_back = false;
#endif
#ifdef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  s.schol.reset(); s.zchol.reset();
  detail::ComplexSparse().swap(s.M_lower);
  SparseMatrix().swap(s.rebuilt);
  s.rebuilt_once = std::make_unique<std::once_flag>();
#endif
  ++s.factorizations;
#ifdef INTRINSIC_HAVE_SUITESPARSE
  s.analysed_ahead.reset();
  if (const std::shared_ptr<detail::AnalysisAhead> ahead = std::move(s.ahead)) {
    auto analysed = std::make_unique<detail::SupernodalSymbolic>();
    if (ahead->take(A, *analysed)) s.analysed_ahead = std::move(analysed);
  }  // dropped here, its thread joined, whether A matched or not
#endif
  const std::string n = std::to_string(A.rows());
  switch (s.requested) {
    case SolverKind::Auto:
      if (s.symmetric && s.try_cholesky()) return;
      if (s.try_lu()) return;
      throw_numerical("the " + n + "x" + n + " system is singular (sparse LU failed)");
    case SolverKind::Cholmod:
    case SolverKind::EigenLLT:
    case SolverKind::SupernodalCholesky:
      if (!s.symmetric)
        throw_usage("solver '" + solver_name(s.requested) + "' needs a symmetric system; this method's is not (use umfpack, eigen-lu or bicgstab)");
      if (s.try_cholesky()) return;
      throw_numerical("Cholesky factorization failed: the " + n + "x" + n +
                      " system is not positive definite (negative cotangent weights from obtuse angles can cause this; try --solver auto)");
    case SolverKind::Umfpack:
    case SolverKind::EigenLU:
    case SolverKind::SupernodalLU:
      if (s.try_lu()) return;
      throw_numerical("the " + n + "x" + n + " system is singular (sparse LU failed)");
    case SolverKind::CG:
      if (!s.symmetric)
        throw_usage("conjugate gradient needs a symmetric system; this method's is not (use bicgstab)");
      s.cg = std::make_unique<CG>();
      s.cg->setTolerance(s.tolerance);
      s.cg->setMaxIterations(std::max<int>(1000, 10 * static_cast<int>(A.rows())));
      s.cg->compute(s.A);
      s.used = SolverKind::CG;
      return;
    case SolverKind::BiCGSTAB:
      s.bicg = std::make_unique<BiCG>();
      s.bicg->setTolerance(s.tolerance);
      s.bicg->setMaxIterations(std::max<int>(1000, 10 * static_cast<int>(A.rows())));
      s.bicg->compute(s.A);
      s.used = SolverKind::BiCGSTAB;
      return;
  }
}

Eigen::MatrixXd LinearSolver::solve(const Eigen::MatrixXd& B) const {
  const Impl& s = *impl_;
  Eigen::MatrixXd X(B.rows(), B.cols());
  s.iterations = 0;
  s.refinement_steps = 0;
  if (s.llt) X = s.llt->solve(B);
#ifdef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  else if (s.zchol) X = s.complex_cholesky_solve(B);
#endif
  else if (s.lu) X = s.lu->solve(B);
#ifdef INTRINSIC_HAVE_SUITESPARSE
  else if (s.cholmod) X = s.cholmod->solve(B, s.ill_conditioned);
  else if (s.umfpack) X = s.umfpack->solve(B);
#endif
#ifdef INTRINSIC_HAVE_SUPERNODAL_LU
  else if (s.slu) X = s.supernodal_solve(B, false);
#endif
#ifdef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  else if (s.schol) X = s.cholesky_solve(B);
#endif
  else if (s.cg || s.bicg) {
    for (int c = 0; c < B.cols(); ++c) {
      if (s.cg) {
        X.col(c) = s.cg->solve(B.col(c));
        s.iterations = std::max<int>(s.iterations, static_cast<int>(s.cg->iterations()));
      } else {
        X.col(c) = s.bicg->solve(B.col(c));
        s.iterations = std::max<int>(s.iterations, static_cast<int>(s.bicg->iterations()));
      }
    }
  } else {
    throw_numerical("internal: solve called before factor");
  }
  return X;
}

Eigen::MatrixXd LinearSolver::solve_transposed(const Eigen::MatrixXd& B) const {
  const Impl& s = *impl_;
  if (s.symmetric) return solve(B);
  if (s.lu) return s.lu->transpose().solve(B);
#ifdef INTRINSIC_HAVE_SUITESPARSE
  if (s.umfpack) return s.umfpack->solve(B, true);
#endif
#ifdef INTRINSIC_HAVE_SUPERNODAL_LU
  if (s.slu) return s.supernodal_solve(B, true);
#endif
  // Other backends: factor the transpose on first use and keep it.
  if (!s.transposed) {
    s.transposed = std::make_unique<LinearSolver>(s.requested, false, s.tolerance);
    s.transposed->factor(SparseMatrix(s.A.transpose()));
  }
  return s.transposed->solve(B);
}

void LinearSolver::set_ill_conditioned(bool on) { impl_->ill_conditioned = on; }
void LinearSolver::set_complex_form(bool on) { impl_->complex_form = on; }
void LinearSolver::set_analysis_ahead(std::shared_ptr<detail::AnalysisAhead> ahead) {
  impl_->ahead = std::move(ahead);
}

#ifdef INTRINSIC_HAVE_SUPERNODAL_LU
// The supernodal LU's answer, refined while its componentwise backward error
// is above 16 ulps (as CHOLMOD's). Diagonally dominant matrices need no
// step; when three steps leave it above 1e-12 the factorization needed
// pivoting (growth), and UMFPACK factors A and answers this solve and every
// later one.
Eigen::MatrixXd LinearSolver::Impl::supernodal_solve(const Eigen::MatrixXd& B, bool transposed) const {
  if (!fell_back.load(std::memory_order_acquire)) {
    Eigen::MatrixXd X = slu->solve(B, transposed), R;
    double omega = backward_error(A, transposed, X, B, R);
    for (int step = 0; step < 3 && omega > 16 * std::numeric_limits<double>::epsilon(); ++step) {
      X += slu->solve(R, transposed);
      omega = backward_error(A, transposed, X, B, R);
    }
    if (omega <= 1e-12) return X;
    std::lock_guard<std::mutex> lock(fallback_mutex);
    if (!fell_back.load(std::memory_order_relaxed)) {
      auto u = std::make_unique<Umfpack>();
      if (!u->factor(A))
        throw_numerical("the " + std::to_string(A.rows()) + "x" + std::to_string(A.rows()) + " system is singular (sparse LU failed)");
      fallback = std::move(u);
      fell_back.store(true, std::memory_order_release);
    }
  }
  return fallback->solve(B, transposed);
}
#endif

#ifdef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
// The supernodal Cholesky's answer, refined (at most 5 steps, as CHOLMOD's
// default) while its componentwise backward error is above 16 ulps.
Eigen::MatrixXd LinearSolver::Impl::cholesky_solve(const Eigen::MatrixXd& B) const {
  Eigen::MatrixXd X = schol->solve(B), R;
  double omega = backward_error(A, false, X, B, R);
  for (int step = 0; step < 5 && omega > 16 * std::numeric_limits<double>::epsilon(); ++step) {
    X += schol->solve(R);
    omega = backward_error(A, false, X, B, R);
  }
  return X;
}
#endif

#ifdef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
// The complex factor's answer, refined with residuals exact to about twice
// double precision (detail::hermitian_lower_residual; a long-double residual
// left the 1M-vertex map up to 1.2e-11 from its exact solution, see
// docs/performance.md#the-natural-map-a-complex-hermitian-factor).
// The complex form is only the natural map's (two pins: ill-conditioned),
// so it always refines: one step
// always, at most 5. A step multiplies the error by about the relative error
// rho of a solve, which the first correction measures (it is the first
// solve's error; later, the ratio of the last two corrections), so the error
// left after a step is about its correction times rho. Refinement stops when
// that is below an ulp of the solution, or when a correction no longer
// halves (the solution is then as exact as doubles hold it).
Eigen::MatrixXd LinearSolver::Impl::complex_cholesky_solve(const Eigen::MatrixXd& B) const {
  const Eigen::MatrixXcd Bz = detail::complex_from_real_form(B);
  Eigen::MatrixXcd X = zchol->solve(Bz);
  double previous = std::numeric_limits<double>::infinity();
  refinement_steps = 0;
  for (int step = 0; step < 5; ++step) {
    ++refinement_steps;
    const Eigen::MatrixXcd D = zchol->solve(detail::hermitian_lower_residual(M_lower, X, Bz));
    X += D;
    const double size = X.cwiseAbs().maxCoeff(), correction = D.cwiseAbs().maxCoeff() / size;
    const double rho = step == 0 ? correction : correction / previous;
    if (!(size > 0) || !(correction * rho > std::numeric_limits<double>::epsilon()) ||
        !(correction < 0.5 * previous))
      break;
    previous = correction;
  }
  return detail::real_form(X);
}
#endif

Eigen::MatrixXd LinearSolver::multiply(const Eigen::MatrixXd& X) const {
#ifdef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  const Impl& s = *impl_;
  if (s.zchol)
    return detail::real_form(detail::hermitian_lower_product(s.M_lower, detail::complex_from_real_form(X)));
#endif
  return impl_->A * X;
}

SolverKind LinearSolver::kind() const {
#ifdef INTRINSIC_HAVE_SUPERNODAL_LU
  if (impl_->fell_back.load(std::memory_order_acquire)) return SolverKind::Umfpack;
#endif
  return impl_->used;
}
std::string LinearSolver::name() const { return solver_name(kind()); }
int LinearSolver::factorizations() const { return impl_->factorizations; }
int LinearSolver::iterations() const { return impl_->iterations; }
int LinearSolver::refinement_steps() const { return impl_->refinement_steps; }
const SparseMatrix& LinearSolver::matrix() const {
#ifdef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  const Impl& s = *impl_;
  if (s.zchol) {
    std::call_once(*s.rebuilt_once, [&] {
      s.rebuilt = detail::real_form_from_hermitian(detail::ComplexSparse(s.M_lower.selfadjointView<Eigen::Lower>()));
    });
    return s.rebuilt;
  }
#endif
  return impl_->A;
}

// How the command line, Python and the reports spell these (intrinsic/choice.h).
template <>
ChoiceTable<SolverKind> choice_table<SolverKind>() {
  static const Choice<SolverKind> rows[] = {{SolverKind::Auto, "auto"},         {SolverKind::Cholmod, "cholmod"},
                                            {SolverKind::Umfpack, "umfpack"},   {SolverKind::EigenLLT, "eigen-llt"},
                                            {SolverKind::EigenLU, "eigen-lu"},  {SolverKind::CG, "cg"},
                                            {SolverKind::BiCGSTAB, "bicgstab"},
                                            {SolverKind::SupernodalLU, "supernodal-lu"},
                                            {SolverKind::SupernodalCholesky, "supernodal-cholesky"}};
  return make_choice_table(rows);
}

}  // namespace intrinsic
