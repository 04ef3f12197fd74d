// CHOLMOD and UMFPACK through their C interfaces with 64-bit indices and a
// given ordering (see suitesparse.h).
#include "solve/suitesparse.h"

#ifdef INTRINSIC_HAVE_SUITESPARSE

#include <cholmod.h>
#include <umfpack.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>

#include "intrinsic/error.h"
#include "solve/complex_form.h"
#include "solve/ordering.h"
#include "solve/solver_threads.h"
#include "util/parallel_for.h"
#include "util/stopwatch.h"

namespace intrinsic::detail {
namespace {

using Long = SuiteSparse_long;

// 64-bit copies of a compressed matrix's index arrays.
struct LongPattern {
  std::vector<Long> p, i;
  LongPattern() = default;
  template <typename Matrix>
  explicit LongPattern(const Matrix& A)
      : p(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1),
        i(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros()) {}
};

SparseMatrix compressed(const SparseMatrix& A) {
  SparseMatrix C = A;
  C.makeCompressed();
  return C;
}

// CHOLMOD's view of a compressed symmetric (Hermitian) matrix, lower triangle used.
cholmod_sparse symmetric_view(Long n, Long nonzeros, LongPattern& pattern, const void* values, int xtype) {
  cholmod_sparse cs{};
  cs.nrow = cs.ncol = n;
  cs.nzmax = nonzeros;
  cs.p = pattern.p.data();
  cs.i = pattern.i.data();
  cs.x = const_cast<void*>(values);
  cs.stype = -1;
  cs.itype = CHOLMOD_LONG;
  cs.xtype = xtype;
  cs.dtype = CHOLMOD_DOUBLE;
  cs.sorted = 1;
  cs.packed = 1;
  return cs;
}

// The lower triangle of P A P^T (column k of it is column order[k] of A),
// rows sorted: CHOLMOD's analysis of it in its natural order is its
// analysis of A on `order`, without CHOLMOD's own permuting transposes of
// the whole matrix (scattered reads: 60% of its analysis at 1M vertices).
// Both passes split the columns over the cores.
LongPattern permuted_lower(const SparseMatrix& A, const std::vector<int>& order) {
  const int n = static_cast<int>(A.rows());
  std::vector<int> position(n);
  for (int k = 0; k < n; ++k) position[order[k]] = k;
  LongPattern C;
  C.p.assign(n + 1, 0);
  const int* Ap = A.outerIndexPtr();
  const int* Ai = A.innerIndexPtr();
  parallel_for(n, [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t k = begin; k < end; ++k) {
      const int j = order[k];
      Long count = 0;
      for (int q = Ap[j]; q < Ap[j + 1]; ++q) count += position[Ai[q]] >= k;
      C.p[k + 1] = count;
    }
  });
  for (int k = 0; k < n; ++k) C.p[k + 1] += C.p[k];
  C.i.resize(static_cast<size_t>(C.p[n]));
  parallel_for(n, [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t k = begin; k < end; ++k) {
      const int j = order[k];
      Long* out = C.i.data() + C.p[k];
      Long* last = out;
      for (int q = Ap[j]; q < Ap[j + 1]; ++q)
        if (position[Ai[q]] >= k) *last++ = position[Ai[q]];
      std::sort(out, last);
    }
  });
  return C;
}

}  // namespace

// The analysis the library's own numeric factorizations share (see the
// header): CHOLMOD's supernodes, relaxed amalgamation and postorder on the
// ordering the conformal system gets.
bool supernodal_analysis(const SparseMatrix& A, SupernodalSymbolic& out, const SupernodeRelaxation& relax) {
  return supernodal_analysis(A, A.rows() == 0 ? std::vector<int>() : level_set_nested_dissection(A), out, relax);
}

