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
#include "util/vertex_adjacency.h"

namespace intrinsic::detail {

namespace {

// Free vertex v (used, not known) is unknown free_index[v], in vertex order
// as intrinsic::partition numbers them; -1 for the others.
std::vector<int> free_numbering(const std::vector<char>& is_known, const std::vector<char>& is_used, int& count) {
  const int n = static_cast<int>(is_known.size());
  std::vector<int> free_index(n, -1);
  count = 0;
  for (int v = 0; v < n; ++v)
    if (is_used[v] && !is_known[v]) free_index[v] = count++;
  return free_index;
}

}  // namespace

SparseMatrix free_block_pattern(const MatrixX3i& F, const std::vector<char>& is_known,
                                const std::vector<char>& is_used) {
  int nf = 0;
  const std::vector<int> free_index = free_numbering(is_known, is_used, nf);
  return vertex_adjacency_pattern(F, nf, free_index, AdjacencyNeighbours::AllAndSelf);
}

// Column by column, the free rows of each free vertex's column, renumbered;
// the numbering increases with the vertex, so the rows stay ascending.
// Counted and copied on all cores.
SparseMatrix free_block_pattern(const SparseMatrix& K, const std::vector<char>& is_known,
                                const std::vector<char>& is_used) {
  int nf = 0;
  const std::vector<int> free_index = free_numbering(is_known, is_used, nf);
  std::vector<int> column(nf);  // the vertex of each free unknown
  for (int v = 0; v < static_cast<int>(free_index.size()); ++v)
    if (free_index[v] >= 0) column[free_index[v]] = v;
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  SparseMatrix P(nf, nf);
  int* begin = P.outerIndexPtr();
  begin[0] = 0;
  parallel_for(nf, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t j = first; j < last; ++j) {
      int count = 0;
      for (int k = outer[column[j]]; k < outer[column[j] + 1]; ++k) count += free_index[inner[k]] >= 0;
      begin[j + 1] = count;
    }
  });
  for (int j = 0; j < nf; ++j) begin[j + 1] += begin[j];
  P.resizeNonZeros(begin[nf]);  // values allocated, never written nor read
  int* row = P.innerIndexPtr();
  parallel_for(nf, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t j = first; j < last; ++j) {
      int out = begin[j];
      for (int k = outer[column[j]]; k < outer[column[j] + 1]; ++k)
        if (free_index[inner[k]] >= 0) row[out++] = free_index[inner[k]];
    }
  });
  return P;
}

AnalysisAhead::AnalysisAhead(SparseMatrix&& pattern) {
  pattern_.swap(pattern);  // Eigen 3.4's SparseMatrix has no move: a swap takes it without a copy
  thread_ = std::thread([this] { analyse(); });
}

AnalysisAhead::~AnalysisAhead() {
  if (thread_.joinable()) thread_.join();
}

// Any failure (out of memory) leaves analysed_ false: factor() then
// analyses A itself, as without this.
void AnalysisAhead::analyse() {
  try {
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
  }
}

bool AnalysisAhead::take(const SparseMatrix& A, SupernodalSymbolic& out) {
  if (taken_) return false;
  taken_ = true;
  if (thread_.joinable()) thread_.join();
  // Kept although the Parameterizer's pattern comes from K's own
  // (free_block_pattern(K, ...)): A is K's free block as split_matrix
  // copies it, P the same block as free_block_pattern restricts it, two
  // separate codes reading the partition each their own way, so a pattern
  // of other faces, another known set or another numbering is refused. It
  // costs one pass over 7M ints at 1M vertices (a few ms).
  const SparseMatrix& P = pattern_;
  const bool same = analysed_ && A.isCompressed() && A.rows() == P.rows() && A.cols() == P.cols() &&
                    A.nonZeros() == P.nonZeros() &&
                    std::equal(P.outerIndexPtr(), P.outerIndexPtr() + P.cols() + 1, A.outerIndexPtr()) &&
                    std::equal(P.innerIndexPtr(), P.innerIndexPtr() + P.nonZeros(), A.innerIndexPtr());
  if (same) {
    out = std::move(symbolic_);
    analysis_ahead_taken().fetch_add(1, std::memory_order_relaxed);
  }
  SparseMatrix().swap(pattern_);  // frees it (assigning an empty SparseMatrix keeps the storage)
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
