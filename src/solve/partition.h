// The split of a system's unknowns into free and fixed ones and of its
// matrix into the free block and the free-by-fixed block (partition.cpp).
#pragma once

#include <vector>

#include "solve/linear_solver.h"

namespace intrinsic {

// A compressed-column matrix from its three arrays (column starts, row
// indices, values; rows sorted within each column).
SparseMatrix make_csc(int rows, int cols, const std::vector<int>& begin, std::vector<int>&& index,
                      std::vector<double>&& value);

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
