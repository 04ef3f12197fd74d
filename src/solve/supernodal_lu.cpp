// Left-looking supernodal LU without pivoting (see supernodal_lu.h). The
// loop over supernodes and the way descendants are found follow CHOLMOD's
// supernodal Cholesky (t_cholmod_super_numeric.c); where it computes one
// panel L_s, this computes two of the same shape: L's columns and U's rows
// (stored transposed, without the diagonal block), and the diagonal block
// holds L_s (unit, strictly below) and U_s (on and above) together. The
// parallelism is the supernodal Cholesky's (supernodal_cholesky.cpp):
// independent subtrees on the threads, then each wide top supernode split
// in column blocks of both panels; the triangular solves run on the same
// subtrees.
#include "solve/supernodal_lu.h"

#ifdef INTRINSIC_HAVE_SUPERNODAL_LU

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "intrinsic/error.h"
#include "solve/solver_threads.h"
#include "solve/suitesparse.h"
#include "solve/supernodal_blas.h"
#include "solve/supernodal_schedule.h"
#include "util/stopwatch.h"

namespace intrinsic::detail {
namespace {

using Long = std::int64_t;
using blas::gemm;
using blas::trsm;

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

// Row (or column) slices of about 256 for the triangular solves of a block.
int slices_of(int count) { return std::max(1, count / 256); }
int slice_start(int count, int t) { return static_cast<int>(static_cast<Long>(count) * t / slices_of(count)); }

// Leaves the panels' doubles uninitialized when they are allocated: each
// supernode zeroes its own panels where it is factored, on the thread that
// factors it (a serial zero fill of the 1.1 GB of a 1M-vertex LU cost about
// a third of a second, mostly page faults).
template <class T>
struct UninitializedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <class U>
  UninitializedAllocator(const UninitializedAllocator<U>&) {}
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
using Panels = std::vector<double, UninitializedAllocator<double>>;

// A worker's scratch: where each row of the current supernode sits in its
// panel, and room for one update block.
struct LuWorkspace {
  std::vector<int> map;
  std::vector<double> work;
  std::int64_t placed = 0;  // entries of A assembled by this worker
};

}  // namespace

struct SupernodalLU::Impl {
  int n = 0, nsuper = 0;
  std::vector<int> perm;      // perm[k]: the row and column of A eliminated k-th
  std::vector<int> super;     // first column of each supernode, and n
  std::vector<Long> pi, px;   // offsets of each supernode's row indices and L values
  std::vector<Long> ux;       // offsets of each supernode's U values
  std::vector<int> rows;      // row indices (permuted numbering), supernode by supernode, ascending
  std::vector<int> super_of;  // the supernode of each column
  std::vector<int> parent;    // supernodal elimination tree (-1 at roots)
  // Per supernode, column-major: L's columns (nsrow x nscol, the diagonal
  // block on top) and U's rows below the block, transposed ((nsrow - nscol)
  // x nscol; U_s itself sits in L's diagonal block).
  Panels Lx, Ux;
  double flops = 0;
  double top_flops = 0, serial_flops = 0;  // of the top supernodes; of those, on one thread
  int threads = 1;
  // Who updates each supernode (ascending: a fixed order), and the subtrees
  // that run in parallel (supernodal_schedule.h); the top supernodes run one
  // after the other, each split in column blocks between the threads.
  DescendantLists updates;
  SupernodalSchedule schedule;
  std::vector<int> top_index;  // a top supernode's column -> its row in the solve's buffers, else -1
  int top_columns = 0;
  int split = 0;  // top supernodes factored in column blocks by the threads
  // During numeric(): A and the inverse of perm, for each supernode's
  // assembly.
  const SparseMatrix* A = nullptr;
  std::vector<int> iperm;

