// Left-looking supernodal LU without pivoting (see supernodal_lu.h). The
// loop over supernodes and the way descendants are found follow CHOLMOD's
// supernodal Cholesky (t_cholmod_super_numeric.c); where it computes one
// panel L_s, this computes two of the same shape: L's columns and U's rows
// (stored transposed, without the diagonal block), and the diagonal block
// holds L_s (unit, strictly below) and U_s (on and above) together.
#include "solve/supernodal_lu.h"

#ifdef INTRINSIC_HAVE_SUPERNODAL_LU

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include "intrinsic/error.h"
#include "solve/solver_threads.h"
#include "solve/suitesparse.h"
#include "solve/supernodal_blas.h"
#include "solve/supernodal_schedule.h"

namespace intrinsic::detail {
namespace {

using Long = std::int64_t;
using blas::gemm;
using blas::trsm;

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
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
  int threads = 1;
  // Who updates each supernode (ascending: a fixed order), and the subtrees
  // that run in parallel (supernodal_schedule.h; the top supernodes run on
  // one thread).
  DescendantLists updates;
  SupernodalSchedule schedule;

  bool analyse(const SparseMatrix& A);
  Long position(int s, int row) const;
  bool assemble(const SparseMatrix& A, const std::vector<int>& iperm);
  double update_from(int d, int s, Long p1, const std::vector<int>& map, std::vector<double>& work);
  bool factor_node(int s, const std::vector<double>& floor, std::vector<int>& map, std::vector<double>& work,
                   double& node_flops);
  bool numeric(const SparseMatrix& A);
  void forward(double* Y, int nrhs, bool transposed) const;
  void backward(double* Y, int nrhs, bool transposed) const;
};

// CHOLMOD's supernodal symbolic analysis (suitesparse.h), the one the
// supernodal Cholesky of the conformal system gets. False when CHOLMOD
// cannot (out of memory): UMFPACK may still.
bool SupernodalLU::Impl::analyse(const SparseMatrix& A) {
  SupernodalSymbolic S;
  if (!supernodal_analysis(A, S)) return false;
  updates = descendant_lists(S);
  std::vector<double> cost(S.nsuper, 0.0);
  for (int s = 0; s < S.nsuper; ++s)
    for (int j = 0; j < S.nscol(s); ++j) cost[s] += 2.0 * (S.nsrow(s) - j) * (S.nsrow(s) - j);
  schedule = subtree_schedule(S, cost);
  n = S.n;
  nsuper = S.nsuper;
  perm = std::move(S.perm);
  super = std::move(S.super);
  pi = std::move(S.pi);
  px = std::move(S.px);
  rows = std::move(S.rows);
  super_of = std::move(S.super_of);
  ux.assign(nsuper + 1, 0);
  for (int s = 0; s < nsuper; ++s) {
    const Long nscol = super[s + 1] - super[s];
    ux[s + 1] = ux[s] + (pi[s + 1] - pi[s] - nscol) * nscol;
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
// p1 (its first row in s) on split into those among s's columns (n1) and those after (n3),
// L_s -= L_d[rows] U_d[:, cols] and U_s^T -= U_d^T[rows after] L_d[cols]^T.
double SupernodalLU::Impl::update_from(int d, int s, Long p1, const std::vector<int>& map,
                                       std::vector<double>& work) {
  const int k1 = super[s], k2 = super[s + 1];
  const Long nsrow = pi[s + 1] - pi[s];
  const int ndcol = super[d + 1] - super[d];
  const Long pdi = pi[d], ndrow = pi[d + 1] - pdi;
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
  const int* drows = rows.data() + pdi + p1;
  const Long nscol = k2 - k1, below = nsrow - nscol;
  double* L = Lx.data() + px[s];
  double* U = Ux.data() + ux[s];  // rows of s past its diagonal block
  for (int j = 0; j < n1; ++j) {
    const Long col = drows[j] - k1;
    for (int i = 0; i < n2; ++i) L[col * nsrow + map[drows[i]]] -= CL[i + static_cast<Long>(j) * n2];
    for (int i = 0; i < n3; ++i) U[col * below + map[drows[n1 + i]] - nscol] -= CU[i + static_cast<Long>(j) * n3];
  }
  return 2.0 * ndcol * n1 * (n2 + n3);
}

// Supernode s: its descendants' updates in ascending order, then the LU of
// its diagonal block and the two panels beside it. False at a bad pivot.
bool SupernodalLU::Impl::factor_node(int s, const std::vector<double>& floor, std::vector<int>& map,
                                     std::vector<double>& work, double& node_flops) {
  const int k1 = super[s], nscol = super[s + 1] - k1;
  const Long psi = pi[s], nsrow = pi[s + 1] - psi;
  for (Long r = 0; r < nsrow; ++r) map[rows[psi + r]] = static_cast<int>(r);
  for (Long u = updates.start[s]; u < updates.start[s + 1]; ++u)
    node_flops += update_from(updates.d[u], s, updates.p[u], map, work);
  double* L = Lx.data() + px[s];
  double* U = Ux.data() + ux[s];
  const int lda = static_cast<int>(nsrow), below = static_cast<int>(nsrow - nscol);
  if (!dense_lu(nscol, L, lda, floor.data() + k1)) return false;
  node_flops += 2.0 * nscol * nscol * nscol / 3;
  trsm('R', 'U', 'N', 'N', below, nscol, L, lda, L + nscol, lda);  // L below = A below U_s^{-1}
  trsm('R', 'L', 'T', 'U', below, nscol, L, lda, U, std::max(below, 1));  // U right^T = A right^T L_s^{-T}
  node_flops += 2.0 * below * nscol * nscol;
  return true;
}

bool SupernodalLU::Impl::numeric(const SparseMatrix& A) {
  std::vector<int> iperm(n);
  for (int k = 0; k < n; ++k) iperm[perm[k]] = k;
  // A pivot must stand out of rounding relative to its column of A.
  std::vector<double> floor(n, 0.0);
  for (int j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      floor[iperm[j]] = std::max(floor[iperm[j]], 1e-14 * std::abs(it.value()));
  Lx.assign(px[nsuper], 0.0);
  Ux.assign(ux[nsuper], 0.0);
  if (!assemble(A, iperm)) return false;
  // The subtrees on `threads` workers, each with its own scratch, then the
  // top supernodes on this thread.
  std::vector<std::vector<int>> maps(threads, std::vector<int>(n, 0));
  std::vector<std::vector<double>> works(threads);
  const int tasks = static_cast<int>(schedule.subtrees.size());
  std::vector<double> task_flops(tasks, 0.0);
  std::vector<char> failed(tasks, 0);
  run_tasks(tasks, threads, [&](int t, int worker) {
    for (int s = schedule.subtrees[t].first; s <= schedule.subtrees[t].second && !failed[t]; ++s)
      failed[t] = !factor_node(s, floor, maps[worker], works[worker], task_flops[t]);
  });
  flops = 0;
  for (int t = 0; t < tasks; ++t) {
    if (failed[t]) return false;
    flops += task_flops[t];
  }
  for (int s : schedule.top)
    if (!factor_node(s, floor, maps[0], works[0], flops)) return false;
  return true;
}

SupernodalLU::SupernodalLU(int threads) : impl_(std::make_unique<Impl>()) {
  impl_->threads = threads > 0 ? threads : hardware_threads();
}
SupernodalLU::~SupernodalLU() = default;

bool SupernodalLU::factor(const SparseMatrix& A) {
  Impl& s = *impl_;
  if (A.rows() != A.cols() || !A.isCompressed()) throw_numerical("internal: supernodal LU needs a compressed square matrix");
  const auto t0 = std::chrono::steady_clock::now();
  if (A.rows() == 0) {  // nothing to factor (every vertex fixed)
    const int threads = s.threads;
    s = Impl();
    s.threads = threads;
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
