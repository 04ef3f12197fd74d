// Left-looking supernodal Cholesky with subtree parallelism (see
// supernodal_cholesky.h). The loop over a supernode's descendants follows
// CHOLMOD's (t_cholmod_super_numeric.c), but the descendants of each
// supernode are listed once after the analysis, in ascending order, instead
// of linked as they finish: the order of each supernode's updates is then
// fixed whatever runs in parallel, and threads never share a list.
//
// The scalar T is double (L L^T) or std::complex<double> (L L^H, the
// natural map's Hermitian form): the code is the same, with the adjoint
// ('C') where the real code transposes and zherk for dsyrk.
#include "solve/supernodal_cholesky.h"

#ifdef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <memory>
#include <type_traits>
#include <vector>

#include "intrinsic/error.h"
#include "solve/solver_threads.h"
#include "solve/suitesparse.h"
#include "solve/supernodal_blas.h"
#include "solve/supernodal_schedule.h"
#include "util/parallel_for.h"
#include "util/stopwatch.h"

namespace intrinsic::detail {
namespace {

using Long = std::int64_t;

// A worker's scratch: where each row of the current supernode sits in its
// panel, and room for one update block.
template <class T>
struct Workspace {
  std::vector<int> map;
  std::vector<T> work;
};

// 'T' for real panels, 'C' (conjugate transpose) for complex ones.
template <class T>
constexpr char kAdjoint = std::is_same_v<T, double> ? 'T' : 'C';

// C := alpha A A^T (real) or alpha A A^H (complex) on C's lower triangle.
void rank_k_lower(int n, int k, double alpha, const double* a, int lda, double beta, double* c, int ldc) {
  blas::syrk_lower(n, k, alpha, a, lda, beta, c, ldc);
}
void rank_k_lower(int n, int k, double alpha, const std::complex<double>* a, int lda, double beta,
                  std::complex<double>* c, int ldc) {
  blas::herk_lower(n, k, alpha, a, lda, beta, c, ldc);
}

bool finite_pivot(double d) { return std::isfinite(d); }
bool finite_pivot(std::complex<double> d) { return std::isfinite(d.real()); }

// The analysis (its ordering) needs a real matrix with both triangles: a
// real A is given so; a complex one may hold its lower triangle only (the
// natural map's, to keep half), so the magnitudes of that triangle are
// mirrored into a temporary, freed before the numeric factorization.
// Built in two passes straight into compressed storage: column j gets the
// mirrors of the rows j of earlier columns (ascending), then its own rows
// >= j (ascending), so its rows come out sorted.
SparseMatrix symmetric_pattern(const Eigen::SparseMatrix<std::complex<double>>& A) {
  using Complex = Eigen::SparseMatrix<std::complex<double>>;
  const Eigen::Index n = A.outerSize();
  SparseMatrix full(A.rows(), A.cols());
  std::vector<int> count(static_cast<size_t>(n) + 1, 0);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Complex::InnerIterator it(A, j); it; ++it)
      if (it.row() >= j) {
        ++count[j];
        if (it.row() > j) ++count[it.row()];
      }
  int* outer = full.outerIndexPtr();
  outer[0] = 0;
  for (Eigen::Index j = 0; j < n; ++j) outer[j + 1] = outer[j] + count[j];
  full.resizeNonZeros(outer[n]);
  std::vector<int> next(outer, outer + n);
  int* row = full.innerIndexPtr();
  double* value = full.valuePtr();
  for (Eigen::Index j = 0; j < n; ++j)
    for (Complex::InnerIterator it(A, j); it; ++it) {
      if (it.row() < j) continue;
      const double x = std::abs(it.value());
      row[next[j]] = static_cast<int>(it.row());
      value[next[j]++] = x;
      if (it.row() > j) {
        row[next[it.row()]] = static_cast<int>(j);
        value[next[it.row()]++] = x;
      }
    }
  return full;
}

bool analyse(const SparseMatrix& A, SupernodalSymbolic& S, const SupernodeRelaxation& relax) {
  return supernodal_analysis(A, S, relax);
}
bool analyse(const Eigen::SparseMatrix<std::complex<double>>& A, SupernodalSymbolic& S,
             const SupernodeRelaxation& relax) {
  return supernodal_analysis(symmetric_pattern(A), S, relax);
}

// An allocator that leaves new elements uninitialised (for double and
// std::complex<double> only): the panels are zeroed in parallel instead
// (assemble), so their pages are first touched on both cores rather than
// by one thread's zero fill (1.15 GB at 1M vertices for the complex factor).
template <class T>
struct Uninitialised : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = Uninitialised<U>;
  };
  Uninitialised() = default;
  template <class U>
  Uninitialised(const Uninitialised<U>&) {}
  template <class U>
  void construct(U*) {}
};

