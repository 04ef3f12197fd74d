// The analysis of K_II's pattern ahead of its values (see ordering_ahead.h).
#include "solve/ordering_ahead.h"

#ifdef INTRINSIC_HAVE_SUITESPARSE

#include <algorithm>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "solve/ordering.h"
#include "solve/supernodal_cholesky.h"
#include "solve/supernodal_lu.h"
#include "util/parallel_for.h"

namespace intrinsic::detail {

// The counting pass of assemble_weight_matrix (src/weights/assemble.cpp),
// on the free vertices only: each face names two neighbours of each of its
// corners; sorted and deduplicated per column.
SparseMatrix free_block_pattern(const MatrixX3i& F, const std::vector<char>& is_known,
                                const std::vector<char>& is_used) {
  const int n = static_cast<int>(is_known.size());
  std::vector<int> free_index(n, -1);
  int nf = 0;
  for (int v = 0; v < n; ++v)
    if (is_used[v] && !is_known[v]) free_index[v] = nf++;
  std::vector<int> begin(nf + 1, 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (free_index[F(f, c)] >= 0) begin[free_index[F(f, c)] + 1] += 2;
  for (int j = 0; j < nf; ++j) begin[j + 1] += begin[j] + 1;
  std::vector<int> row(begin[nf]), fill(begin.begin(), begin.end() - 1);
  for (int j = 0; j < nf; ++j) row[fill[j]++] = j;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int j = free_index[F(f, c)];
      if (j < 0) continue;
      for (int d : {(c + 1) % 3, (c + 2) % 3})
        if (free_index[F(f, d)] >= 0) row[fill[j]++] = free_index[F(f, d)];
    }
  parallel_for(nf, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t j = first; j < last; ++j) std::sort(row.begin() + begin[j], row.begin() + fill[j]);
  });
  int out = 0;
  for (int j = 0; j < nf; ++j) {
    const int b = begin[j], e = fill[j];
    begin[j] = out;
    for (int k = b; k < e; ++k)
      if (k == b || row[k] != row[k - 1]) row[out++] = row[k];
  }
  begin[nf] = out;
  SparseMatrix P(nf, nf);
  P.resizeNonZeros(out);  // values allocated, never written nor read
  std::copy(begin.begin(), begin.end(), P.outerIndexPtr());
  std::copy(row.begin(), row.begin() + out, P.innerIndexPtr());
  return P;
}

AnalysisAhead::AnalysisAhead(const MatrixX3i& F, const std::vector<char>& is_known,
                             const std::vector<char>& is_used)
    : faces_future_(faces_done_.get_future()) {
  // The copies are the thread's; F is read until faces_done_.
  thread_ = std::thread([this, &F, known = is_known, used = is_used] { run(F, known, used); });
}

AnalysisAhead::~AnalysisAhead() {
  if (thread_.joinable()) thread_.join();
}

// Any failure (out of memory) leaves analysed_ false: factor() then
// analyses A itself, as without this.
void AnalysisAhead::run(const MatrixX3i& F, const std::vector<char>& is_known, const std::vector<char>& is_used) {
  bool released = false;
  try {
    pattern_ = free_block_pattern(F, is_known, is_used);
    released = true;
    faces_done_.set_value();
    if (pattern_.rows() > 0) {
      const std::vector<int> order = level_set_nested_dissection(pattern_);
      analysed_ = supernodal_analysis(pattern_, order, symbolic_);
    }
#ifdef __GLIBC__
    // The ordering's and the analysis's work arrays were freed into this
    // thread's malloc arena, which keeps them resident (about 100 MB at 1M
    // vertices) while the numeric factorization allocates anew: hand them
    // back to the system.
    malloc_trim(0);
#endif
  } catch (...) {
    analysed_ = false;
    if (!released) faces_done_.set_value();
  }
}

void AnalysisAhead::faces_released() {
  if (faces_future_.valid()) faces_future_.wait();
}

bool AnalysisAhead::take(const SparseMatrix& A, SupernodalSymbolic& out) {
  if (taken_) return false;
  taken_ = true;
  if (thread_.joinable()) thread_.join();
  const SparseMatrix& P = pattern_;
  const bool same = analysed_ && A.isCompressed() && A.rows() == P.rows() && A.cols() == P.cols() &&
                    A.nonZeros() == P.nonZeros() &&
                    std::equal(P.outerIndexPtr(), P.outerIndexPtr() + P.cols() + 1, A.outerIndexPtr()) &&
                    std::equal(P.innerIndexPtr(), P.innerIndexPtr() + P.nonZeros(), A.innerIndexPtr());
  if (same) {
    out = std::move(symbolic_);
    analysis_ahead_taken().fetch_add(1, std::memory_order_relaxed);
  }
  pattern_ = SparseMatrix();
  symbolic_ = SupernodalSymbolic();
  return same;
}

std::atomic<int>& analysis_ahead_min_vertices() {
  static std::atomic<int> min_vertices{20000};
  return min_vertices;
}

std::atomic<long>& analysis_ahead_taken() {
  static std::atomic<long> taken{0};
  return taken;
}

bool analysis_ahead_wanted(SolverKind kind, int vertices) {
#if defined(INTRINSIC_HAVE_SUPERNODAL_CHOLESKY) && defined(INTRINSIC_HAVE_SUPERNODAL_LU)
  return vertices >= analysis_ahead_min_vertices().load(std::memory_order_relaxed) &&
         (kind == SolverKind::Auto || kind == SolverKind::SupernodalCholesky || kind == SolverKind::SupernodalLU);
#else
  (void)kind;
  (void)vertices;
  return false;
#endif
}

}  // namespace intrinsic::detail

#endif
