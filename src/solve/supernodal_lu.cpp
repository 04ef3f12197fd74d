// Left-looking supernodal LU without pivoting (see supernodal_lu.h). The
// loop over supernodes and the way descendants are found follow CHOLMOD's
// supernodal Cholesky (t_cholmod_super_numeric.c); where it computes one
// panel L_s, this computes two of the same shape: L's columns and U's rows
// (stored transposed, without the diagonal block), and the diagonal block
// holds L_s (unit, strictly below) and U_s (on and above) together.
#include "solve/supernodal_lu.h"

#ifdef INTRINSIC_HAVE_SUPERNODAL_LU

#include <cholmod.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include "intrinsic/error.h"
#include "solve/ordering.h"
#include "solve/solver_threads.h"

extern "C" {
void dgemm_(const char* ta, const char* tb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc);
void dtrsm_(const char* side, const char* uplo, const char* ta, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb);
}

namespace intrinsic::detail {
namespace {

using Long = SuiteSparse_long;
constexpr double kOne = 1, kMinusOne = -1, kZero = 0;

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void gemm(char ta, char tb, int m, int n, int k, double alpha, const double* a, int lda, const double* b, int ldb,
          double beta, double* c, int ldc) {
  if (m > 0 && n > 0 && k > 0) dgemm_(&ta, &tb, &m, &n, &k, &alpha, a, &lda, b, &ldb, &beta, c, &ldc);
}

void trsm(char side, char uplo, char ta, char diag, int m, int n, const double* a, int lda, double* b, int ldb) {
  if (m > 0 && n > 0) dtrsm_(&side, &uplo, &ta, &diag, &m, &n, &kOne, a, &lda, b, &ldb);
}

// In-place LU without pivoting of the n x n block A (leading dimension lda),
// recursively halved so that most of the work is one gemm. False when a
// pivot is not above floor[k] in magnitude (or not a number).
bool dense_lu(int n, double* A, int lda, const double* floor) {
  if (n <= 16) {
    for (int k = 0; k < n; ++k) {
      const double p = A[k + static_cast<Long>(k) * lda];
      if (!(std::abs(p) > floor[k]) || !std::isfinite(p)) return false;
      for (int i = k + 1; i < n; ++i) A[i + static_cast<Long>(k) * lda] /= p;
      for (int j = k + 1; j < n; ++j) {
        const double a = A[k + static_cast<Long>(j) * lda];
        if (a == 0) continue;
        for (int i = k + 1; i < n; ++i) A[i + static_cast<Long>(j) * lda] -= A[i + static_cast<Long>(k) * lda] * a;
      }
    }
    return true;
  }
  const int n1 = n / 2, n2 = n - n1;
  if (!dense_lu(n1, A, lda, floor)) return false;
  double* A12 = A + static_cast<Long>(n1) * lda;
  double* A21 = A + n1;
  double* A22 = A12 + n1;
  trsm('L', 'L', 'N', 'U', n1, n2, A, lda, A12, lda);  // U12 = L11^{-1} A12
  trsm('R', 'U', 'N', 'N', n2, n1, A, lda, A21, lda);  // L21 = A21 U11^{-1}
  gemm('N', 'N', n2, n2, n1, -1, A21, lda, A12, lda, 1, A22, lda);
  return dense_lu(n2, A22, lda, floor + n1);
}

}  // namespace

struct SupernodalLU::Impl {
  int n = 0, nsuper = 0;
  std::vector<int> perm;      // perm[k]: the row and column of A eliminated k-th
  std::vector<int> super;     // first column of each supernode, and n
  std::vector<Long> pi, px;   // offsets of each supernode's row indices and L values
  std::vector<Long> ux;       // offsets of each supernode's U values
  std::vector<int> rows;      // row indices (permuted numbering), supernode by supernode, ascending
  std::vector<int> super_of;  // the supernode of each column
  // Per supernode, column-major: L's columns (nsrow x nscol, the diagonal
  // block on top) and U's rows below the block, transposed ((nsrow - nscol)
  // x nscol; U_s itself sits in L's diagonal block).
  std::vector<double> Lx, Ux;
  double flops = 0;