double conj_of(double x) { return x; }
std::complex<double> conj_of(std::complex<double> z) { return std::conj(z); }

}  // namespace

template <class T>
struct SupernodalCholeskyOf<T>::Impl {
  using Sparse = Eigen::SparseMatrix<T>;
  static constexpr char kH = kAdjoint<T>;
  int threads = 1;
  SupernodeRelaxation relax = std::is_same_v<T, double> ? SupernodeRelaxation() : kComplexRelaxation;
  SupernodalSymbolic S;
  std::vector<T, Uninitialised<T>> Lx;  // panels, column-major nsrow x nscol
  DescendantLists updates;  // who updates each supernode, in the fixed order
  SupernodalSchedule schedule;
  std::vector<int> top_index;  // a top supernode's column -> its row in the solve's buffers, else -1
  int top_columns = 0;
  double flops = 0;

  void make_schedule();
  bool assemble(const Sparse& A);
  void update_block(int s, int c1, int c2, const int* map, std::vector<T>& work);
  bool factor_node(int s, Workspace<T>& ws, int node_threads);
  bool numeric(const Sparse& A);
  void forward_node(int s, T* Y, int nrhs, T* top_buffer, std::vector<T>& W) const;
  void backward_node(int s, T* Y, int nrhs, std::vector<T>& G) const;
  void solve_in_place(T* Y, int nrhs) const;
};

// The subtree split, costed by each supernode's flops (CHOLMOD's count:
// the square of each column's length), and the flop total.
template <class T>
void SupernodalCholeskyOf<T>::Impl::make_schedule() {
  std::vector<double> cost(S.nsuper, 0.0);
  flops = 0;
  for (int s = 0; s < S.nsuper; ++s) {
    const double nsrow = static_cast<double>(S.nsrow(s));
    for (int j = 0; j < S.nscol(s); ++j) cost[s] += (nsrow - j) * (nsrow - j);
    flops += cost[s];
  }
  schedule = subtree_schedule(S, cost);
  top_index.assign(S.n, -1);
  top_columns = 0;
  for (int s : schedule.top)
    for (int k = S.super[s]; k < S.super[s + 1]; ++k) top_index[k] = top_columns++;
}

// The panels start as the lower triangle of C = P^T A P, from A's lower
// triangle alone (its upper one, if stored, is the mirror): an entry that
// the permutation moves above the diagonal goes to its mirror position,
// conjugated (Hermitian A). Each position is written by one entry, so the
// columns can be filled in parallel. False when an entry falls outside the
// factor's pattern.
template <class T>
bool SupernodalCholeskyOf<T>::Impl::assemble(const Sparse& A) {
  std::vector<int> iperm(S.n);
  for (int k = 0; k < S.n; ++k) iperm[S.perm[k]] = k;
  Lx.resize(static_cast<size_t>(S.px[S.nsuper]));
  parallel_for(S.px[S.nsuper], [&](std::int64_t begin, std::int64_t end) {
    std::fill(Lx.data() + begin, Lx.data() + end, T(0));
  }, 1 << 20);
  bool ok = true;
  std::atomic<bool> outside{false};
  parallel_for(S.n, [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t j = begin; j < end; ++j) {
      for (typename Sparse::InnerIterator it(A, static_cast<int>(j)); it; ++it) {
        if (it.row() < j) continue;
        const int ri = iperm[it.row()], ci = iperm[j];
        const int r = std::max(ri, ci), c = std::min(ri, ci), sc = S.super_of[c];
        const int* first = S.rows.data() + S.pi[sc];
        const int* last = S.rows.data() + S.pi[sc + 1];
        const int* at = std::lower_bound(first, last, r);
        if (at == last || *at != r) { outside = true; return; }
        Lx[S.px[sc] + (c - S.super[sc]) * S.nsrow(sc) + (at - first)] = ri >= ci ? it.value() : conj_of(it.value());
      }
    }
  }, 20000);
  ok = !outside;
  return ok;
}