  bool analyse(const SparseMatrix& A, SupernodalSymbolic* analysed);
  bool assemble_node(int s, const int* map, double* floor, Long& placed);
  double update_block(int s, int c1, int c2, const int* map, std::vector<double>& work);
  void block_solves(int s, int c1, int c2, int node_threads);
  void trailing_update(int s, int c1, int c2, int node_threads);
  bool factor_node(int s, double* floor, LuWorkspace& ws, int node_threads, double& node_flops);
  bool numeric(const SparseMatrix& matrix);
  void forward_node(int s, double* Y, int nrhs, bool transposed, double* top_buffer, std::vector<double>& W,
                    int node_threads) const;
  void backward_node(int s, double* Y, int nrhs, bool transposed, std::vector<double>& G, int node_threads) const;
  void solve_in_place(double* Y, int nrhs, bool transposed) const;
  int top_threads(int s) const;
  // Enough flops to share between threads (a thread costs tens of microseconds).
  bool wide(int s) const {
    const double nscol = super[s + 1] - super[s], nsrow = static_cast<double>(pi[s + 1] - pi[s]);
    return nscol * nscol * nsrow > kParallelFlops;
  }
};

// CHOLMOD's supernodal symbolic analysis (suitesparse.h), the one the
// supernodal Cholesky of the conformal system gets. False when CHOLMOD
// cannot (out of memory): UMFPACK may still.
bool SupernodalLU::Impl::analyse(const SparseMatrix& A, SupernodalSymbolic* analysed) {
  SupernodalSymbolic S;
  if (analysed) S = std::move(*analysed);
  else if (!supernodal_analysis(A, S)) return false;
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
  parent = std::move(S.parent);
  ux.assign(nsuper + 1, 0);
  for (int s = 0; s < nsuper; ++s) {
    const Long nscol = super[s + 1] - super[s];
    ux[s + 1] = ux[s] + (pi[s + 1] - pi[s] - nscol) * nscol;
  }
  top_index.assign(n, -1);
  top_columns = 0;
  split = 0;
  for (int s : schedule.top) {
    for (int k = super[s]; k < super[s + 1]; ++k) top_index[k] = top_columns++;
    split += column_blocks(super[s + 1] - super[s]) > 1 && wide(s);
  }
  return true;
}

// Supernode s's panels start zero with its entries of C = P^T A P: for each
// of its columns c, C(r, c) with r in the supernode (r >= its first column)
// goes to L's panel, and for r past its columns also C(c, r) (row c of C)
// to U's rows. C(c, r) is read at its place in A, column perm[r], found by
// bisection of that column's rows: A's pattern is symmetric, so row c has
// its entries where column c has, and no transpose of A is needed (at 1M
// vertices it took about 88 MB and a serial pass). Every entry of C lands once:
// C(r, c) with r before c's supernode is in U's rows of r's supernode.
// Done where s is factored, so the panels are filled on the thread that
// works on them. map: each row's position in s's row list (set for s; other
// rows hold stale positions, hence the check). floor: the least pivot of
// each of s's columns, 1e-14 of its largest entry in A. False when an entry of
// column c falls outside the factor's pattern. An entry C(r, c) right of
// r's supernode whose mirror C(c, r) is absent is read by no supernode:
// numeric() finds that by counting the entries placed (placed).
bool SupernodalLU::Impl::assemble_node(int s, const int* map, double* floor, Long& placed) {
  const int k1 = super[s], k2 = super[s + 1];
  const Long nsrow = pi[s + 1] - pi[s], nscol = k2 - k1, below = nsrow - nscol;
  const int* srows = rows.data() + pi[s];
  const int* outer = A->outerIndexPtr();
  const int* inner = A->innerIndexPtr();
  const double* value = A->valuePtr();
  double* L = Lx.data() + px[s];
  double* U = Ux.data() + ux[s];
  std::fill(L, L + nsrow * nscol, 0.0);
  std::fill(U, U + below * nscol, 0.0);
  for (int c = k1; c < k2; ++c) {
    const int j = perm[c];
    double largest = 0;
    for (int k = outer[j]; k < outer[j + 1]; ++k) largest = std::max(largest, std::abs(value[k]));
    floor[c] = 1e-14 * largest;
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      const int r = iperm[inner[k]];
      if (r < k1) continue;  // U's, of r's supernode
      const int at = map[r];
      if (at >= nsrow || srows[at] != r) return false;
      L[(c - k1) * nsrow + at] = value[k];
      ++placed;
      if (r < k2) continue;  // the diagonal block: L_s and U_s both from column c
      const int* first = inner + outer[inner[k]];
      const int* last = inner + outer[inner[k] + 1];
      const int* m = std::lower_bound(first, last, j);
      if (m == last || *m != j) continue;  // C(c, r) is zero
      U[(c - k1) * below + at - nscol] = value[m - inner];
      ++placed;
    }
  }
  return true;
}

