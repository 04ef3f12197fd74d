// The natural map against its exact solution
// (docs/performance.md#the-natural-map-a-complex-hermitian-factor):
// the map equals the exact solution of its system rounded to doubles, on a
// mesh whose natural system is ill-conditioned enough that an unrefined
// solve, or one refined with a long-double residual, is not; the
// refinement's residual equals one written here in quad precision; neither
// depends on the thread count.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <random>

#include "core/natural_system.h"
#include "weights/assemble.h"
#include "intrinsic/parameterize.h"
#include "solve/complex_form.h"
#include "test_support.h"
#include "util/parallel_for.h"

namespace intrinsic {
namespace {

using Quad = __float128;  // 113-bit mantissa: a product of two doubles (106 bits) is exact

constexpr double kEps = std::numeric_limits<double>::epsilon();

// A long strip of a sphere (the paper's Figure 7 case) pinned at two
// vertices: its natural system is the worst conditioned of the generators at
// this size (13161 vertices; an unrefined solve is off by 1.5e-10).
Mesh strip() {
  GenerateOptions g;
  g.rings = 80;
  g.jitter = 0.5;
  return make_mesh(generate_sphere_strip(g));
}

ParamOptions natural_options() {
  ParamOptions o;
  o.boundary = BoundaryShape::Natural;
  o.scale = ScaleMode::Surface;  // the pins at their 3D distance: UV is the system's solution
  return o;
}

// b - A x with every product exact and sums in quad precision (2^-113).
Eigen::VectorXd quad_residual(const SparseMatrix& A, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  std::vector<Quad> r(b.data(), b.data() + b.size());
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) r[it.row()] -= Quad(it.value()) * Quad(x[j]);
  Eigen::VectorXd out(b.size());
  for (Eigen::Index i = 0; i < b.size(); ++i) out[i] = static_cast<double>(r[i]);
  return out;
}

struct Reference {
  MatrixX2d UV, unrefined;
};

// The exact solution, written here: the real 2n system from the natural
// system by triplets (the pins moved to the right-hand side), Eigen's
// simplicial LDL^T, refined with quad_residual until the correction is an ulp.
Reference exact_reference(const Mesh& mesh, const std::vector<FixedVertex>& pins) {
  const SparseMatrix Q = assemble_natural_system(mesh);
  const int n = static_cast<int>(mesh.V.rows());
  std::vector<int> index(2 * n, -1);
  Eigen::VectorXd pinned = Eigen::VectorXd::Zero(2 * n);
  for (const FixedVertex& p : pins) pinned[p.vertex] = p.uv.x(), pinned[n + p.vertex] = p.uv.y(), index[p.vertex] = -2;
  int m = 0;
  for (int k = 0; k < 2 * n; ++k)
    if (index[k % n] != -2) index[k] = m++;
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(m);
  for (int j = 0; j < 2 * n; ++j)
    for (SparseMatrix::InnerIterator it(Q, j); it; ++it) {
      if (index[it.row()] < 0) continue;
      if (index[j] >= 0) t.emplace_back(index[it.row()], index[j], it.value());
      else b[index[it.row()]] -= it.value() * pinned[j];
    }
  SparseMatrix A(m, m);
  A.setFromTriplets(t.begin(), t.end());
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(A);
  EXPECT_EQ(ldlt.info(), Eigen::Success);
  const Eigen::VectorXd first = ldlt.solve(b);
  Eigen::VectorXd x = first;
  for (int step = 0; step < 10; ++step) {
    const Eigen::VectorXd d = ldlt.solve(quad_residual(A, x, b));
    x += d;
    if (!(d.cwiseAbs().maxCoeff() > kEps * x.cwiseAbs().maxCoeff())) break;
  }
  Reference r{MatrixX2d::Zero(n, 2), MatrixX2d::Zero(n, 2)};
  for (int k = 0; k < 2 * n; ++k) {
    r.UV(k % n, k / n) = index[k] >= 0 ? x[index[k]] : pinned[k];
    r.unrefined(k % n, k / n) = index[k] >= 0 ? first[index[k]] : pinned[k];
  }
  return r;
}

double relative(const MatrixX2d& a, const MatrixX2d& ref) {
  return (a - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
}

// The map is the exact solution rounded: the test's refinement and the
// library's each converge to within an ulp or so of it (their residuals
// are exact to ~2^-100 relative to |A||x|, which the conditioning, below
// 1e12 here, cannot lift to an ulp), so they differ by at most a few ulps
// of the largest coordinate: 4 eps. A long-double residual leaves the map
// 6e-15 to 3e-14 off here (bench/natural_accuracy_bench on this mesh).
TEST(NaturalAccuracy, MapIsTheExactSolutionRounded) {
  const Mesh mesh = strip();
  const ParamResult p = parameterize(mesh, natural_options());
  const Reference ref = exact_reference(mesh, p.pins);
  const double unrefined = relative(ref.unrefined, ref.UV);
  EXPECT_GT(unrefined, 1e-13);  // the refinement matters on this mesh
  EXPECT_LE(relative(p.UV, ref.UV), 4 * kEps);
}

// Hermitian lower triangle of the (singular, whole) natural system, a
// random Z, and B = M Z rounded: B - M Z then cancels to the rounding of B,
// the regime of a converged refinement.
struct ResidualCase {
  detail::ComplexSparse lower;
  Eigen::MatrixXcd Z, B;
};

ResidualCase residual_case() {
  ResidualCase c;
  detail::ComplexSparse M;
  EXPECT_TRUE(detail::hermitian_from_real_form(assemble_natural_system(strip()), M));
  c.lower = M.triangularView<Eigen::Lower>();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  c.Z = Eigen::MatrixXcd(M.rows(), 2);
  for (Eigen::Index k = 0; k < c.Z.size(); ++k) c.Z.data()[k] = {u(rng), u(rng)};
  c.B = M * c.Z;
  return c;
}

// The residual's real and imaginary parts, each against a plain quad
// precision sum over the full Hermitian matrix: Dot2's bound is
// |computed - exact| <= eps/2 |exact| + gamma^2 (|M| |Z| + |B|), gamma = n eps
// for n terms (7 or so here); 1e-28 of the row's scale covers the second term
// with room. A long-double sum (error ~2^-64 of the scale) fails it.
TEST(NaturalAccuracy, ResidualEqualsAQuadPrecisionResidual) {
  const ResidualCase c = residual_case();
  double omega = -1;
  const Eigen::MatrixXcd R = detail::hermitian_lower_residual(c.lower, c.Z, c.B, &omega);
  const detail::ComplexSparse M = c.lower.selfadjointView<Eigen::Lower>();
  double expected_omega = 0;
  for (Eigen::Index col = 0; col < c.Z.cols(); ++col) {
    std::vector<Quad> re(M.rows()), im(M.rows());
    std::vector<double> scale(M.rows());
    for (Eigen::Index i = 0; i < M.rows(); ++i) {
      re[i] = c.B(i, col).real(), im[i] = c.B(i, col).imag();
      scale[i] = std::abs(c.B(i, col).real()) + std::abs(c.B(i, col).imag());
    }
    for (Eigen::Index j = 0; j < M.cols(); ++j)
      for (detail::ComplexSparse::InnerIterator it(M, j); it; ++it) {
        const std::complex<double> m = it.value(), z = c.Z(j, col);
        re[it.row()] -= Quad(m.real()) * Quad(z.real()) - Quad(m.imag()) * Quad(z.imag());
        im[it.row()] -= Quad(m.real()) * Quad(z.imag()) + Quad(m.imag()) * Quad(z.real());
        scale[it.row()] += (std::abs(m.real()) + std::abs(m.imag())) * (std::abs(z.real()) + std::abs(z.imag()));
      }
    int cancelled = 0;
    for (Eigen::Index i = 0; i < M.rows(); ++i) {
      const double er = static_cast<double>(re[i]), ei = static_cast<double>(im[i]);
      ASSERT_LE(std::abs(R(i, col).real() - er), 0.5 * kEps * std::abs(er) + 1e-28 * scale[i]) << "row " << i;
      ASSERT_LE(std::abs(R(i, col).imag() - ei), 0.5 * kEps * std::abs(ei) + 1e-28 * scale[i]) << "row " << i;
      cancelled += std::abs(er) + std::abs(ei) < 1e-12 * scale[i];
      expected_omega = std::max(expected_omega, (std::abs(er) + std::abs(ei)) / scale[i]);
    }
    EXPECT_GT(cancelled, M.rows() / 2);  // the regime that needs the exact products
  }
  EXPECT_NEAR(omega, expected_omega, 1e-12 * expected_omega);
}

// Rows are split over threads; each row sums in column order whoever
// computes it, so 1 and 2 threads give the same bits; and so does the map.
TEST(NaturalAccuracy, SameResultForAnyThreadCount) {
  const ResidualCase c = residual_case();
  std::atomic<int>& limit = detail::thread_limit();
  const int saved = limit.load();
  std::vector<Eigen::MatrixXcd> R;
  std::vector<double> omega;
  std::vector<MatrixX2d> UV;
  const Mesh mesh = strip();
  for (int threads : {1, 2}) {
    limit = threads;
    // The rows are cut into `threads` pieces (at least 20000 entries each).
    EXPECT_EQ(detail::parallel_parts(c.lower.nonZeros(), 20000), threads);
    omega.push_back(0);
    R.push_back(detail::hermitian_lower_residual(c.lower, c.Z, c.B, &omega.back()));
    UV.push_back(parameterize(mesh, natural_options()).UV);
  }
  limit = saved;
  for (size_t k = 1; k < R.size(); ++k) {
    EXPECT_TRUE(R[k] == R[0]) << k + 1 << " threads";
    EXPECT_EQ(omega[k], omega[0]);
  }
  EXPECT_TRUE(UV[1] == UV[0]);
}

}  // namespace
}  // namespace intrinsic
