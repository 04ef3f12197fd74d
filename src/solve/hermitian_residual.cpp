// The natural map's refinement residual B - M Z (complex_form.h), exact to
// about twice double precision: each product of two doubles is split
// exactly into a sum of two doubles (Dekker, or one FMA where the build
// targets it) and each row's sum is compensated (Ogita, Rump and Oishi's
// Dot2, "Accurate sum and dot product", SIAM J. Sci. Comput. 2005), then
// rounded once. A long-double sum (64-bit mantissa) was not enough: its
// rounding acts like a relative perturbation of M of 2^-64, and the natural
// system at 1M vertices moves by 1.6e-7 under a 2^-52 perturbation, so
// refinement stalled near 4e-11
// (docs/performance.md#the-natural-map-a-complex-hermitian-factor).
// Rows are split over threads; every row sums its terms in the order of
// their column, whichever thread computes it, so the result does not depend
// on the thread count.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <vector>

#include "solve/complex_form.h"
#include "util/parallel_for.h"

namespace intrinsic::detail {
namespace {

// a * b = p + e exactly (no overflow or underflow on mesh data).
inline double two_product(double a, double b, double& e) {
  const double p = a * b;
#ifdef __FP_FAST_FMA
  e = std::fma(a, b, -p);
#else
  // Veltkamp's split into 26-bit halves, whose products are exact.
  const double ca = 134217729.0 * a, cb = 134217729.0 * b;
  const double ah = ca - (ca - a), al = a - ah, bh = cb - (cb - b), bl = b - bh;
  e = al * bl - (((p - ah * bh) - al * bh) - ah * bl);
#endif
  return p;
}

// One component's sum: s + c, s the rounded running sum and c the sum of
// every rounding error (Knuth's two-sum) and product remainder.
struct Sum2 {
  double s = 0, c = 0;
  void add(double a, double b) {
    double e;
    const double p = two_product(a, b, e);
    const double t = s + p, z = t - s;
    c += ((s - (t - z)) + (p - z)) + e;
    s = t;
  }
};

// Row i's residual so far, and its scale for the backward error.
struct RowSum {
  Sum2 re, im;
  double scale = 0;  // sum of |m| |z| over the row's terms, plus |b| (1-norms)
  // Subtracts m z (conj(m) z when `conjugate`).
  void subtract(std::complex<double> m, std::complex<double> z, bool conjugate) {
    const double mi = conjugate ? -m.imag() : m.imag();
    re.add(-m.real(), z.real());
    re.add(mi, z.imag());
    im.add(-m.real(), z.imag());
    im.add(-mi, z.real());
    scale += (std::abs(m.real()) + std::abs(m.imag())) * (std::abs(z.real()) + std::abs(z.imag()));
  }
};

// Rows [lo, hi) of column c: row i's terms come in column order, the
// entries left of the diagonal (stored in earlier columns) first, then the
// diagonal, then the conjugates of column i's entries below it.
void residual_rows(const ComplexSparse& lower, const Eigen::MatrixXcd& Z, const Eigen::MatrixXcd& B,
                   Eigen::Index c, Eigen::Index lo, Eigen::Index hi, Eigen::MatrixXcd& R, double& omega) {
  const int* outer = lower.outerIndexPtr();
  const int* row = lower.innerIndexPtr();
  const std::complex<double>* value = lower.valuePtr();
  std::vector<RowSum> acc(static_cast<size_t>(hi - lo));
  for (Eigen::Index i = lo; i < hi; ++i) {
    acc[i - lo].re.s = B(i, c).real();
    acc[i - lo].im.s = B(i, c).imag();
    acc[i - lo].scale = std::abs(B(i, c).real()) + std::abs(B(i, c).imag());
  }
  for (Eigen::Index j = 0; j < lo; ++j)  // earlier columns: only their rows in [lo, hi)
    for (int q = outer[j + 1] - 1; q >= outer[j] && row[q] >= lo; --q)
      if (row[q] < hi) acc[row[q] - lo].subtract(value[q], Z(j, c), false);
  for (Eigen::Index j = lo; j < hi; ++j) {
    RowSum& own = acc[j - lo];
    for (int q = outer[j]; q < outer[j + 1]; ++q) {
      const Eigen::Index i = row[q];
      if (i == j) { own.subtract(value[q], Z(j, c), false); continue; }
      own.subtract(value[q], Z(i, c), true);
      if (i < hi) acc[i - lo].subtract(value[q], Z(j, c), false);
    }
    const std::complex<double> r(own.re.s + own.re.c, own.im.s + own.im.c);
    R(j, c) = r;
    const double size = std::abs(r.real()) + std::abs(r.imag());
    if (own.scale > 0) omega = std::max(omega, size / own.scale);
    else if (size != 0 || std::isnan(size)) omega = INFINITY;
  }
}

}  // namespace

Eigen::MatrixXcd hermitian_lower_residual(const ComplexSparse& lower, const Eigen::MatrixXcd& Z,
                                          const Eigen::MatrixXcd& B, double* backward_error) {
  const Eigen::Index n = lower.rows();
  Eigen::MatrixXcd R(n, Z.cols());
  // Row pieces of about equal entries (rows cost their entries).
  const int parts = parallel_parts(lower.nonZeros(), 20000);
  std::vector<Eigen::Index> first(static_cast<size_t>(parts) + 1, n);
  first[0] = 0;
  for (int p = 1; p < parts; ++p)
    first[p] = std::upper_bound(lower.outerIndexPtr(), lower.outerIndexPtr() + n,
                                static_cast<int>(lower.nonZeros() * p / parts)) -
               lower.outerIndexPtr() - 1;
  std::vector<double> omega(static_cast<size_t>(parts), 0.0);
  for (Eigen::Index c = 0; c < Z.cols(); ++c)
    parallel_for_parts(parts, parts, [&](int p, std::int64_t, std::int64_t) {
      residual_rows(lower, Z, B, c, first[p], std::max(first[p], first[p + 1]), R, omega[p]);
    });
  if (backward_error) *backward_error = *std::max_element(omega.begin(), omega.end());
  return R;
}

}  // namespace intrinsic::detail