// Subtracts from columns [c1, c2) of supernode s (local numbering) the
// updates of all its descendants, in ascending order: with d's rows from the
// first in those columns split into the n1 among them and the rest,
// L_s[:, c1:c2] -= L_d[rows] L_d[cols]^T (^H if complex; dsyrk/zherk on the
// n1 x n1 block, dgemm below). map: each row's position in s's panel.
template <class T>
void SupernodalCholeskyOf<T>::Impl::update_block(int s, int c1, int c2, const int* map, std::vector<T>& work) {
  const int k1 = S.super[s];
  const Long nsrow = S.nsrow(s);
  T* Ls = Lx.data() + S.px[s];
  for (Long u = updates.start[s]; u < updates.start[s + 1]; ++u) {
    const int d = updates.d[u];
    const Long pdi = S.pi[d], ndrow = S.nsrow(d);
    const int ndcol = S.nscol(d);
    const int* drows = S.rows.data() + pdi;
    // d's rows from updates.p are ascending: those in [k1 + c1, k1 + c2) first.
    const int* q1 = std::lower_bound(drows + updates.p[u], drows + ndrow, k1 + c1);
    const int* q2 = std::lower_bound(q1, drows + ndrow, k1 + c2);
    const int n1 = static_cast<int>(q2 - q1), n2 = static_cast<int>(drows + ndrow - q1);
    if (n1 == 0) continue;
    const T* Ld = Lx.data() + S.px[d] + (q1 - drows);
    const int ld = static_cast<int>(ndrow);
    work.resize(static_cast<size_t>(n2) * n1);
    T* C = work.data();
    rank_k_lower(n1, ndcol, 1, Ld, ld, 0, C, n2);
    blas::gemm('N', kH, n2 - n1, n1, ndcol, 1, Ld + n1, ld, Ld, ld, 0, C + n1, n2);
    for (int j = 0; j < n1; ++j) {
      T* column = Ls + static_cast<Long>(q1[j] - k1) * nsrow;
      const T* c = C + static_cast<Long>(j) * n2;
      for (int i = j; i < n2; ++i) column[map[q1[i]]] -= c[i];
    }
  }
}

// Supernode s: its descendants' updates, column block by column block, then
// a right-looking blocked Cholesky of its panel (dpotrf on each diagonal
// block, dtrsm below it, dsyrk/dgemm on the blocks to its right). Each step's
// blocks are independent, so node_threads threads share them.
template <class T>
bool SupernodalCholeskyOf<T>::Impl::factor_node(int s, Workspace<T>& ws, int node_threads) {
  const int k1 = S.super[s], nscol = S.nscol(s);
  const Long psi = S.pi[s], nsrow = S.nsrow(s);
  for (Long r = 0; r < nsrow; ++r) ws.map[S.rows[psi + r]] = static_cast<int>(r);
  const int blocks = column_blocks(nscol);
  std::vector<std::vector<T>> works(node_threads > 1 ? node_threads : 0);
  auto work_of = [&](int worker) -> std::vector<T>& { return worker == 0 ? ws.work : works[worker]; };
  run_tasks(blocks, node_threads, [&](int b, int worker) {
    update_block(s, block_start(nscol, b), block_start(nscol, b + 1), ws.map.data(), work_of(worker));
  });
  (void)k1;
  T* L = Lx.data() + S.px[s];
  const int lda = static_cast<int>(nsrow);
  for (int b = 0; b < blocks; ++b) {
    const int c1 = block_start(nscol, b), c2 = block_start(nscol, b + 1), w = c2 - c1;
    T* D = L + static_cast<Long>(c1) * lda + c1;
    if (!blas::potrf_lower(w, D, lda)) return false;
    for (int i = 0; i < w; ++i)
      if (!finite_pivot(D[i + static_cast<Long>(i) * lda])) return false;
    // Rows below the diagonal block, in slices of 256 rows.
    const int below = static_cast<int>(nsrow - c2), slices = std::max(1, below / 256);
    run_tasks(slices, node_threads, [&](int t, int) {
      const int r1 = static_cast<int>(static_cast<Long>(below) * t / slices);
      const int r2 = static_cast<int>(static_cast<Long>(below) * (t + 1) / slices);
      blas::trsm('R', 'L', kH, 'N', r2 - r1, w, D, lda, D + w + r1, lda);
    });
    run_tasks(blocks - b - 1, node_threads, [&](int t, int) {
      const int j1 = block_start(nscol, b + 1 + t), j2 = block_start(nscol, b + 2 + t);
      const T* Lj = L + static_cast<Long>(c1) * lda + j1;  // rows j1.., columns c1..c2
      T* Tj = L + static_cast<Long>(j1) * lda + j1;
      rank_k_lower(j2 - j1, w, -1, Lj, lda, 1, Tj, lda);
      blas::gemm('N', kH, static_cast<int>(nsrow - j2), j2 - j1, w, -1, Lj + (j2 - j1), lda, Lj, lda, 1,
                 Tj + (j2 - j1), lda);
    });
  }
  return true;
}