// Subtracts from columns [c1, c2) of supernode s (local numbering), in L's
// panel and in U's rows below, the updates of all its descendants in
// ascending order. With d's rows from its first in s (p1) on, those in
// s's columns [c1, c2) (q1..q2) and those past s's columns (p2 on):
// L_s[rows from p1, cols] -= L_d[rows from p1] U_d[cols]^T (the diagonal
// block's part above the columns is U_s's) and
// U_s^T[rows from p2, cols] -= U_d^T[rows from p2] L_d[cols]^T.
// Returns the flops.
double SupernodalLU::Impl::update_block(int s, int c1, int c2, const int* map, std::vector<double>& work) {
  const int k1 = super[s], k2 = super[s + 1];
  const Long nsrow = pi[s + 1] - pi[s], nscol = k2 - k1, below = nsrow - nscol;
  double* L = Lx.data() + px[s];
  double* U = Ux.data() + ux[s];
  double flops = 0;
  for (Long u = updates.start[s]; u < updates.start[s + 1]; ++u) {
    const int d = updates.d[u], ndcol = super[d + 1] - super[d];
    const Long ndrow = pi[d + 1] - pi[d];
    const int* drows = rows.data() + pi[d];
    const int* end = drows + ndrow;
    const int* p1 = drows + updates.p[u];
    const int* q1 = std::lower_bound(p1, end, k1 + c1);
    const int* q2 = std::lower_bound(q1, end, k1 + c2);
    const int n1 = static_cast<int>(q2 - q1);
    if (n1 == 0) continue;
    const int* p2 = std::lower_bound(q2, end, k2);
    const int nl = static_cast<int>(end - p1), n3 = static_cast<int>(end - p2);
    const double* Ld = Lx.data() + px[d];
    const double* Ud = Ux.data() + ux[d];  // Ud[r - ndcol]: U_d's entry for d's row r (r >= ndcol)
    const int ld = static_cast<int>(ndrow), ldu = static_cast<int>(ndrow - ndcol);
    work.resize(static_cast<size_t>(nl + n3) * n1);
    double* CL = work.data();
    double* CU = CL + static_cast<size_t>(nl) * n1;
    gemm('N', 'T', nl, n1, ndcol, 1, Ld + (p1 - drows), ld, Ud + (q1 - drows - ndcol), ldu, 0, CL, nl);
    gemm('N', 'T', n3, n1, ndcol, 1, Ud + (p2 - drows - ndcol), ldu, Ld + (q1 - drows), ld, 0, CU, n3);
    for (int j = 0; j < n1; ++j) {
      const Long col = q1[j] - k1;
      double* Lc = L + col * nsrow;
      double* Uc = U + col * below;  // Uc[map[r] - nscol]: row r past s's columns
      const double* cl = CL + static_cast<Long>(j) * nl;
      const double* cu = CU + static_cast<Long>(j) * n3;
      for (int i = 0; i < nl; ++i) Lc[map[p1[i]]] -= cl[i];
      for (int i = 0; i < n3; ++i) Uc[map[p2[i]] - nscol] -= cu[i];
    }
    flops += 2.0 * ndcol * n1 * (nl + n3);
  }
  return flops;
}

