// The weight matrix's assembly in its two stages (internal), for a caller
// that needs K's pattern before its values: the Parameterizer hands the free
// block of that pattern to the ordering thread (solve/ordering_ahead.h) and
// then fills the values in place, so the faces' adjacency is counted once.
// assemble_weight_matrix (intrinsic/assemble.h) is the two in a row.
#pragma once

#include "solve/linear_solver.h"
#include "intrinsic/weights.h"

namespace intrinsic::detail {

// K's pattern (docs/maths.md §2.3): n x n, every vertex's column holds itself
// and its face neighbours, rows ascending; the values are allocated, unset.
SparseMatrix weight_matrix_pattern(const MatrixX3i& F, int n);

// Writes K's values into a K holding weight_matrix_pattern(F, V.rows()).
void assemble_weight_values(const MatrixX3d& V, const MatrixX3i& F, const WeightOptions& w, SparseMatrix& K);

}  // namespace intrinsic::detail