bool supernodal_analysis(const SparseMatrix& A, const std::vector<int>& order, SupernodalSymbolic& out,
                         const SupernodeRelaxation& relax) {
  out = SupernodalSymbolic();
  const int n = static_cast<int>(A.rows());
  out.n = n;
  out.super = {0};
  out.pi = out.px = {0};
  if (n == 0) return true;
  if (static_cast<int>(order.size()) != n)
    throw_numerical("internal: supernodal analysis given a permutation of the wrong size");
  LongPattern pattern = permuted_lower(A, order);
  cholmod_common c;
  cholmod_l_start(&c);
  c.supernodal = CHOLMOD_SUPERNODAL;
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_NATURAL;  // the order is the pattern's own
  c.postorder = 1;
  c.print = 0;
  for (int k = 0; k < 3; ++k) {
    c.nrelax[k] = relax.nrelax[k];
    c.zrelax[k] = relax.zrelax[k];
  }
  cholmod_sparse cs = symmetric_view(n, static_cast<Long>(pattern.i.size()), pattern, nullptr, CHOLMOD_PATTERN);
  cholmod_factor* L = cholmod_l_analyze(&cs, &c);
  if (!L || !L->is_super) {
    if (L) cholmod_l_free_factor(&L, &c);
    cholmod_l_finish(&c);
    return false;
  }
  const int nsuper = static_cast<int>(L->nsuper);
  const Long* Lsuper = static_cast<const Long*>(L->super);
  const Long* Lpi = static_cast<const Long*>(L->pi);
  const Long* Lpx = static_cast<const Long*>(L->px);
  const Long* Ls = static_cast<const Long*>(L->s);
  const Long* Lperm = static_cast<const Long*>(L->Perm);
  out.nsuper = nsuper;
  out.super.assign(Lsuper, Lsuper + nsuper + 1);
  out.pi.assign(Lpi, Lpi + nsuper + 1);
  out.px.assign(Lpx, Lpx + nsuper + 1);
  out.rows.assign(Ls, Ls + out.pi[nsuper]);
  out.perm.resize(n);  // CHOLMOD's postorder of the pattern's columns, in A's numbering
  for (int k = 0; k < n; ++k) out.perm[k] = order[Lperm[k]];
  out.flops = c.fl;
  out.nonzeros = c.lnz;
  cholmod_l_free_factor(&L, &c);
  cholmod_l_finish(&c);
  out.super_of.resize(n);
  out.parent.assign(nsuper, -1);
  for (int s = 0; s < nsuper; ++s) {
    for (int k = out.super[s]; k < out.super[s + 1]; ++k) out.super_of[k] = s;
  }
  for (int s = 0; s < nsuper; ++s)
    if (out.nsrow(s) > out.nscol(s)) out.parent[s] = out.super_of[out.rows[out.pi[s] + out.nscol(s)]];
  return true;
}

std::string ordering_name(Ordering o) {
  switch (o) {
    case Ordering::NestedDissection: return "nested-dissection";
    case Ordering::AMD: return "amd";
    case Ordering::METIS: return "metis";
  }
  return "?";
}

struct CholmodFactor::Impl {
  Ordering ordering;
  cholmod_common c;
  cholmod_factor* L = nullptr;
  const SparseMatrix* A = nullptr;  // the caller's, for refinement
  bool complex = false;             // L factors the complex form of A
  SparseMatrix abs_A;               // |A|, for the componentwise backward error
  std::unique_ptr<std::once_flag> abs_A_once = std::make_unique<std::once_flag>();
  Long n = 0;                       // L's size
  explicit Impl(Ordering o) : ordering(o) {
    cholmod_l_start(&c);
    c.supernodal = CHOLMOD_SUPERNODAL;
    c.nmethods = 1;
    c.postorder = 1;
    c.final_ll = 1;
    c.print = 0;
  }
  ~Impl() {
    if (L) cholmod_l_free_factor(&L, &c);
    cholmod_l_finish(&c);
  }
};

CholmodFactor::CholmodFactor(Ordering ordering) : impl_(std::make_unique<Impl>(ordering)) {}
CholmodFactor::~CholmodFactor() = default;

// Chooses CHOLMOD's ordering: the level-set dissection of `pattern` given,
// or CHOLMOD's own AMD or METIS. Returns the given permutation (empty if none).
std::vector<Long> choose_ordering(Ordering ordering, const SparseMatrix& pattern, cholmod_common& c) {
  c.nmethods = 1;
  switch (ordering) {
    case Ordering::NestedDissection: {
      // The refined dissection fills less than AMD on the generated disks and
      // on scanned meshes (max-planck: nnz(L) 30.0M against AMD's 33.0M;
      // METIS 21.1M, at several times the ordering cost), so CHOLMOD is not
      // asked to try AMD beside it.
      c.method[0].ordering = CHOLMOD_GIVEN;
      const std::vector<int> p = level_set_nested_dissection(pattern);
      return std::vector<Long>(p.begin(), p.end());
    }
    case Ordering::AMD: c.method[0].ordering = CHOLMOD_AMD; break;
    case Ordering::METIS: c.method[0].ordering = CHOLMOD_METIS; break;
  }
  return {};
}