// After the LU of the diagonal block of columns [c1, c2): L's rows below it
// (L = A U_b^{-1}), U's columns right of it in the diagonal block and U's
// rows below the supernode (U = L_b^{-1} A), in slices shared by the threads.
void SupernodalLU::Impl::block_solves(int s, int c1, int c2, int node_threads) {
  const int nscol = super[s + 1] - super[s], nsrow = static_cast<int>(pi[s + 1] - pi[s]);
  const int lda = nsrow, below = nsrow - nscol, ldu = std::max(below, 1), w = c2 - c1;
  double* L = Lx.data() + px[s];
  double* U = Ux.data() + ux[s];
  const double* D = L + static_cast<Long>(c1) * lda + c1;
  const int lrows = nsrow - c2, ucols = nscol - c2;
  const int nl = slices_of(lrows), nd = slices_of(ucols), nu = slices_of(below);
  run_tasks(nl + nd + nu, node_threads, [&](int t, int) {
    if (t < nl) {
      const int r1 = slice_start(lrows, t), r2 = slice_start(lrows, t + 1);
      trsm('R', 'U', 'N', 'N', r2 - r1, w, D, lda, L + static_cast<Long>(c1) * lda + c2 + r1, lda);
    } else if (t < nl + nd) {
      const int j1 = slice_start(ucols, t - nl), j2 = slice_start(ucols, t - nl + 1);
      trsm('L', 'L', 'N', 'U', w, j2 - j1, D, lda, L + static_cast<Long>(c2 + j1) * lda + c1, lda);
    } else {
      const int r1 = slice_start(below, t - nl - nd), r2 = slice_start(below, t - nl - nd + 1);
      trsm('R', 'L', 'T', 'U', r2 - r1, w, D, lda, U + static_cast<Long>(c1) * ldu + r1, ldu);
    }
  });
}

// The right-looking step after block [c1, c2): each later column block
// [j1, j2) loses L[rows from c2, block] U[block, j1:j2] in L's panel and
// U^T[below, block] L[j1:j2, block]^T in U's rows below; one task per block.
void SupernodalLU::Impl::trailing_update(int s, int c1, int c2, int node_threads) {
  const int nscol = super[s + 1] - super[s], nsrow = static_cast<int>(pi[s + 1] - pi[s]);
  const int lda = nsrow, below = nsrow - nscol, ldu = std::max(below, 1), w = c2 - c1;
  double* L = Lx.data() + px[s];
  double* U = Ux.data() + ux[s];
  const int blocks = column_blocks(nscol);
  int b = 0;
  while (block_start(nscol, b) < c2) ++b;
  run_tasks(blocks - b, node_threads, [&](int t, int) {
    const int j1 = block_start(nscol, b + t), j2 = block_start(nscol, b + t + 1);
    const double* Lb = L + static_cast<Long>(c1) * lda;  // the block's columns
    gemm('N', 'N', nsrow - c2, j2 - j1, w, -1, Lb + c2, lda, L + static_cast<Long>(j1) * lda + c1, lda, 1,
         L + static_cast<Long>(j1) * lda + c2, lda);
    gemm('N', 'T', below, j2 - j1, w, -1, U + static_cast<Long>(c1) * ldu, ldu, Lb + j1, lda, 1,
         U + static_cast<Long>(j1) * ldu, ldu);
  });
}

