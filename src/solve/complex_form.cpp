// Real form <-> complex Hermitian form of the natural map's system (see
// complex_form.h; docs/maths.md §3.6).
#include "solve/complex_form.h"

#include <vector>

namespace intrinsic::detail {
namespace {

// A is [K -B; B K]: the right half mirrors the left half entry for entry
// (exactly: the Parameterizer assembles both halves from the same numbers),
// K is symmetric and B antisymmetric.
bool has_real_form(const SparseMatrix& A, Eigen::Index m) {
  Eigen::Index left = 0;
  for (Eigen::Index j = 0; j < m; ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      ++left;
      const Eigen::Index i = it.row();
      const double v = it.value();
      if (i < m) {  // K(i, j)
        if (A.coeff(i + m, j + m) != v || A.coeff(j, i) != v) return false;
      } else {  // B(i - m, j)
        if (A.coeff(i - m, j + m) != -v || A.coeff(j + m, i - m) != -v) return false;
      }
    }
  return A.nonZeros() == 2 * left;
}

}  // namespace

bool hermitian_from_real_form(const SparseMatrix& A, ComplexSparse& M) {
  if (A.rows() != A.cols() || A.rows() % 2 != 0 || !A.isCompressed()) return false;
  const Eigen::Index m = A.rows() / 2;
  if (!has_real_form(A, m)) return false;
  std::vector<Eigen::Triplet<std::complex<double>>> t;
  t.reserve(static_cast<size_t>(A.nonZeros() / 2));
  for (Eigen::Index j = 0; j < m; ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      if (it.row() < m) t.emplace_back(it.row(), j, std::complex<double>(it.value(), 0));
      else t.emplace_back(it.row() - m, j, std::complex<double>(0, it.value()));
    }
  M.resize(m, m);
  M.setFromTriplets(t.begin(), t.end());  // K and B entries at one position add up
  M.makeCompressed();
  return true;
}

Eigen::MatrixXcd complex_from_real_form(const Eigen::MatrixXd& X) {
  const Eigen::Index m = X.rows() / 2;
  Eigen::MatrixXcd Z(m, X.cols());
  Z.real() = X.topRows(m);
  Z.imag() = X.bottomRows(m);
  return Z;
}

Eigen::MatrixXd real_form(const Eigen::MatrixXcd& Z) {
  Eigen::MatrixXd X(2 * Z.rows(), Z.cols());
  X.topRows(Z.rows()) = Z.real();
  X.bottomRows(Z.rows()) = Z.imag();
  return X;
}

}  // namespace intrinsic::detail