template <class T>
bool SupernodalCholeskyOf<T>::Impl::numeric(const Sparse& A) {
  if (!assemble(A)) return false;
  const int workers = threads;
  std::vector<Workspace<T>> ws(workers);
  for (Workspace<T>& w : ws) w.map.assign(S.n, 0);
  std::vector<char> failed(schedule.subtrees.size(), 0);
  run_tasks(static_cast<int>(schedule.subtrees.size()), workers, [&](int t, int worker) {
    const auto [first, last] = schedule.subtrees[t];
    for (int s = first; s <= last; ++s)
      if (!factor_node(s, ws[worker], 1)) { failed[t] = 1; return; }
  });
  for (char f : failed)
    if (f) return false;
  for (int s : schedule.top) {
    const double nsrow = static_cast<double>(S.nsrow(s)), nscol = S.nscol(s);
    const int node_threads = nscol * nscol * nsrow > kParallelFlops ? workers : 1;
    if (!factor_node(s, ws[0], node_threads)) return false;
  }
  return true;
}

template <class T>
SupernodalCholeskyOf<T>::SupernodalCholeskyOf(int threads) : impl_(std::make_unique<Impl>()) {
  impl_->threads = threads > 0 ? threads : hardware_threads();
}
template <class T>
SupernodalCholeskyOf<T>::~SupernodalCholeskyOf() = default;
template <class T>
void SupernodalCholeskyOf<T>::set_relaxation(const SupernodeRelaxation& relax) {
  impl_->relax = relax;
}

template <class T>
bool SupernodalCholeskyOf<T>::factor(const Sparse& A, SupernodalSymbolic* analysed) {
  Impl& s = *impl_;
  if (A.rows() != A.cols() || !A.isCompressed())
    throw_numerical("internal: supernodal Cholesky needs a compressed square matrix");
  const auto t0 = std::chrono::steady_clock::now();
  decltype(s.Lx)().swap(s.Lx);  // frees the previous factor before the analysis
  if (analysed) s.S = std::move(*analysed);
  else if (!analyse(A, s.S, s.relax)) return false;
  s.updates = descendant_lists(s.S);
  s.make_schedule();
  analyse_ms = ms_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  bool ok;
  {
    SolverThreads one_blas_thread;  // the parallelism is ours: one BLAS thread per worker
    ok = s.numeric(A);
  }
  factor_ms = ms_since(t1);
  if (!ok) decltype(s.Lx)().swap(s.Lx);
  return ok;
}

// Forward step of supernode s on Y (n x nrhs, leading dimension n): its
// diagonal block, then its rows below get the block's contribution; rows of
// top supernodes go to top_buffer instead when one is given (a subtree's
// private sum, added in a fixed order afterwards).
template <class T>
void SupernodalCholeskyOf<T>::Impl::forward_node(int s, T* Y, int nrhs, T* top_buffer, std::vector<T>& W) const {
  const int n = S.n, k1 = S.super[s], nscol = S.nscol(s);
  const Long psi = S.pi[s], nsrow = S.nsrow(s);
  const int lda = static_cast<int>(nsrow), below = static_cast<int>(nsrow - nscol);
  const T* L = Lx.data() + S.px[s];
  blas::trsm('L', 'L', 'N', 'N', nscol, nrhs, L, lda, Y + k1, n);
  if (below == 0) return;
  W.resize(static_cast<size_t>(below) * nrhs);
  blas::gemm('N', 'N', below, nrhs, nscol, 1, L + nscol, lda, Y + k1, n, 0, W.data(), below);
  const int* rows = S.rows.data() + psi + nscol;
  for (int c = 0; c < nrhs; ++c)
    for (int i = 0; i < below; ++i) {
      const int r = rows[i], t = top_buffer ? top_index[r] : -1;
      if (t >= 0) top_buffer[t + static_cast<Long>(c) * top_columns] -= W[i + static_cast<Long>(c) * below];
      else Y[r + static_cast<Long>(c) * n] -= W[i + static_cast<Long>(c) * below];
    }
}

