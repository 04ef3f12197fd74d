// Assembly of the weight matrix K (internal) of a method: K_ij = -w_ij, K_ii = sum_j w_ij
// (so K u = 0 is docs/maths.md §1.4's "M u = 0" up to sign, and the conformal K is positive
// semi-definite).
#pragma once

#include <vector>

#include "solve/linear_solver.h"
#include "solve/partition.h"  // the split of K, which callers of the assembly use
#include "intrinsic/weights.h"

namespace intrinsic {

// n x n matrix of the method on faces F of positions V (n = V.rows()).
SparseMatrix assemble_weight_matrix(const MatrixX3d& V, const MatrixX3i& F, const WeightOptions& w);

}  // namespace intrinsic
