// Fill-reducing orderings for the mesh systems (internal).
//
// Level-set nested dissection: a mesh graph is nearly planar, so a middle
// level of a breadth-first search from a pseudo-peripheral vertex is a short
// vertex separator (a curve across the piece). Ordering both halves first and
// the separator last, recursively, gives fill within a small factor of METIS
// at a fraction of its cost (George 1973; like geometric nested dissection,
// but on the graph instead of coordinates so that any matrix of
// the solver can be ordered).
#pragma once

#include <vector>

#include "intrinsic/linear_solver.h"

namespace intrinsic::detail {

// Permutation perm of 0..n-1 (perm[k] = index of the k-th pivot) for the
// symmetric pattern of the square matrix A (A's pattern must be symmetric, as
// every mesh matrix here is; the diagonal is ignored). Deterministic.
std::vector<int> level_set_nested_dissection(const SparseMatrix& A, int leaf_size = 64);

}  // namespace intrinsic::detail