bool CholmodFactor::factor(const SparseMatrix& input, Structure structure) {
  Impl& s = *impl_;
  if (s.L) cholmod_l_free_factor(&s.L, &s.c);
  const auto t0 = std::chrono::steady_clock::now();
  const SparseMatrix copy = input.isCompressed() ? SparseMatrix() : compressed(input);
  const SparseMatrix& A = input.isCompressed() ? input : copy;
  s.A = &input;
  SparseMatrix().swap(s.abs_A);  // frees it: assigning an empty SparseMatrix keeps the storage (Eigen 3.4)
  s.abs_A_once = std::make_unique<std::once_flag>();
  ComplexSparse M;
  s.complex = structure == Structure::ComplexPairs && hermitian_from_real_form(A, M);
  s.n = s.complex ? M.rows() : A.rows();
  std::vector<Long> perm =
      s.complex ? choose_ordering(s.ordering, SparseMatrix(M.cwiseAbs()), s.c) : choose_ordering(s.ordering, A, s.c);
  if (s.complex) M = ComplexSparse(M.triangularView<Eigen::Lower>());  // all CHOLMOD reads; half the memory
  LongPattern pattern = s.complex ? LongPattern(M) : LongPattern(A);
  cholmod_sparse cs = s.complex ? symmetric_view(s.n, M.nonZeros(), pattern, M.valuePtr(), CHOLMOD_COMPLEX)
                                : symmetric_view(s.n, A.nonZeros(), pattern, A.valuePtr(), CHOLMOD_REAL);
  s.L = cholmod_l_analyze_p(&cs, perm.empty() ? nullptr : perm.data(), nullptr, 0, &s.c);
  if (!s.L) throw_numerical("CHOLMOD analysis failed (status " + std::to_string(s.c.status) + ")");
  analyse_ms = ms_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  int ok;
  {
    SolverThreads threads;
    ok = cholmod_l_factorize(&cs, s.L, &s.c);
  }
  factor_ms = ms_since(t1);
  if (!ok && s.c.status != CHOLMOD_NOT_POSDEF)
    throw_numerical("CHOLMOD factorization failed (status " + std::to_string(s.c.status) + ", out of memory?)");
  if (s.c.status == CHOLMOD_NOT_POSDEF || s.L->minor < static_cast<size_t>(s.n)) {
    cholmod_l_free_factor(&s.L, &s.c);
    return false;
  }
  return true;
}

namespace {

// A X = B with the factor L, B given (and X returned) in the real form; a
// complex factor solves the complex form (complex_form.h).
Eigen::MatrixXd cholmod_solve(cholmod_factor* L, cholmod_common& c, bool complex, const Eigen::MatrixXd& B) {
  const Eigen::MatrixXcd Z = complex ? complex_from_real_form(B) : Eigen::MatrixXcd();
  cholmod_dense b{};
  b.nrow = complex ? Z.rows() : B.rows();
  b.ncol = B.cols();
  b.nzmax = b.nrow * b.ncol;
  b.d = b.nrow;
  b.x = complex ? static_cast<void*>(const_cast<std::complex<double>*>(Z.data()))
                : static_cast<void*>(const_cast<double*>(B.data()));
  b.xtype = complex ? CHOLMOD_COMPLEX : CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* x = cholmod_l_solve(CHOLMOD_A, L, &b, &c);
  if (!x) throw_numerical("CHOLMOD solve failed (status " + std::to_string(c.status) + ")");
  Eigen::MatrixXd X;
  if (complex) {
    X = real_form(Eigen::Map<const Eigen::MatrixXcd>(static_cast<std::complex<double>*>(x->x), b.nrow, b.ncol));
  } else {
    X = Eigen::Map<const Eigen::MatrixXd>(static_cast<double*>(x->x), b.nrow, b.ncol);
  }
  cholmod_l_free_dense(&x, &c);
  return X;
}

// B - A X with each row's sum accumulated in long double (64-bit mantissa on
// x86), then rounded once.
Eigen::MatrixXd extended_residual(const SparseMatrix& A, const Eigen::MatrixXd& X, const Eigen::MatrixXd& B) {
  Eigen::MatrixXd R(B.rows(), B.cols());
  std::vector<long double> r(static_cast<size_t>(B.rows()));
  for (Eigen::Index c = 0; c < B.cols(); ++c) {
    for (Eigen::Index i = 0; i < B.rows(); ++i) r[i] = B(i, c);
    for (int j = 0; j < A.outerSize(); ++j) {
      const long double x = X(j, c);
      for (SparseMatrix::InnerIterator it(A, j); it; ++it) r[it.row()] -= static_cast<long double>(it.value()) * x;
    }
    for (Eigen::Index i = 0; i < B.rows(); ++i) R(i, c) = static_cast<double>(r[i]);
  }
  return R;
}

}  // namespace