// Supernode s: its descendants' updates, column block by column block, then
// a right-looking blocked LU of its panels (the LU of each diagonal block,
// the triangular solves beside it, the update of the blocks to its right).
// Each step's pieces are independent, so node_threads threads share them;
// the pieces are the same for any node_threads. False at a bad pivot.
bool SupernodalLU::Impl::factor_node(int s, double* floor, LuWorkspace& ws, int node_threads,
                                     double& node_flops) {
  const int k1 = super[s], nscol = super[s + 1] - k1;
  const Long psi = pi[s], nsrow = pi[s + 1] - psi;
  for (Long r = 0; r < nsrow; ++r) ws.map[rows[psi + r]] = static_cast<int>(r);
  if (!assemble_node(s, ws.map.data(), floor, ws.placed)) return false;
  const int blocks = column_blocks(nscol);
  std::vector<double> block_flops(blocks, 0.0);
  std::vector<std::vector<double>> works(node_threads > 1 ? node_threads : 0);
  run_tasks(blocks, node_threads, [&](int b, int worker) {
    std::vector<double>& work = worker == 0 ? ws.work : works[worker];
    block_flops[b] = update_block(s, block_start(nscol, b), block_start(nscol, b + 1), ws.map.data(), work);
  });
  for (double f : block_flops) node_flops += f;
  double* L = Lx.data() + px[s];
  const int lda = static_cast<int>(nsrow);
  for (int b = 0; b < blocks; ++b) {
    const int c1 = block_start(nscol, b), c2 = block_start(nscol, b + 1);
    if (!dense_lu(c2 - c1, L + static_cast<Long>(c1) * lda + c1, lda, floor + k1 + c1)) return false;
    block_solves(s, c1, c2, node_threads);
    trailing_update(s, c1, c2, node_threads);
  }
  const double below = static_cast<double>(nsrow - nscol);
  node_flops += 2.0 * nscol * nscol * nscol / 3 + 2.0 * below * nscol * nscol;
  return true;
}

bool SupernodalLU::Impl::numeric(const SparseMatrix& matrix) {
  A = &matrix;
  iperm.resize(n);
  for (int k = 0; k < n; ++k) iperm[perm[k]] = k;
  // A pivot must stand out of rounding relative to its column of A: each
  // supernode's assembly sets its columns' floors.
  std::vector<double> floor(n, 0.0);
  Lx.resize(px[nsuper]);
  Ux.resize(ux[nsuper]);
  // The subtrees on `threads` workers, each with its own scratch, then the
  // top supernodes one by one, the large ones split between the threads.
  std::vector<LuWorkspace> ws(threads);
  for (LuWorkspace& w : ws) w.map.assign(n, 0);
  const int tasks = static_cast<int>(schedule.subtrees.size());
  std::vector<double> task_flops(tasks, 0.0);
  std::vector<char> failed(tasks, 0);
  run_tasks(tasks, threads, [&](int t, int worker) {
    for (int s = schedule.subtrees[t].first; s <= schedule.subtrees[t].second && !failed[t]; ++s)
      failed[t] = !factor_node(s, floor.data(), ws[worker], 1, task_flops[t]);
  });
  flops = 0;
  for (int t = 0; t < tasks; ++t) {
    if (failed[t]) return false;
    flops += task_flops[t];
  }
  top_flops = serial_flops = 0;
  for (int s : schedule.top) {
    const int node_threads = wide(s) ? threads : 1;
    double node_flops = 0;
    if (!factor_node(s, floor.data(), ws[0], node_threads, node_flops)) return false;
    flops += node_flops;
    top_flops += node_flops;
    if (!wide(s)) serial_flops += node_flops;
    else  // the diagonal blocks' LUs
      for (int b = 0, nscol = super[s + 1] - super[s]; b < column_blocks(nscol); ++b)
        serial_flops += 2.0 * std::pow(block_start(nscol, b + 1) - block_start(nscol, b), 3) / 3;
  }
  A = nullptr;
  // Each entry of A was placed once, unless the pattern was not symmetric.
  Long placed = 0;
  for (const LuWorkspace& w : ws) placed += w.placed;
  return placed == matrix.nonZeros();
}

SupernodalLU::SupernodalLU(int threads) : impl_(std::make_unique<Impl>()) {
  impl_->threads = threads > 0 ? threads : hardware_threads();
}
SupernodalLU::~SupernodalLU() = default;

bool SupernodalLU::factor(const SparseMatrix& A, SupernodalSymbolic* analysed) {
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
  if (!s.analyse(A, analysed)) return false;
  analyse_ms = ms_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  bool ok;
  {
    SolverThreads threads;
    ok = s.numeric(A);
  }
  s.A = nullptr;
  factor_ms = ms_since(t1);
  if (!ok) {
    s.Lx = Panels();
    s.Ux = Panels();
  }
  return ok;
}

