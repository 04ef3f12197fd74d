// b - A x for a real sparse matrix A (both triangles stored) to about twice
// double precision: the residual of the benchmarks' exact references for
// the natural map (intrinsic_bench, natural_accuracy_bench). Written apart
// from the library's complex residual (src/solve/hermitian_residual.cpp) so
// that a reference does not share its code: each product a x split exactly
// into p + e (Dekker's product on Veltkamp's 26-bit halves), each row's sum
// compensated (Knuth's two-sum; Ogita, Rump and Oishi's Dot2), one
// thread, column order. A long-double sum is not enough: its 2^-64
// rounding moves the 1M-vertex natural map by ~1e-11
// (docs/performance.md#the-natural-map-a-complex-hermitian-factor).
#pragma once

#include <Eigen/Sparse>
#include <vector>

namespace intrinsic::bench {

inline Eigen::VectorXd compensated_residual(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& x,
                                            const Eigen::VectorXd& b) {
  const Eigen::Index m = A.rows();
  std::vector<double> s(b.data(), b.data() + m), c(static_cast<size_t>(m), 0.0);
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it) {
      const double a = -it.value(), y = x[j], p = a * y;
      const double ca = 134217729.0 * a, cy = 134217729.0 * y;
      const double ah = ca - (ca - a), al = a - ah, yh = cy - (cy - y), yl = y - yh;
      const double e = al * yl - (((p - ah * yh) - al * yh) - ah * yl);
      const Eigen::Index i = it.row();
      const double t = s[i] + p, z = t - s[i];
      c[i] += ((s[i] - (t - z)) + (p - z)) + e;
      s[i] = t;
    }
  Eigen::VectorXd r(m);
  for (Eigen::Index i = 0; i < m; ++i) r[i] = s[i] + c[i];
  return r;
}

}  // namespace intrinsic::bench