Eigen::MatrixXd CholmodFactor::solve(const Eigen::MatrixXd& B, bool refine_always) const {
  Impl& s = *impl_;
  if (!s.L) throw_numerical("internal: CHOLMOD solve before factor");
  SolverThreads threads;  // the triangular solves' BLAS calls are small
  Eigen::MatrixXd X = cholmod_solve(s.L, s.c, s.complex, B);
  // Iterative refinement. Fixed-boundary systems: only while the
  // componentwise backward error max_i |B - A X|_i / (|A| |X| + |B|)_i is
  // above a few ulps (each step costs a product and a full solve, 0.3 s at
  // 1M vertices); componentwise, because maps that squeeze most of a mesh
  // into a tiny region (the bunny with free holes) need the small
  // coordinates accurate too, or their flip counts move. Ill-conditioned
  // systems (the natural map's, two pinned vertices): a plain solve is only
  // good to about 1e-9 relative at 100k vertices although its backward error
  // is at rounding level. There the residual is accumulated in long double
  // (mixed-precision refinement: each step then gains about what the
  // conditioning costs, instead of stalling at cond * eps), one step always
  // and more while the correction keeps shrinking (below).
  const SparseMatrix& A = *s.A;
  double previous_correction = std::numeric_limits<double>::infinity();
  for (int step = 0; step < 5; ++step) {
    const Eigen::MatrixXd R = refine_always ? extended_residual(A, X, B) : Eigen::MatrixXd(B - A * X);
    if (!refine_always) {
      std::call_once(*s.abs_A_once, [&] { s.abs_A = A.cwiseAbs(); });  // once per factorization
      const Eigen::MatrixXd scale = s.abs_A * X.cwiseAbs() + B.cwiseAbs();
      double omega = 0;
      for (Eigen::Index k = 0; k < R.size(); ++k)
        if (scale.data()[k] > 0) omega = std::max(omega, std::abs(R.data()[k]) / scale.data()[k]);
      if (!(omega > 16 * std::numeric_limits<double>::epsilon())) break;
    }
    const Eigen::MatrixXd D = cholmod_solve(s.L, s.c, s.complex, R);
    X += D;
    if (refine_always) {
      // Stop below 1e-12 of X, or when a step no longer halves the
      // correction: it has reached the noise of the solves (about 1e-12 at
      // 300k vertices; the next correction measured there was 2.3e-12 after
      // 7.9e-13, i.e. noise) and further steps only cost a complex solve
      // each. Each step shrinks the error by about the ratio of successive
      // corrections (1e-3 to 1e-4 here), so X after a correction below
      // 1e-12 is far within the natural map's 1e-11 accuracy budget.
      const double correction = D.cwiseAbs().maxCoeff() / X.cwiseAbs().maxCoeff();
      if (!(correction > 1e-12) || !(correction < 0.5 * previous_correction)) break;
      previous_correction = correction;
    }
  }
  return X;
}

bool CholmodFactor::complex() const { return impl_->complex; }

// CHOLMOD counts the flops of the real factorization on L's pattern; a
// complex multiply-add is four real ones.
double CholmodFactor::flops() const { return impl_->L ? impl_->c.fl * (impl_->complex ? 4 : 1) : 0; }

double CholmodFactor::factor_nonzeros() const {
  return impl_->L ? impl_->c.lnz : 0;
}