// Forward step of supernode s with L (or U^T when transposed): its diagonal
// block, then its rows below get the block's contribution; rows of top
// supernodes go to top_buffer instead when one is given (a subtree's private
// sum, added in a fixed order afterwards). node_threads > 0 (the top
// supernodes): the rows below in slices shared by that many threads; the
// slices depend on the sizes only.
void SupernodalLU::Impl::forward_node(int s, double* Y, int nrhs, bool transposed, double* top_buffer,
                                      std::vector<double>& W, int node_threads) const {
  const int k1 = super[s], nscol = super[s + 1] - k1;
  const Long psi = pi[s], nsrow = pi[s + 1] - psi;
  const int lda = static_cast<int>(nsrow), below = static_cast<int>(nsrow - nscol);
  const double* L = Lx.data() + px[s];
  if (transposed) trsm('L', 'U', 'T', 'N', nscol, nrhs, L, lda, Y + k1, n);
  else trsm('L', 'L', 'N', 'U', nscol, nrhs, L, lda, Y + k1, n);
  if (below == 0) return;
  W.resize(static_cast<size_t>(below) * nrhs);
  const double* P = transposed ? Ux.data() + ux[s] : L + nscol;
  const int ldp = transposed ? below : lda;
  const int* r = rows.data() + psi + nscol;
  auto rows_below = [&](int i1, int i2) {
    gemm('N', 'N', i2 - i1, nrhs, nscol, 1, P + i1, ldp, Y + k1, n, 0, W.data() + i1, below);
    for (int c = 0; c < nrhs; ++c)
      for (int i = i1; i < i2; ++i) {
        const int t = top_buffer ? top_index[r[i]] : -1;
        if (t >= 0) top_buffer[t + static_cast<Long>(c) * top_columns] -= W[i + static_cast<Long>(c) * below];
        else Y[r[i] + static_cast<Long>(c) * n] -= W[i + static_cast<Long>(c) * below];
      }
  };
  if (node_threads == 0) return rows_below(0, below);
  run_tasks(slices_of(below), node_threads,
            [&](int t, int) { rows_below(slice_start(below, t), slice_start(below, t + 1)); });
}

// Backward step of supernode s with U (or L^T when transposed): its rows
// below (already solved) gathered, then its diagonal block. node_threads > 0
// (the top supernodes): the block's rows in slices shared by the threads.
void SupernodalLU::Impl::backward_node(int s, double* Y, int nrhs, bool transposed, std::vector<double>& G,
                                       int node_threads) const {
  const int k1 = super[s], nscol = super[s + 1] - k1;
  const Long psi = pi[s], nsrow = pi[s + 1] - psi;
  const int lda = static_cast<int>(nsrow), below = static_cast<int>(nsrow - nscol);
  const double* L = Lx.data() + px[s];
  if (below > 0) {
    G.resize(static_cast<size_t>(below) * nrhs);
    const int* r = rows.data() + psi + nscol;
    for (int c = 0; c < nrhs; ++c)
      for (int i = 0; i < below; ++i) G[i + static_cast<Long>(c) * below] = Y[r[i] + static_cast<Long>(c) * n];
    const double* P = transposed ? L + nscol : Ux.data() + ux[s];
    const int ldp = transposed ? lda : below;
    auto columns = [&](int j1, int j2) {
      gemm('T', 'N', j2 - j1, nrhs, below, -1, P + static_cast<Long>(j1) * ldp, ldp, G.data(), below, 1,
           Y + k1 + j1, n);
    };
    if (node_threads == 0) columns(0, nscol);
    else
      run_tasks(slices_of(nscol), node_threads,
                [&](int t, int) { columns(slice_start(nscol, t), slice_start(nscol, t + 1)); });
  }
  if (transposed) trsm('L', 'L', 'T', 'U', nscol, nrhs, L, lda, Y + k1, n);
  else trsm('L', 'U', 'N', 'N', nscol, nrhs, L, lda, Y + k1, n);
}