  bool analyse(const SparseMatrix& A);
  Long position(int s, int row) const;
  bool assemble(const SparseMatrix& A, const std::vector<int>& iperm);
  void update_from(int d, int s, std::vector<Long>& lpos, const std::vector<int>& map, std::vector<double>& work);
  bool numeric(const SparseMatrix& A);
  void forward(double* Y, int nrhs, bool transposed) const;
  void backward(double* Y, int nrhs, bool transposed) const;
};

// CHOLMOD's supernodal symbolic analysis of A's (symmetric) pattern on the
// level-set nested dissection ordering, the one the conformal system gets.
// False when CHOLMOD cannot (out of memory): UMFPACK may still.
bool SupernodalLU::Impl::analyse(const SparseMatrix& A) {
  n = static_cast<int>(A.rows());
  const std::vector<int> order = level_set_nested_dissection(A);
  std::vector<Long> given(order.begin(), order.end());
  std::vector<Long> p(A.outerIndexPtr(), A.outerIndexPtr() + n + 1), i(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
  cholmod_common c;
  cholmod_l_start(&c);
  c.supernodal = CHOLMOD_SUPERNODAL;
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_GIVEN;
  c.postorder = 1;
  c.print = 0;
  cholmod_sparse cs{};
  cs.nrow = cs.ncol = n;
  cs.nzmax = A.nonZeros();
  cs.p = p.data();
  cs.i = i.data();
  cs.stype = -1;  // the lower triangle's pattern; the whole pattern is symmetric
  cs.itype = CHOLMOD_LONG;
  cs.xtype = CHOLMOD_PATTERN;
  cs.dtype = CHOLMOD_DOUBLE;
  cs.sorted = 1;
  cs.packed = 1;
  cholmod_factor* L = cholmod_l_analyze_p(&cs, given.data(), nullptr, 0, &c);
  if (!L || !L->is_super) {
    if (L) cholmod_l_free_factor(&L, &c);
    cholmod_l_finish(&c);
    return false;
  }
  nsuper = static_cast<int>(L->nsuper);
  const Long* Lsuper = static_cast<const Long*>(L->super);
  const Long* Lpi = static_cast<const Long*>(L->pi);
  const Long* Lpx = static_cast<const Long*>(L->px);
  const Long* Ls = static_cast<const Long*>(L->s);
  const Long* Lperm = static_cast<const Long*>(L->Perm);
  super.assign(Lsuper, Lsuper + nsuper + 1);
  pi.assign(Lpi, Lpi + nsuper + 1);
  px.assign(Lpx, Lpx + nsuper + 1);
  rows.assign(Ls, Ls + pi[nsuper]);
  perm.assign(Lperm, Lperm + n);
  cholmod_l_free_factor(&L, &c);
  cholmod_l_finish(&c);
  ux.assign(nsuper + 1, 0);
  super_of.resize(n);
  for (int s = 0; s < nsuper; ++s) {
    const Long nscol = super[s + 1] - super[s];
    ux[s + 1] = ux[s] + (pi[s + 1] - pi[s] - nscol) * nscol;
    for (int k = super[s]; k < super[s + 1]; ++k) super_of[k] = s;
  }
  return true;
}

// Where `row` is in supernode s's (ascending) row list; -1 if absent.
Long SupernodalLU::Impl::position(int s, int row) const {
  const int* first = rows.data() + pi[s];
  const int* last = rows.data() + pi[s + 1];
  const int* at = std::lower_bound(first, last, row);
  return at != last && *at == row ? at - first : -1;
}

// The panels start as the entries of C = P^T A P: C(r, c) with r >= c, and
// those of the diagonal blocks, go to L's panel of c's supernode, the others
// (r < c, c beyond r's supernode) to U's panel of r's supernode. Placed all
// at once (no transposed copy of A is needed for U's rows). False when an
// entry falls outside the factor's pattern: the analysis saw only the lower
// triangle, so an upper entry without its mirror does.
bool SupernodalLU::Impl::assemble(const SparseMatrix& A, const std::vector<int>& iperm) {
  for (int j = 0; j < n; ++j) {
    const int c = iperm[j], sc = super_of[c];
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      const int r = iperm[it.row()];
      if (r >= super[sc]) {
        const Long nsrow = pi[sc + 1] - pi[sc], at = position(sc, r);
        if (at < 0) return false;
        Lx[px[sc] + (c - super[sc]) * nsrow + at] = it.value();
      } else {
        const int t = super_of[r];
        const Long nscol = super[t + 1] - super[t], below = pi[t + 1] - pi[t] - nscol, at = position(t, c);
        if (at < nscol) return false;
        Ux[ux[t] + (r - super[t]) * below + at - nscol] = it.value();
      }
    }
  }
  return true;
}

// Subtracts descendant d's contribution from supernode s: with d's rows from
// lpos[d] on split into those among s's columns (n1) and those after (n3),
// L_s -= L_d[rows] U_d[:, cols] and U_s^T -= U_d^T[rows after] L_d[cols]^T.
void SupernodalLU::Impl::update_from(int d, int s, std::vector<Long>& lpos, const std::vector<int>& map,
                                     std::vector<double>& work) {
  const int k1 = super[s], k2 = super[s + 1];
  const Long nsrow = pi[s + 1] - pi[s];
  const int ndcol = super[d + 1] - super[d];
  const Long pdi = pi[d], ndrow = pi[d + 1] - pdi;
  const Long p1 = lpos[d];  // at least ndcol: past d's diagonal block
  Long p2 = p1;
  while (p2 < ndrow && rows[pdi + p2] < k2) ++p2;
  const int n1 = static_cast<int>(p2 - p1), n2 = static_cast<int>(ndrow - p1), n3 = n2 - n1;
  const double* Ld = Lx.data() + px[d] + p1;
  const double* Ud = Ux.data() + ux[d] + (p1 - ndcol);
  const int ld = static_cast<int>(ndrow), ldu = static_cast<int>(ndrow - ndcol);
  work.resize(static_cast<size_t>(n2 + n3) * n1);
  double* CL = work.data();
  double* CU = CL + static_cast<size_t>(n2) * n1;
  gemm('N', 'T', n2, n1, ndcol, 1, Ld, ld, Ud, ldu, 0, CL, n2);
  gemm('N', 'T', n3, n1, ndcol, 1, Ud + n1, ldu, Ld, ld, 0, CU, n3);
  flops += 2.0 * ndcol * n1 * (n2 + n3);
  const int* drows = rows.data() + pdi + p1;
  const Long nscol = k2 - k1, below = nsrow - nscol;
  double* L = Lx.data() + px[s];
  double* U = Ux.data() + ux[s];  // rows of s past its diagonal block
  for (int j = 0; j < n1; ++j) {
    const Long col = drows[j] - k1;
    for (int i = 0; i < n2; ++i) L[col * nsrow + map[drows[i]]] -= CL[i + static_cast<Long>(j) * n2];
    for (int i = 0; i < n3; ++i) U[col * below + map[drows[n1 + i]] - nscol] -= CU[i + static_cast<Long>(j) * n3];
  }
  lpos[d] = p2;
}

bool SupernodalLU::Impl::numeric(const SparseMatrix& A) {
  std::vector<int> iperm(n), map(n, 0);
  for (int k = 0; k < n; ++k) iperm[perm[k]] = k;
  // A pivot must stand out of rounding relative to its column of A.
  std::vector<double> floor(n, 0.0);
  for (int j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      floor[iperm[j]] = std::max(floor[iperm[j]], 1e-14 * std::abs(it.value()));
  Lx.assign(px[nsuper], 0.0);
  Ux.assign(ux[nsuper], 0.0);
  if (!assemble(A, iperm)) return false;
  // head[s]: descendants whose next unused row lies in s, linked by next.
  std::vector<int> head(nsuper, -1), next(nsuper, -1);
  std::vector<Long> lpos(nsuper, 0);
  std::vector<double> work;
  flops = 0;
  for (int s = 0; s < nsuper; ++s) {
    const int k1 = super[s], nscol = super[s + 1] - k1;
    const Long psi = pi[s], nsrow = pi[s + 1] - psi;
    for (Long r = 0; r < nsrow; ++r) map[rows[psi + r]] = static_cast<int>(r);
    for (int d = head[s]; d >= 0;) {
      const int following = next[d];
      update_from(d, s, lpos, map, work);
      if (lpos[d] < pi[d + 1] - pi[d]) {
        const int t = super_of[rows[pi[d] + lpos[d]]];
        next[d] = head[t];
        head[t] = d;
      }
      d = following;
    }
    double* L = Lx.data() + px[s];
    double* U = Ux.data() + ux[s];
    const int lda = static_cast<int>(nsrow), below = static_cast<int>(nsrow - nscol);
    if (!dense_lu(nscol, L, lda, floor.data() + k1)) return false;
    flops += 2.0 * nscol * nscol * nscol / 3;
    trsm('R', 'U', 'N', 'N', below, nscol, L, lda, L + nscol, lda);  // L below = A below U_s^{-1}
    trsm('R', 'L', 'T', 'U', below, nscol, L, lda, U, std::max(below, 1));  // U right^T = A right^T L_s^{-T}
    flops += 2.0 * below * nscol * nscol;
    if (below > 0) {
      lpos[s] = nscol;
      const int t = super_of[rows[psi + nscol]];
      next[s] = head[t];
      head[t] = s;
    }
  }
  return true;
}

SupernodalLU::SupernodalLU() : impl_(std::make_unique<Impl>()) {}
SupernodalLU::~SupernodalLU() = default;

bool SupernodalLU::factor(const SparseMatrix& A) {
  Impl& s = *impl_;
  if (A.rows() != A.cols() || !A.isCompressed()) throw_numerical("internal: supernodal LU needs a compressed square matrix");
  const auto t0 = std::chrono::steady_clock::now();
  if (A.rows() == 0) {  // nothing to factor (every vertex fixed)
    s = Impl();
    s.super = {0};
    s.pi = s.px = s.ux = {0};
    return true;
  }
  if (!s.analyse(A)) return false;
  analyse_ms = ms_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  bool ok;
  {
    SolverThreads threads;
    ok = s.numeric(A);
  }
  factor_ms = ms_since(t1);
  if (!ok) {
    s.Lx = std::vector<double>();
    s.Ux = std::vector<double>();
  }
  return ok;
}

// Y := (L or U^T)^{-1} Y, supernodes in order: the diagonal block, then the
// rows below get the block's contribution.
void SupernodalLU::Impl::forward(double* Y, int nrhs, bool transposed) const {
  std::vector<double> W;
  for (int s = 0; s < nsuper; ++s) {
    const int k1 = super[s], nscol = super[s + 1] - k1;
    const Long psi = pi[s], nsrow = pi[s + 1] - psi;
    const int lda = static_cast<int>(nsrow), below = static_cast<int>(nsrow - nscol);
    const double* L = Lx.data() + px[s];
    if (transposed) trsm('L', 'U', 'T', 'N', nscol, nrhs, L, lda, Y + k1, n);
    else trsm('L', 'L', 'N', 'U', nscol, nrhs, L, lda, Y + k1, n);
    if (below == 0) continue;
    W.resize(static_cast<size_t>(below) * nrhs);
    if (transposed) gemm('N', 'N', below, nrhs, nscol, 1, Ux.data() + ux[s], below, Y + k1, n, 0, W.data(), below);
    else gemm('N', 'N', below, nrhs, nscol, 1, L + nscol, lda, Y + k1, n, 0, W.data(), below);
    for (int c = 0; c < nrhs; ++c)
      for (int i = 0; i < below; ++i) Y[rows[psi + nscol + i] + static_cast<Long>(c) * n] -= W[i + static_cast<Long>(c) * below];
  }
}

// Y := (U or L^T)^{-1} Y, supernodes in reverse: the rows below (already
// solved) are gathered, then the diagonal block.
void SupernodalLU::Impl::backward(double* Y, int nrhs, bool transposed) const {
  std::vector<double> G;
  for (int s = nsuper - 1; s >= 0; --s) {
    const int k1 = super[s], nscol = super[s + 1] - k1;
    const Long psi = pi[s], nsrow = pi[s + 1] - psi;
    const int lda = static_cast<int>(nsrow), below = static_cast<int>(nsrow - nscol);
    const double* L = Lx.data() + px[s];
    if (below > 0) {
      G.resize(static_cast<size_t>(below) * nrhs);
      for (int c = 0; c < nrhs; ++c)
        for (int i = 0; i < below; ++i) G[i + static_cast<Long>(c) * below] = Y[rows[psi + nscol + i] + static_cast<Long>(c) * n];
      if (transposed) gemm('T', 'N', nscol, nrhs, below, -1, L + nscol, lda, G.data(), below, 1, Y + k1, n);
      else gemm('T', 'N', nscol, nrhs, below, -1, Ux.data() + ux[s], below, G.data(), below, 1, Y + k1, n);
    }
    if (transposed) trsm('L', 'L', 'T', 'U', nscol, nrhs, L, lda, Y + k1, n);
    else trsm('L', 'U', 'N', 'N', nscol, nrhs, L, lda, Y + k1, n);
  }
}

Eigen::MatrixXd SupernodalLU::solve(const Eigen::MatrixXd& B, bool transposed) const {
  const Impl& s = *impl_;
  if (s.Lx.empty() && s.n > 0) throw_numerical("internal: supernodal LU solve before a successful factor");
  const int nrhs = static_cast<int>(B.cols());
  Eigen::MatrixXd Y(s.n, nrhs);
  for (int k = 0; k < s.n; ++k) Y.row(k) = B.row(s.perm[k]);
  {
    SolverThreads threads;
    s.forward(Y.data(), nrhs, transposed);
    s.backward(Y.data(), nrhs, transposed);
  }
  Eigen::MatrixXd X(s.n, nrhs);
  for (int k = 0; k < s.n; ++k) X.row(s.perm[k]) = Y.row(k);
  return X;
}

double SupernodalLU::factor_nonzeros() const {
  return impl_->Lx.empty() ? 0 : static_cast<double>(impl_->Lx.size() + impl_->Ux.size());
}
double SupernodalLU::flops() const { return impl_->flops; }

}  // namespace intrinsic::detail

#endif
