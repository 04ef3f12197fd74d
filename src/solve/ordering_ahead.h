// The ordering and symbolic analysis of a fixed-boundary system computed
// ahead, on another thread, while the weights are assembled (internal).
//
// The fill-reducing ordering (ordering.h) and CHOLMOD's supernodal analysis
// (suitesparse.h) read only the pattern of A = K_II, and that pattern is
// known before any weight is: the vertex adjacency of the faces, plus the
// diagonal, restricted to the free vertices (docs/maths.md §2.3). The
// Parameterizer builds K's pattern, starts them on its free block before it
// assembles K's values into that pattern (so the adjacency is counted once),
// and LinearSolver::factor takes the result in place of analysing A
// (LinearSolver::set_analysis_ahead). On 2 cores the gain is where one side
// leaves a core idle: the top levels of the dissection and CHOLMOD's
// analysis run on one thread, and so does most of the assembly's pattern
// pass (docs/performance.md#symbolic-analysis).
//
// The result is the same bit for bit: the ordering and the analysis are
// deterministic functions of the pattern, and the analysis ahead is used only
// when A's compressed pattern is exactly the one analysed (compared entry by
// entry), else A is analysed as before.
#pragma once

#ifdef INTRINSIC_HAVE_SUITESPARSE

#include <atomic>
#include <exception>
#include <memory>
#include <thread>
#include <vector>

#include "solve/linear_solver.h"
#include "intrinsic/mesh.h"
#include "solve/suitesparse.h"

namespace intrinsic::detail {

// The pattern of K_II for the faces F (indices below is_known.size()): free
// vertex v (used, not known) is unknown free_index(v), numbered in vertex
// order as intrinsic::partition numbers them; column j holds the free
// neighbours of its vertex and itself, rows ascending. The values are left
// unset (never read).
// Built from the faces (util/vertex_adjacency.h), for a caller without K's
// pattern.
SparseMatrix free_block_pattern(const MatrixX3i& F, const std::vector<char>& is_known,
                                const std::vector<char>& is_used);
// The same pattern taken from K's (weights/assemble_stages.h: the vertex
// adjacency with the diagonal, compressed, over is_known.size() vertices),
// so that the faces' adjacency is counted once for both.
SparseMatrix free_block_pattern(const SparseMatrix& K, const std::vector<char>& is_known,
                                const std::vector<char>& is_used);

class AnalysisAhead {
 public:
  // Starts the ordering and analysis of a free block's pattern built
  // already (taken: `pattern` is left empty); no faces are read.
  explicit AnalysisAhead(SparseMatrix&& pattern);
  ~AnalysisAhead();  // waits for the thread
  AnalysisAhead(const AnalysisAhead&) = delete;
  AnalysisAhead& operator=(const AnalysisAhead&) = delete;

  // Waits for the analysis; true, with it moved into `out`, when A's
  // pattern is the one analysed and the analysis succeeded. Once only.
  bool take(const SparseMatrix& A, SupernodalSymbolic& out);

 private:
  void analyse();  // orders and analyses pattern_

  SparseMatrix pattern_;
  SupernodalSymbolic symbolic_;
  bool analysed_ = false;
  bool taken_ = false;
  std::thread thread_;
};

// Whether to analyse ahead for this solver choice: only the supernodal
// backends (Auto's choice for the fixed-boundary systems) use it, and only
// systems of at least analysis_ahead_min_vertices() vertices (20000 by
// default: below, the thread costs about what it saves). Tests and benches
// set that to 0 (always) or INT_MAX (never) to compare both paths.
bool analysis_ahead_wanted(SolverKind kind, int vertices);
std::atomic<int>& analysis_ahead_min_vertices();
// How many take() calls matched so far (process-wide): lets tests and
// benches see that the path ahead was the one taken.
std::atomic<long>& analysis_ahead_taken();

}  // namespace intrinsic::detail

#endif