// Threads for a top supernode's solve steps: its panels' entries as the
// work (a multiply-add each per right-hand side); below about a million
// one thread, since a thread costs tens of microseconds.
int SupernodalLU::Impl::top_threads(int s) const {
  const double entries = static_cast<double>(pi[s + 1] - pi[s]) * (super[s + 1] - super[s]);
  return entries > 1e6 ? threads : 1;
}

// A Y = B (or A^T Y = B) in place, as the supernodal Cholesky's solve: the
// subtrees forward in parallel (their updates of top rows summed privately,
// then added subtree by subtree in a fixed order), the top supernodes
// forward and backward, the subtrees backward in parallel (each reads only
// rows of its own subtree and of the top).
void SupernodalLU::Impl::solve_in_place(double* Y, int nrhs, bool transposed) const {
  const int tasks = static_cast<int>(schedule.subtrees.size());
  std::vector<std::vector<double>> buffers(tasks);
  std::vector<std::vector<double>> scratch(threads);
  run_tasks(tasks, threads, [&](int t, int worker) {
    const auto [first, last] = schedule.subtrees[t];
    const bool reaches_top = parent[last] >= 0;
    if (reaches_top) buffers[t].assign(static_cast<size_t>(top_columns) * nrhs, 0.0);
    for (int s = first; s <= last; ++s)
      forward_node(s, Y, nrhs, transposed, reaches_top ? buffers[t].data() : nullptr, scratch[worker], 0);
  });
  for (int t = 0; t < tasks; ++t) {
    if (buffers[t].empty()) continue;
    for (int s : schedule.top)
      for (int k = super[s]; k < super[s + 1]; ++k)
        for (int c = 0; c < nrhs; ++c)
          Y[k + static_cast<Long>(c) * n] += buffers[t][top_index[k] + static_cast<Long>(c) * top_columns];
  }
  for (int s : schedule.top) forward_node(s, Y, nrhs, transposed, nullptr, scratch[0], top_threads(s));
  for (auto it = schedule.top.rbegin(); it != schedule.top.rend(); ++it)
    backward_node(*it, Y, nrhs, transposed, scratch[0], top_threads(*it));
  run_tasks(tasks, threads, [&](int t, int worker) {
    const auto [first, last] = schedule.subtrees[t];
    for (int s = last; s >= first; --s) backward_node(s, Y, nrhs, transposed, scratch[worker], 0);
  });
}

Eigen::MatrixXd SupernodalLU::solve(const Eigen::MatrixXd& B, bool transposed) const {
  const Impl& s = *impl_;
  if (s.Lx.empty() && s.n > 0) throw_numerical("internal: supernodal LU solve before a successful factor");
  const int nrhs = static_cast<int>(B.cols());
  Eigen::MatrixXd Y(s.n, nrhs);
  for (int k = 0; k < s.n; ++k) Y.row(k) = B.row(s.perm[k]);
  {
    SolverThreads one_blas_thread;  // the parallelism is ours: one BLAS thread per worker
    s.solve_in_place(Y.data(), nrhs, transposed);
  }
  Eigen::MatrixXd X(s.n, nrhs);
  for (int k = 0; k < s.n; ++k) X.row(s.perm[k]) = Y.row(k);
  return X;
}

double SupernodalLU::factor_nonzeros() const {
  return impl_->Lx.empty() ? 0 : static_cast<double>(impl_->Lx.size() + impl_->Ux.size());
}
double SupernodalLU::flops() const { return impl_->flops; }
int SupernodalLU::split_supernodes() const { return impl_->split; }
double SupernodalLU::top_flops() const { return impl_->top_flops; }
double SupernodalLU::serial_flops() const { return impl_->serial_flops; }
std::vector<double> SupernodalLU::factor_values() const {
  std::vector<double> v(impl_->Lx.begin(), impl_->Lx.end());
  v.insert(v.end(), impl_->Ux.begin(), impl_->Ux.end());
  return v;
}

}  // namespace intrinsic::detail

#endif