// Backward step of supernode s: its rows below (already solved) gathered,
// then its diagonal block transposed (its adjoint if complex).
template <class T>
void SupernodalCholeskyOf<T>::Impl::backward_node(int s, T* Y, int nrhs, std::vector<T>& G) const {
  const int n = S.n, k1 = S.super[s], nscol = S.nscol(s);
  const Long psi = S.pi[s], nsrow = S.nsrow(s);
  const int lda = static_cast<int>(nsrow), below = static_cast<int>(nsrow - nscol);
  const T* L = Lx.data() + S.px[s];
  if (below > 0) {
    G.resize(static_cast<size_t>(below) * nrhs);
    const int* rows = S.rows.data() + psi + nscol;
    for (int c = 0; c < nrhs; ++c)
      for (int i = 0; i < below; ++i) G[i + static_cast<Long>(c) * below] = Y[rows[i] + static_cast<Long>(c) * n];
    blas::gemm(kH, 'N', nscol, nrhs, below, -1, L + nscol, lda, G.data(), below, 1, Y + k1, n);
  }
  blas::trsm('L', 'L', kH, 'N', nscol, nrhs, L, lda, Y + k1, n);
}

// L L^T Y = B in place: the subtrees forward in parallel (their updates of
// top rows summed privately, then added subtree by subtree), the top
// supernodes forward and backward, the subtrees backward in parallel.
template <class T>
void SupernodalCholeskyOf<T>::Impl::solve_in_place(T* Y, int nrhs) const {
  // A solve of under kParallelFlops runs on the calling thread: the two
  // thread starts cost more than it (the atlas solves thousands of small
  // charts: 4,090 thread starts on decimated-knight, 300 without).
  const int workers = 2.0 * static_cast<double>(Lx.size()) * nrhs > kParallelFlops ? threads : 1;
  const int tasks = static_cast<int>(schedule.subtrees.size());
  std::vector<std::vector<T>> buffers(tasks);
  std::vector<std::vector<T>> scratch(workers);
  run_tasks(tasks, workers, [&](int t, int worker) {
    const auto [first, last] = schedule.subtrees[t];
    const bool reaches_top = S.parent[last] >= 0;
    if (reaches_top) buffers[t].assign(static_cast<size_t>(top_columns) * nrhs, T(0));
    for (int s = first; s <= last; ++s) forward_node(s, Y, nrhs, reaches_top ? buffers[t].data() : nullptr, scratch[worker]);
  });
  for (int s : schedule.top)  // top columns get the subtrees' sums before their own step
    for (int k = S.super[s]; k < S.super[s + 1]; ++k)
      for (int c = 0; c < nrhs; ++c)
        for (int t = 0; t < tasks; ++t)
          if (!buffers[t].empty()) Y[k + static_cast<Long>(c) * S.n] += buffers[t][top_index[k] + static_cast<Long>(c) * top_columns];
  for (int s : schedule.top) forward_node(s, Y, nrhs, nullptr, scratch[0]);
  for (auto it = schedule.top.rbegin(); it != schedule.top.rend(); ++it) backward_node(*it, Y, nrhs, scratch[0]);
  run_tasks(tasks, workers, [&](int t, int worker) {
    const auto [first, last] = schedule.subtrees[t];
    for (int s = last; s >= first; --s) backward_node(s, Y, nrhs, scratch[worker]);
  });
}

template <class T>
typename SupernodalCholeskyOf<T>::Dense SupernodalCholeskyOf<T>::solve(const Dense& B) const {
  const Impl& s = *impl_;
  if (s.Lx.empty() && s.S.n > 0) throw_numerical("internal: supernodal Cholesky solve before a successful factor");
  const int n = s.S.n, nrhs = static_cast<int>(B.cols());
  Dense Y(n, nrhs);
  for (int k = 0; k < n; ++k) Y.row(k) = B.row(s.S.perm[k]);
  {
    SolverThreads one_blas_thread;
    s.solve_in_place(Y.data(), nrhs);
  }
  Dense X(n, nrhs);
  for (int k = 0; k < n; ++k) X.row(s.S.perm[k]) = Y.row(k);
  return X;
}

template <class T>
double SupernodalCholeskyOf<T>::factor_nonzeros() const {
  return static_cast<double>(impl_->Lx.size());
}
template <class T>
double SupernodalCholeskyOf<T>::flops() const {
  return impl_->flops * (std::is_same_v<T, double> ? 1 : 4);
}

template class SupernodalCholeskyOf<double>;
template class SupernodalCholeskyOf<std::complex<double>>;

}  // namespace intrinsic::detail

#endif
