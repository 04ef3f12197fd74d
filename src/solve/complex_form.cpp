// Real form <-> complex Hermitian form of the natural map's system (see
// complex_form.h; docs/maths.md §3.6).
#include "solve/complex_form.h"

#include <algorithm>
#include <climits>
#include <vector>

namespace intrinsic::detail {
namespace {

// A is [K -B; B K]: the right half mirrors the left half entry for entry
// (exactly: the Parameterizer assembles both halves from the same numbers),
// K is symmetric and B antisymmetric. Column j + m must be column j with its
// two halves swapped and the B half negated, which is checked by walking the
// two columns side by side; the (anti)symmetry needs a lookup per entry.
bool has_real_form(const SparseMatrix& A, Eigen::Index m) {
  const int* outer = A.outerIndexPtr();
  const int* row = A.innerIndexPtr();
  const double* value = A.valuePtr();
  for (Eigen::Index j = 0; j < m; ++j) {
    const int b = outer[j], e = outer[j + 1], rb = outer[j + m], re = outer[j + m + 1];
    if (re - rb != e - b) return false;
    int split = b;  // first row of the B half in column j
    while (split < e && row[split] < m) ++split;
    // Right column: -B rows first (rows < m), then K rows (rows >= m).
    int k = rb;
    for (int q = split; q < e; ++q, ++k)
      if (row[k] != row[q] - m || value[k] != -value[q]) return false;
    for (int q = b; q < split; ++q, ++k)
      if (row[k] != row[q] + m || value[k] != value[q]) return false;
    for (int q = b; q < e; ++q) {
      const Eigen::Index i = row[q];
      if (i < m ? A.coeff(j, i) != value[q] : A.coeff(j + m, i - m) != -value[q]) return false;
    }
  }
  return true;
}

}  // namespace

// Column j of M merges column j's two sorted halves (K rows < m, B rows
// >= m): straight into compressed storage, no triplet list (which at 1M
// vertices would be 14M triplets of 24 bytes).
bool hermitian_from_real_form(const SparseMatrix& A, ComplexSparse& M) {
  if (A.rows() != A.cols() || A.rows() % 2 != 0 || !A.isCompressed()) return false;
  const Eigen::Index m = A.rows() / 2;
  if (!has_real_form(A, m)) return false;
  const int* outer = A.outerIndexPtr();
  const int* row = A.innerIndexPtr();
  const double* value = A.valuePtr();
  std::vector<int> begin(static_cast<size_t>(m) + 1, 0), rows;
  std::vector<std::complex<double>> values;
  rows.reserve(static_cast<size_t>(outer[m]));
  values.reserve(static_cast<size_t>(outer[m]));
  for (Eigen::Index j = 0; j < m; ++j) {
    const int b = outer[j], e = outer[j + 1];
    int split = b;
    while (split < e && row[split] < m) ++split;
    int k = b, q = split;
    while (k < split || q < e) {
      const int rk = k < split ? row[k] : INT_MAX, rq = q < e ? row[q] - static_cast<int>(m) : INT_MAX;
      const int r = std::min(rk, rq);
      // K and B entries at one position add up, the K one first (as the
      // triplet assembly this replaces did, down to the sign of a zero).
      std::complex<double> z = rk == r ? std::complex<double>(value[k++], 0) : std::complex<double>(0, value[q++]);
      if (rk == r && rq == r) z += std::complex<double>(0, value[q++]);
      rows.push_back(r);
      values.push_back(z);
    }
    begin[static_cast<size_t>(j) + 1] = static_cast<int>(rows.size());
  }
  M.resize(m, m);
  M.resizeNonZeros(static_cast<Eigen::Index>(rows.size()));
  std::copy(begin.begin(), begin.end(), M.outerIndexPtr());
  std::copy(rows.begin(), rows.end(), M.innerIndexPtr());
  std::copy(values.begin(), values.end(), M.valuePtr());
  return true;
}

// M Z, M from its lower triangle: each stored (i, j), i > j, stands for
// M(i, j) and M(j, i) = conj(M(i, j)). The complex products are written out
// in real arithmetic.
Eigen::MatrixXcd hermitian_lower_product(const ComplexSparse& lower, const Eigen::MatrixXcd& Z) {
  const Eigen::Index n = lower.rows();
  Eigen::MatrixXcd Y(n, Z.cols());
  std::vector<double> re(static_cast<size_t>(n)), im(static_cast<size_t>(n));
  for (Eigen::Index c = 0; c < Z.cols(); ++c) {
    std::fill(re.begin(), re.end(), 0.0);
    std::fill(im.begin(), im.end(), 0.0);
    for (Eigen::Index j = 0; j < lower.outerSize(); ++j) {
      const double zr = Z(j, c).real(), zi = Z(j, c).imag();
      for (ComplexSparse::InnerIterator it(lower, j); it; ++it) {
        const Eigen::Index i = it.row();
        const double mr = it.value().real(), mi = it.value().imag();
        re[i] += mr * zr - mi * zi;
        im[i] += mr * zi + mi * zr;
        if (i != j) {
          const double xr = Z(i, c).real(), xi = Z(i, c).imag();
          re[j] += mr * xr + mi * xi;
          im[j] += mr * xi - mi * xr;
        }
      }
    }
    for (Eigen::Index i = 0; i < n; ++i) Y(i, c) = std::complex<double>(re[i], im[i]);
  }
  return Y;
}

// Column j: K's entries (rows < m) over B's (rows >= m); column m + j: -B
// over K, the layout hermitian_from_real_form accepts.
SparseMatrix real_form_from_hermitian(const ComplexSparse& M) {
  const Eigen::Index m = M.rows();
  SparseMatrix A(2 * m, 2 * m);
  Eigen::Index count = 0;
  for (Eigen::Index k = 0; k < M.nonZeros(); ++k)
    count += (M.valuePtr()[k].real() != 0) + (M.valuePtr()[k].imag() != 0);
  A.resizeNonZeros(2 * count);
  Eigen::Index out = 0;
  auto append = [&](Eigen::Index j, Eigen::Index shift, auto value) {
    for (ComplexSparse::InnerIterator it(M, j); it; ++it) {
      const double x = value(it.value());
      if (x == 0) continue;  // K or B has no entry there (both halves skip it alike)
      A.innerIndexPtr()[out] = static_cast<int>(it.row() + shift);
      A.valuePtr()[out++] = x;
    }
  };
  for (Eigen::Index j = 0; j < m; ++j) {
    A.outerIndexPtr()[j] = static_cast<int>(out);
    append(j, 0, [](std::complex<double> z) { return z.real(); });
    append(j, m, [](std::complex<double> z) { return z.imag(); });
  }
  for (Eigen::Index j = 0; j < m; ++j) {
    A.outerIndexPtr()[m + j] = static_cast<int>(out);
    append(j, 0, [](std::complex<double> z) { return -z.imag(); });
    append(j, m, [](std::complex<double> z) { return z.real(); });
  }
  A.outerIndexPtr()[2 * m] = static_cast<int>(out);
  return A;
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
