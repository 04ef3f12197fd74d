// The natural map's system as an n x n complex Hermitian matrix (to halve the work;
// docs/maths.md §3.6). With z = u + i v the energy E_D - A is z^H M z for
// M = K + iB, K the cotangent matrix and B the antisymmetric boundary
// coupling of the area term; its real form, the 2n x 2n matrix the
// Parameterizer assembles in blocked ordering, is A = [K -B; B K]. Factoring
// M instead of A orders and analyses the n-vertex graph (the conformal map's)
// rather than a 2n graph, and the complex supernodal kernels do the work in
// half the real flops (see
// docs/performance.md#the-natural-map-a-complex-hermitian-factor).
#pragma once

#include <complex>

#include "solve/linear_solver.h"

namespace intrinsic::detail {

using ComplexSparse = Eigen::SparseMatrix<std::complex<double>>;

// M = K + iB (both triangles) when A (2m x 2m) is exactly [K -B; B K] with K
// symmetric and B antisymmetric; false (M untouched) otherwise.
bool hermitian_from_real_form(const SparseMatrix& A, ComplexSparse& M);

// M Z from M's lower triangle alone (M Hermitian): what a refinement
// residual needs, without keeping the 2m x 2m real form (four times the
// entries) beside the factor.
Eigen::MatrixXcd hermitian_lower_product(const ComplexSparse& lower, const Eigen::MatrixXcd& Z);

// B - M Z from M's lower triangle, each entry to about twice double
// precision (exact products, compensated sums) and rounded once: the
// residual of the natural map's mixed-precision refinement
// (LinearSolver::set_ill_conditioned), which gains accuracy only as far as
// the residual is more exact than the solve. Rows are split over the cores
// (detail::thread_limit); the result does not depend on how many. With
// `backward_error`, also max_i |R|_i / (|M| |Z| + |B|)_i, complex moduli
// taken as |re| + |im| (hermitian_residual.cpp).
Eigen::MatrixXcd hermitian_lower_residual(const ComplexSparse& lower, const Eigen::MatrixXcd& Z,
                                          const Eigen::MatrixXcd& B, double* backward_error = nullptr);

// The real form [K -B; B K] (2m x 2m, compressed) of M = K + iB given with
// both triangles: hermitian_from_real_form's inverse (zero parts of M's
// entries give no entry: K or B had none there).
SparseMatrix real_form_from_hermitian(const ComplexSparse& M);

// Rows [top; bottom] (2m x k) as top + i bottom (m x k), and back.
Eigen::MatrixXcd complex_from_real_form(const Eigen::MatrixXd& X);
Eigen::MatrixXd real_form(const Eigen::MatrixXcd& Z);

}  // namespace intrinsic::detail
