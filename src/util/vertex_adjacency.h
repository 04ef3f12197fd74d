// The vertex adjacency pattern of a face list, restricted to a subset of the
// vertices with a new numbering: for each kept vertex, the kept vertices it
// shares a face with, sorted, without repeats, in compressed-column form.
// One counting sort serves the three places that need it: the weight
// matrix's pattern (weights/assemble.cpp: every vertex and itself,
// docs/maths.md §2.3), the edge list of the distortion measures
// (metrics/distortion.cpp: each edge once, from its smaller end) and the free
// block's pattern ordered ahead of the assembly (solve/ordering_ahead.cpp:
// the free vertices, numbered as intrinsic::partition numbers them).
//
// Each face names two neighbours of each of its corners. The faces are cut
// into parts that count and fill on all cores, each part into its own slots
// of each vertex's bucket; the order within a bucket then depends on the
// parts, but the sort that follows makes it canonical, so the pattern is the
// same on any number of threads.
#pragma once

#include <Eigen/Sparse>
#include <vector>

#include "intrinsic/mesh_data.h"

namespace intrinsic::detail {

// The solver's matrix type (intrinsic/linear_solver.h names it the same).
using SparseMatrix = Eigen::SparseMatrix<double>;

// Which neighbours a kept vertex's column holds.
enum class AdjacencyNeighbours {
  All,          // every kept neighbour
  AllAndSelf,   // every kept neighbour and the vertex itself (a matrix pattern with its diagonal)
  LargerOnly,   // only neighbours with a larger new number: each edge once, at its smaller end
};

// The pattern as a count x count compressed-column matrix: column k lists
// the rows of the new vertex k, ascending. The values are allocated but left
// unset. `number` gives each vertex of F its new number in [0, count), or -1
// to leave it out (faces may still name it; they add nothing to it nor it to
// them); an empty `number` keeps every vertex with its own number, and then
// F's indices must be below count.
SparseMatrix vertex_adjacency_pattern(const MatrixX3i& F, int count, const std::vector<int>& number,
                                      AdjacencyNeighbours which);

}  // namespace intrinsic::detail
