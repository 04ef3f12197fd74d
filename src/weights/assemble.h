// Assembly of the weight matrix K (internal) of a method: K_ij = -w_ij, K_ii = sum_j w_ij
// (so K u = 0 is docs/maths.md §1.4's "M u = 0" up to sign, and the conformal K is positive
// semi-definite), and its split into free and fixed blocks for elimination.
#pragma once

#include <vector>

#include "solve/linear_solver.h"
#include "intrinsic/weights.h"

namespace intrinsic {

// n x n matrix of the method on faces F of positions V (n = V.rows()).
SparseMatrix assemble_weight_matrix(const MatrixX3d& V, const MatrixX3i& F, const WeightOptions& w);

// Index maps between the vertices and the free/fixed unknowns.
struct Partition {
  std::vector<int> free_index;   // per vertex: row among free unknowns or -1
  std::vector<int> fixed_index;  // per vertex: column among fixed or -1
  std::vector<int> free_vertices, fixed_vertices;
};
Partition partition(int num_vertices, const std::vector<char>& is_fixed, const std::vector<char>& is_used);

// K_II and K_IB of K for the partition.
void split_matrix(const SparseMatrix& K, const Partition& p, SparseMatrix& K_II, SparseMatrix& K_IB);

}  // namespace intrinsic
