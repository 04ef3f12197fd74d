// Fill-reducing orderings for the mesh systems (internal).
//
// Level-set nested dissection: a mesh graph is nearly planar, so a middle
// level of a breadth-first search from a pseudo-peripheral vertex is a short
// vertex separator (a curve across the piece); a vertex-separator
// Fiduccia-Mattheyses pass then shortens it (ordering_refine.h), and each
// half is searched from a corner (an end of its parent's separator) and from
// the vertex farthest from it, keeping the shorter cut. Ordering both halves
// first and the separator last, recursively, gives flops within ~10% of
// METIS's on the mesh systems at a fraction of its cost (George 1973; like
// geometric nested dissection, but on the graph instead of coordinates so
// that any matrix of the solver can be ordered; docs/perf-nd.md).
#pragma once

#include <vector>

#include "solve/linear_solver.h"

namespace intrinsic::detail {

// Permutation perm of 0..n-1 (perm[k] = index of the k-th pivot) for the
// symmetric pattern of the square matrix A (A's pattern must be symmetric, as
// every mesh matrix here is; the diagonal is ignored). Deterministic: the
// same for any thread count (it uses the cores, parallel_for.h's
// thread_limit, above ~40k vertices). Pieces of at most compact_below
// vertices are dissected in a compact copy of their own subgraph (-1: the
// default size; 0: never), which changes the time only, never the
// permutation (the tests force it on and off).
std::vector<int> level_set_nested_dissection(const SparseMatrix& A, int leaf_size = 64, int compact_below = -1);

}  // namespace intrinsic::detail
