// The natural map's system factored in its complex Hermitian form
// (docs/maths.md §3.6), and the solver's thread settings.
#include <dlfcn.h>

#include <random>

#include "core/natural_system.h"
#include "weights/assemble.h"
#include "intrinsic/parameterize.h"
#include "solve/complex_form.h"
#include "test_support.h"
#ifdef INTRINSIC_HAVE_SUITESPARSE
#include "solve/suitesparse.h"
#endif

namespace intrinsic {
namespace {

Mesh curved_disk() {
  GenerateOptions g;
  g.rings = 14;
  g.jitter = 0.5;
  return make_mesh(generate_sphere_cap(g));
}

// [K 0; 0 K] - H, H twice the area Hessian written out per boundary half-edge
// a -> b as docs/maths.md §3.2 states it: +1 at (u_a, v_b), (v_b, u_a); -1 at
// (v_a, u_b), (u_b, v_a). Dense, for small meshes.
Eigen::MatrixXd natural_matrix_by_definition(const Mesh& mesh) {
  const int n = static_cast<int>(mesh.V.rows());
  WeightOptions conformal;
  const Eigen::MatrixXd K = Eigen::MatrixXd(assemble_weight_matrix(mesh.V, mesh.F, conformal));
  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  Q.topLeftCorner(n, n) = K;
  Q.bottomRightCorner(n, n) = K;
  for (const std::vector<int>& loop : mesh.topology.boundary_loops)
    for (size_t k = 0; k < loop.size(); ++k) {
      const int a = loop[k], b = loop[(k + 1) % loop.size()];
      Q(a, n + b) -= 1;
      Q(n + b, a) -= 1;
      Q(n + a, b) += 1;
      Q(b, n + a) += 1;
    }
  return Q;
}

TEST(ComplexForm, NaturalSystemEqualsItsDefinition) {
  const Mesh mesh = curved_disk();
  const Eigen::MatrixXd expected = natural_matrix_by_definition(mesh);
  const Eigen::MatrixXd Q = Eigen::MatrixXd(assemble_natural_system(mesh));
  EXPECT_EQ((Q - expected).cwiseAbs().maxCoeff(), 0.0);
}

TEST(ComplexForm, HermitianFormHasTheSameQuadraticForm) {
  const Mesh mesh = curved_disk();
  const SparseMatrix Q = assemble_natural_system(mesh);
  detail::ComplexSparse M;
  ASSERT_TRUE(detail::hermitian_from_real_form(Q, M));
  ASSERT_EQ(M.rows(), mesh.V.rows());
  const Eigen::MatrixXcd Md = Eigen::MatrixXcd(M);
  EXPECT_EQ((Md - Md.adjoint()).cwiseAbs().maxCoeff(), 0.0);
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::VectorXd U(Q.rows());
    for (Eigen::Index k = 0; k < U.size(); ++k) U[k] = normal(rng);
    const Eigen::VectorXcd z = detail::complex_from_real_form(U);
    const double real_form = U.dot(Q * U);
    const std::complex<double> hermitian = z.dot(M * z);  // z^H M z
    EXPECT_NEAR(hermitian.real(), real_form, 1e-12 * std::abs(real_form));
    EXPECT_NEAR(hermitian.imag(), 0.0, 1e-12 * std::abs(real_form));
    EXPECT_EQ(detail::real_form(z), U);  // the two forms convert exactly
  }
}

// The product from the lower triangle alone against Eigen's product with
// both triangles, and the merge into compressed storage against Eigen's
// triplet assembly of the same entries.
TEST(ComplexForm, LowerTriangleProductAndDirectAssembly) {
  const Mesh mesh = curved_disk();
  const SparseMatrix Q = assemble_natural_system(mesh);
  detail::ComplexSparse M;
  ASSERT_TRUE(detail::hermitian_from_real_form(Q, M));
  const Eigen::Index m = Q.rows() / 2;
  std::vector<Eigen::Triplet<std::complex<double>>> t;
  for (Eigen::Index j = 0; j < m; ++j)
    for (SparseMatrix::InnerIterator it(Q, j); it; ++it)
      t.emplace_back(it.row() % m, j, it.row() < m ? std::complex<double>(it.value(), 0)
                                                   : std::complex<double>(0, it.value()));
  detail::ComplexSparse by_triplets(m, m);
  by_triplets.setFromTriplets(t.begin(), t.end());
  EXPECT_EQ(Eigen::MatrixXcd(M - by_triplets).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(M.nonZeros(), by_triplets.nonZeros());
  const detail::ComplexSparse lower = M.triangularView<Eigen::Lower>();
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  Eigen::MatrixXcd Z(m, 2);
  for (Eigen::Index k = 0; k < Z.size(); ++k) Z.data()[k] = {normal(rng), normal(rng)};
  const Eigen::MatrixXcd expected = M * Z;
  EXPECT_LT((detail::hermitian_lower_product(lower, Z) - expected).cwiseAbs().maxCoeff(),
            1e-13 * expected.cwiseAbs().maxCoeff());
}

TEST(ComplexForm, MatricesWithoutTheStructureAreRefused) {
  const Mesh mesh = curved_disk();
  SparseMatrix Q = assemble_natural_system(mesh);
  detail::ComplexSparse M;
  SparseMatrix odd = Q.topLeftCorner(Q.rows() - 1, Q.cols() - 1);
  odd.makeCompressed();
  EXPECT_FALSE(detail::hermitian_from_real_form(odd, M));
  const int n = static_cast<int>(mesh.V.rows());
  const int b = mesh.topology.boundary_loops[0][0];
  SparseMatrix broken = Q;
  broken.coeffRef(n + b, n + b) *= 1 + 1e-15;  // the two K blocks differ in one ulp-sized entry
  broken.makeCompressed();
  EXPECT_FALSE(detail::hermitian_from_real_form(broken, M));
  SparseMatrix mirrored = Q;  // B's blocks with the same sign: not a real form of K + iB
  const int c = mesh.topology.boundary_loops[0][1];
  mirrored.coeffRef(c, n + b) = -mirrored.coeff(c, n + b);
  mirrored.makeCompressed();
  EXPECT_FALSE(detail::hermitian_from_real_form(mirrored, M));
}

#ifdef INTRINSIC_HAVE_SUITESPARSE
// Pins two boundary vertices of the natural system and factors the rest both
// ways: the solutions agree to refinement accuracy, and the complex factor
// does fewer flops.
TEST(ComplexForm, ComplexFactorSolvesLikeTheRealOne) {
  const Mesh mesh = curved_disk();
  const int n = static_cast<int>(mesh.V.rows());
  const SparseMatrix Q = assemble_natural_system(mesh);
  const std::vector<int>& loop = mesh.topology.boundary_loops[0];
  std::vector<char> known(2 * n, 0), used(2 * n, 1);
  for (int v : {loop[0], loop[loop.size() / 2]}) known[v] = known[n + v] = 1;
  const Partition p = partition(2 * n, known, used);
  SparseMatrix A, A_IB;
  split_matrix(Q, p, A, A_IB);
  Eigen::MatrixXd known_values(4, 1);
  known_values << 0, 1, 0, 0.3;  // pinned values (any: this is a right-hand side)
  const Eigen::MatrixXd B = -(A_IB * known_values);

  detail::CholmodFactor real, complex;
  ASSERT_TRUE(real.factor(A, detail::Structure::Real));
  ASSERT_TRUE(complex.factor(A, detail::Structure::ComplexPairs));
  EXPECT_FALSE(real.complex());
  EXPECT_TRUE(complex.complex());
  EXPECT_LT(complex.flops(), real.flops());
  const Eigen::MatrixXd x_real = real.solve(B, true), x_complex = complex.solve(B, true);
  EXPECT_LT((x_real - x_complex).cwiseAbs().maxCoeff(), 1e-11 * x_real.cwiseAbs().maxCoeff());
  EXPECT_LT((A * x_complex - B).norm(), 1e-12 * B.norm());
}

// The natural map through the Parameterizer equals the real-form solve of
// the same pinned system by Eigen's own LL^T (no SuiteSparse code involved).
TEST(ComplexForm, NaturalMapEqualsEigenSolveOfTheRealForm) {
  const Mesh mesh = curved_disk();
  ParamOptions o;
  o.boundary = BoundaryShape::Natural;
  o.scale = ScaleMode::Surface;
  const ParamResult r = parameterize(mesh, o);
  const int n = static_cast<int>(mesh.V.rows());
  std::vector<char> known(2 * n, 0), used(2 * n, 1);
  Eigen::MatrixXd pins(2 * r.pins.size(), 1);
  for (const FixedVertex& pin : r.pins) known[pin.vertex] = known[n + pin.vertex] = 1;
  const Partition p = partition(2 * n, known, used);
  for (const FixedVertex& pin : r.pins) {
    pins(p.fixed_index[pin.vertex], 0) = pin.uv.x();
    pins(p.fixed_index[n + pin.vertex], 0) = pin.uv.y();
  }
  SparseMatrix A, A_IB;
  split_matrix(assemble_natural_system(mesh), p, A, A_IB);
  Eigen::SimplicialLLT<SparseMatrix> llt(A);
  const Eigen::VectorXd x = llt.solve(-(A_IB * pins));
  double worst = 0;
  for (int v = 0; v < n; ++v)
    for (int c = 0; c < 2; ++c) {
      const int k = p.free_index[c * n + v];
      if (k >= 0) worst = std::max(worst, std::abs(x[k] - r.UV(v, c)));
    }
  EXPECT_LT(worst, 1e-9 * r.UV.cwiseAbs().maxCoeff());
}
#endif

// The solver sets OpenBLAS's thread count only while it factors: the
// caller's setting is back afterwards (also for a caller that set it).
TEST(SolverThreads, CallersOpenBlasSettingIsRestored) {
  using Get = int (*)();
  using Set = void (*)(int);
  const auto get = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  const auto set = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  if (!get || !set) GTEST_SKIP() << "not linked with OpenBLAS";
  const int before = get();
  set(2);
  ParamOptions o;
  o.boundary = BoundaryShape::Natural;
  parameterize(curved_disk(), o);
  EXPECT_EQ(get(), 2);
  set(before);
}

}  // namespace
}  // namespace intrinsic