struct UmfpackFactor::Impl {
  Ordering ordering;
  SparseMatrix A;
  std::vector<Long> p, i;
  void* numeric = nullptr;
  double control[UMFPACK_CONTROL], info[UMFPACK_INFO];
  explicit Impl(Ordering o) : ordering(o) { umfpack_dl_defaults(control); }
  ~Impl() {
    if (numeric) umfpack_dl_free_numeric(&numeric);
  }
};

UmfpackFactor::UmfpackFactor(Ordering ordering) : impl_(std::make_unique<Impl>(ordering)) {}
UmfpackFactor::~UmfpackFactor() = default;

bool UmfpackFactor::factor(const SparseMatrix& input) {
  Impl& s = *impl_;
  if (s.numeric) umfpack_dl_free_numeric(&s.numeric);
  const auto t0 = std::chrono::steady_clock::now();
  s.A = input;
  s.A.makeCompressed();
  s.p.assign(s.A.outerIndexPtr(), s.A.outerIndexPtr() + s.A.cols() + 1);
  s.i.assign(s.A.innerIndexPtr(), s.A.innerIndexPtr() + s.A.nonZeros());
  const Long n = s.A.rows();
  // Mesh matrices have a symmetric pattern and a strong diagonal: the
  // symmetric strategy keeps the ordering's fill.
  s.control[UMFPACK_STRATEGY] = UMFPACK_STRATEGY_SYMMETRIC;
  // No iterative refinement: each step costs a matrix product and two
  // triangular solves per right-hand side, and the LU of these diagonally
  // dominated matrices is accurate without (the caller checks the residual).
  s.control[UMFPACK_IRSTEP] = 0;
  void* symbolic = nullptr;
  Long status;
  if (s.ordering == Ordering::AMD || s.ordering == Ordering::METIS) {
    s.control[UMFPACK_ORDERING] = s.ordering == Ordering::AMD ? UMFPACK_ORDERING_AMD : UMFPACK_ORDERING_METIS;
    status = umfpack_dl_symbolic(n, n, s.p.data(), s.i.data(), s.A.valuePtr(), &symbolic, s.control, s.info);
  } else {
    const std::vector<int> q = level_set_nested_dissection(s.A);
    const std::vector<Long> qinit(q.begin(), q.end());
    status = umfpack_dl_qsymbolic(n, n, s.p.data(), s.i.data(), s.A.valuePtr(), qinit.data(), &symbolic,
                                  s.control, s.info);
  }
  if (status != UMFPACK_OK) throw_numerical("UMFPACK analysis failed (status " + std::to_string(status) + ")");
  analyse_ms = ms_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  {
    SolverThreads threads;
    status = umfpack_dl_numeric(s.p.data(), s.i.data(), s.A.valuePtr(), symbolic, &s.numeric, s.control, s.info);
  }
  umfpack_dl_free_symbolic(&symbolic);
  factor_ms = ms_since(t1);
  if (status == UMFPACK_WARNING_singular_matrix) {
    umfpack_dl_free_numeric(&s.numeric);
    return false;
  }
  if (status != UMFPACK_OK) {
    if (s.numeric) umfpack_dl_free_numeric(&s.numeric);
    throw_numerical("UMFPACK factorization failed (status " + std::to_string(status) + ", out of memory?)");
  }
  return true;
}

Eigen::MatrixXd UmfpackFactor::solve(const Eigen::MatrixXd& B, bool transposed) const {
  Impl& s = *impl_;
  if (!s.numeric) throw_numerical("internal: UMFPACK solve before factor");
  Eigen::MatrixXd X(B.rows(), B.cols());
  for (int c = 0; c < B.cols(); ++c) {
    const Long status = umfpack_dl_solve(transposed ? UMFPACK_At : UMFPACK_A, s.p.data(), s.i.data(),
                                         s.A.valuePtr(), X.col(c).data(), B.col(c).data(), s.numeric,
                                         s.control, s.info);
    if (status != UMFPACK_OK && status != UMFPACK_WARNING_singular_matrix)
      throw_numerical("UMFPACK solve failed (status " + std::to_string(status) + ")");
  }
  return X;
}

double UmfpackFactor::flops() const { return impl_->numeric ? impl_->info[UMFPACK_FLOPS] : 0; }

double UmfpackFactor::factor_nonzeros() const {
  return impl_->numeric ? impl_->info[UMFPACK_LNZ] + impl_->info[UMFPACK_UNZ] : 0;
}

}  // namespace intrinsic::detail

#endif
