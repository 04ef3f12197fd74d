// The complex instantiation of the supernodal Cholesky (L L^H of a
// Hermitian positive definite matrix, src/solve/supernodal_cholesky.h) on
// the natural map's complex form (src/solve/complex_form.h): against
// Eigen's SimplicialLLT<complex> (its own AMD ordering and an unblocked
// simplicial factorization: a separate code path) and the residual of the
// full Hermitian matrix; a Hermitian matrix that is not positive definite
// (the factorization says so and LinearSolver falls back); 0x0, 1x1 and
// disconnected systems; the same bits with 1, 2 and 3 threads; the
// tighter supernode amalgamation of complex factors; the matrices handed to
// the solver freed, not copied; and the natural map on it against CHOLMOD's
// complex factor.
#include <Eigen/Eigenvalues>
#include <random>

#include "core/natural_system.h"
#include "weights/assemble.h"
#include "intrinsic/error.h"
#include "solve/linear_solver.h"
#include "intrinsic/parameterize.h"
#include "solve/complex_form.h"
#include "solve/eliminated_system.h"
#include "solve/supernodal_cholesky.h"
#include "test_support.h"

namespace intrinsic {
namespace {

using detail::ComplexSparse;
using Complex = std::complex<double>;

// The natural system of `mesh` with two boundary vertices pinned (the
// unknowns of both u and v removed): its real form A and complex form M
// (both triangles), and the pins' contribution as right-hand side.
struct NaturalSystem {
  SparseMatrix A;
  ComplexSparse M;
  Eigen::MatrixXd B;  // real form
};

NaturalSystem natural_system(const Mesh& mesh) {
  const int n = static_cast<int>(mesh.V.rows());
  const std::vector<int>& loop = mesh.topology.boundary_loops[0];
  std::vector<char> known(2 * n, 0), used(2 * n, 1);
  for (int v : {loop[0], loop[loop.size() / 2]}) known[v] = known[n + v] = 1;
  const Partition p = partition(2 * n, known, used);
  NaturalSystem s;
  SparseMatrix A_IB;
  split_matrix(assemble_natural_system(mesh), p, s.A, A_IB);
  s.A.makeCompressed();
  Eigen::MatrixXd pins(4, 1);
  pins << 0, 1, 0, 0.3;
  s.B = -(A_IB * pins);
  EXPECT_TRUE(detail::hermitian_from_real_form(s.A, s.M));
  return s;
}

double relative_residual(const ComplexSparse& M, const Eigen::MatrixXcd& X, const Eigen::MatrixXcd& B) {
  return (M * X - B).norm() / B.norm();
}

// Normwise backward error max_c |M x - b|_inf / (|M|_inf |x|_inf + |b|_inf):
// what a plain (unrefined) solve guarantees whatever the conditioning.
double backward_error(const ComplexSparse& M, const Eigen::MatrixXcd& X, const Eigen::MatrixXcd& B) {
  Eigen::VectorXd row_sums = Eigen::VectorXd::Zero(M.rows());
  for (Eigen::Index j = 0; j < M.outerSize(); ++j)
    for (ComplexSparse::InnerIterator it(M, j); it; ++it) row_sums[it.row()] += std::abs(it.value());
  const double norm_M = row_sums.maxCoeff();
  double worst = 0;
  for (Eigen::Index c = 0; c < X.cols(); ++c) {
    const double r = (M * X.col(c) - B.col(c)).cwiseAbs().maxCoeff();
    worst = std::max(worst, r / (norm_M * X.col(c).cwiseAbs().maxCoeff() + B.col(c).cwiseAbs().maxCoeff()));
  }
  return worst;
}

#ifdef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
Eigen::MatrixXcd factor_and_solve(const ComplexSparse& M, const Eigen::MatrixXcd& B, int threads) {
  detail::ComplexSupernodalCholesky f(threads);
  EXPECT_TRUE(f.factor(M));
  return f.solve(B);
}

// A Hermitian positive definite matrix with a dense m x m block coupled to
// a path: one supernode wider than a column block (split between threads).
ComplexSparse dense_block_matrix(int m, int path) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXcd G(m, m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) G(i, j) = Complex(u(rng), u(rng));
  const Eigen::MatrixXcd D = G * G.adjoint() / m + Eigen::MatrixXcd::Identity(m, m);
  std::vector<Eigen::Triplet<Complex>> t;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) t.emplace_back(i, j, i == j ? Complex(D(i, i).real(), 0) : D(i, j));
  for (int k = 0; k < path; ++k) {
    const int v = m + k, prev = k == 0 ? 0 : v - 1;
    const Complex c(-0.5, 0.5 * u(rng));
    t.emplace_back(v, v, 3.0);
    t.emplace_back(v, prev, c);
    t.emplace_back(prev, v, std::conj(c));
    t.emplace_back(prev, prev, 1.0);
  }
  ComplexSparse M(m + path, m + path);
  M.setFromTriplets(t.begin(), t.end());
  M.makeCompressed();
  return M;
}
#endif

TEST(SupernodalCholeskyComplex, AgreesWithSimplicialLLTOnNaturalSystems) {
#ifndef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
#else
  for (int rings : {4, 30, 90}) {
    const NaturalSystem s = natural_system(test::wavy(rings));
    std::mt19937 rng(rings);
    std::uniform_real_distribution<double> u(-1, 1);
    Eigen::MatrixXcd B(s.M.rows(), 2);
    B.col(0) = detail::complex_from_real_form(s.B);
    for (Eigen::Index i = 0; i < B.rows(); ++i) B(i, 1) = Complex(u(rng), u(rng));
    const Eigen::MatrixXcd X = factor_and_solve(s.M, B, 2);
    Eigen::SimplicialLLT<ComplexSparse, Eigen::Lower> llt(s.M);
    ASSERT_EQ(llt.info(), Eigen::Success);
    const Eigen::MatrixXcd ref = llt.solve(B);
    // Two pins leave the system ill-conditioned: both plain solutions have
    // backward errors near rounding (their relative residuals reach 1e-10
    // at 90 rings, for ours and Eigen's alike), and differ by about
    // cond * eps. LinearSolver's refined solve is held to 1e-12 below.
    EXPECT_LT(backward_error(s.M, X, B), 1e-14) << rings;
    EXPECT_LT(backward_error(s.M, ref, B), 1e-14) << rings;
    EXPECT_LT((X - ref).cwiseAbs().maxCoeff(), 1e-8 * ref.cwiseAbs().maxCoeff()) << rings;
  }
#endif
}

// Through LinearSolver (Auto, complex form declared): our complex factor,
// refined in long double, agrees with CHOLMOD's complex factor and its own
// refinement to 1e-11, and only M's lower triangle is kept.
TEST(SupernodalCholeskyComplex, LinearSolverAgreesWithCholmodComplex) {
#ifndef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
#else
  const NaturalSystem s = natural_system(test::wavy(90));
  LinearSolver ours(SolverKind::Auto, true), cholmod(SolverKind::Cholmod, true);
  for (LinearSolver* solver : {&ours, &cholmod}) {
    solver->set_ill_conditioned(true);
    solver->set_complex_form(true);
    solver->factor(s.A);
  }
  EXPECT_EQ(ours.kind(), SolverKind::SupernodalCholesky);
  EXPECT_EQ(cholmod.kind(), SolverKind::Cholmod);
  const Eigen::MatrixXd X = ours.solve(s.B), ref = cholmod.solve(s.B);
  EXPECT_LT((X - ref).cwiseAbs().maxCoeff(), 1e-11 * ref.cwiseAbs().maxCoeff());
  EXPECT_LT((s.A * X - s.B).norm(), 1e-12 * s.B.norm());
  // The real form is rebuilt on request, entry for entry (explicit zeros aside).
  EXPECT_EQ((SparseMatrix(ours.matrix()) - s.A).cwiseAbs().sum(), 0.0);
  EXPECT_LT((ours.multiply(X) - s.A * X).cwiseAbs().maxCoeff(), 1e-12 * (s.A * X).cwiseAbs().maxCoeff());
#endif
}

// M - sigma I with sigma between the extreme eigenvalues: Hermitian,
// invertible, indefinite. The factorization reports it, and LinearSolver
// (Auto) rebuilds the real form and solves it with a fallback.
TEST(SupernodalCholeskyComplex, NotPositiveDefiniteFallsBack) {
#ifndef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
#else
  NaturalSystem s = natural_system(test::wavy(12));
  const Eigen::Index m = s.M.rows();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> eig{Eigen::MatrixXcd(s.M)};
  const Eigen::VectorXd ev = eig.eigenvalues();
  const Eigen::Index mid = m / 2;
  const double sigma = 0.5 * (ev[mid] + ev[mid + 1]);  // halfway between two eigenvalues
  ComplexSparse shift(m, m);
  shift.setIdentity();
  const ComplexSparse M = s.M - sigma * shift;
  detail::ComplexSupernodalCholesky f;
  EXPECT_FALSE(f.factor(M));

  const SparseMatrix A = detail::real_form_from_hermitian(M);
  LinearSolver solver(SolverKind::Auto, true);
  solver.set_ill_conditioned(true);
  solver.set_complex_form(true);
  solver.factor(A);
  EXPECT_NE(solver.kind(), SolverKind::SupernodalCholesky);
  const Eigen::MatrixXd X = solver.solve(s.B);
  EXPECT_LT((A * X - s.B).norm(), 1e-10 * s.B.norm());
  EXPECT_EQ((solver.matrix() - A).cwiseAbs().sum(), 0.0);

  LinearSolver explicit_choice(SolverKind::SupernodalCholesky, true);
  explicit_choice.set_complex_form(true);
  EXPECT_THROW(explicit_choice.factor(A), Error);
#endif
}

TEST(SupernodalCholeskyComplex, TinySystems) {
#ifndef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
#else
  detail::ComplexSupernodalCholesky f;
  ComplexSparse empty(0, 0);
  empty.makeCompressed();
  ASSERT_TRUE(f.factor(empty));
  EXPECT_EQ(f.solve(Eigen::MatrixXcd(0, 2)).rows(), 0);

  ComplexSparse one(1, 1);
  one.insert(0, 0) = 4.0;
  one.makeCompressed();
  ASSERT_TRUE(f.factor(one));
  Eigen::MatrixXcd b(1, 1);
  b(0, 0) = Complex(2, -6);
  EXPECT_EQ(f.solve(b)(0, 0), Complex(0.5, -1.5));

  one.coeffRef(0, 0) = -1.0;
  EXPECT_FALSE(f.factor(one));
#endif
}

// Two natural systems side by side (no coupling): two roots in the
// elimination tree; each block's solution is its own system's.
TEST(SupernodalCholeskyComplex, DisconnectedBlocks) {
#ifndef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
#else
  const NaturalSystem a = natural_system(test::wavy(20)), b = natural_system(test::wavy(7));
  const Eigen::Index ma = a.M.rows(), mb = b.M.rows();
  std::vector<Eigen::Triplet<Complex>> t;
  for (int j = 0; j < ma; ++j)
    for (ComplexSparse::InnerIterator it(a.M, j); it; ++it) t.emplace_back(it.row(), j, it.value());
  for (int j = 0; j < mb; ++j)
    for (ComplexSparse::InnerIterator it(b.M, j); it; ++it) t.emplace_back(ma + it.row(), ma + j, it.value());
  ComplexSparse M(ma + mb, ma + mb);
  M.setFromTriplets(t.begin(), t.end());
  M.makeCompressed();
  Eigen::MatrixXcd B(ma + mb, 1);
  B.topRows(ma) = detail::complex_from_real_form(a.B);
  B.bottomRows(mb) = detail::complex_from_real_form(b.B);
  const Eigen::MatrixXcd X = factor_and_solve(M, B, 2);
  EXPECT_LT(relative_residual(M, X, B), 1e-12);
  const Eigen::MatrixXcd Xa = factor_and_solve(a.M, B.topRows(ma), 1);
  const Eigen::MatrixXcd Xb = factor_and_solve(b.M, B.bottomRows(mb), 1);
  EXPECT_LT((X.topRows(ma) - Xa).cwiseAbs().maxCoeff(), 1e-9 * Xa.cwiseAbs().maxCoeff());
  EXPECT_LT((X.bottomRows(mb) - Xb).cwiseAbs().maxCoeff(), 1e-9 * Xb.cwiseAbs().maxCoeff());
#endif
}

TEST(SupernodalCholeskyComplex, SameBitsWithOneTwoAndThreeThreads) {
#ifndef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
#else
  const NaturalSystem s = natural_system(test::wavy(90));
  const Eigen::MatrixXcd B = detail::complex_from_real_form(s.B);
  const ComplexSparse D = dense_block_matrix(500, 1500);
  const Eigen::MatrixXcd BD = Eigen::MatrixXcd::Random(D.rows(), 2);
  const Eigen::MatrixXcd X1 = factor_and_solve(s.M, B, 1), D1 = factor_and_solve(D, BD, 1);
  EXPECT_LT(relative_residual(D, D1, BD), 1e-12);
  for (int threads : {2, 3}) {
    EXPECT_TRUE((factor_and_solve(s.M, B, threads).array() == X1.array()).all()) << threads;
    EXPECT_TRUE((factor_and_solve(D, BD, threads).array() == D1.array()).all()) << threads;
  }
#endif
}

// The complex factor's tighter amalgamation (kComplexRelaxation) against
// CHOLMOD's default and against none at all: fewer stored entries than
// CHOLMOD's default, at least the unrelaxed count, and the same solution as
// Eigen's SimplicialLLT<complex> (its own ordering, no supernodes) to
// 1e-11. M + I keeps the natural system's pattern but is well conditioned,
// so two correct plain solves agree that closely.
TEST(SupernodalCholeskyComplex, TighterRelaxationStoresFewerZeros) {
#ifndef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
#else
  const NaturalSystem s = natural_system(test::wavy(90));
  ComplexSparse I(s.M.rows(), s.M.cols());
  I.setIdentity();
  ComplexSparse M = s.M + I;
  M.makeCompressed();
  const Eigen::MatrixXcd B = Eigen::MatrixXcd::Random(M.rows(), 2);
  Eigen::SimplicialLLT<ComplexSparse, Eigen::Lower> llt(M);
  ASSERT_EQ(llt.info(), Eigen::Success);
  const Eigen::MatrixXcd ref = llt.solve(B);
  detail::ComplexSupernodalCholesky ours(2), cholmods(2), none(2);
  cholmods.set_relaxation(detail::SupernodeRelaxation());
  none.set_relaxation({{0, 0, 0}, {0, 0, 0}});
  for (detail::ComplexSupernodalCholesky* f : {&ours, &cholmods, &none}) {
    ASSERT_TRUE(f->factor(M));
    EXPECT_LT((f->solve(B) - ref).cwiseAbs().maxCoeff(), 1e-11 * ref.cwiseAbs().maxCoeff());
  }
  EXPECT_LT(ours.factor_nonzeros(), cholmods.factor_nonzeros());
  EXPECT_GE(ours.factor_nonzeros(), none.factor_nonzeros());
  EXPECT_LE(ours.flops(), cholmods.flops());
  // The same bits on 1, 2 and 3 threads under each amalgamation.
  for (const detail::SupernodeRelaxation& r : {detail::kComplexRelaxation, detail::SupernodeRelaxation()}) {
    Eigen::MatrixXcd first;
    for (int threads : {1, 2, 3}) {
      detail::ComplexSupernodalCholesky f(threads);
      f.set_relaxation(r);
      ASSERT_TRUE(f.factor(M));
      const Eigen::MatrixXcd X = f.solve(B);
      if (threads == 1) first = X;
      else EXPECT_TRUE((X.array() == first.array()).all()) << threads;
    }
  }
#endif
}

// Eigen 3.4's SparseMatrix has no move assignment, and assigning an empty
// matrix keeps the storage: the solver and the eliminated system must swap
// the matrices they are given, or a copy of the natural map's real form
// (168 MB at 1M vertices) stays allocated beside the factor.
TEST(SupernodalCholeskyComplex, FactorTakesAndFreesTheGivenMatrix) {
  const NaturalSystem s = natural_system(test::wavy(30));
  SparseMatrix A = s.A;
  LinearSolver solver(SolverKind::Auto, true);
  solver.set_ill_conditioned(true);
  solver.set_complex_form(true);
  solver.factor(std::move(A));
  EXPECT_EQ(A.data().allocatedSize(), 0);  // taken, not copied
  const Eigen::MatrixXd X = solver.solve(s.B);
  EXPECT_LT((s.A * X - s.B).norm(), 1e-12 * s.B.norm());

  const Mesh mesh = test::wavy(30);
  const int n = static_cast<int>(mesh.V.rows());
  SparseMatrix Q = assemble_natural_system(mesh);
  std::vector<char> known(2 * n, 0), used(2 * n, 1);
  const std::vector<int>& loop = mesh.topology.boundary_loops[0];
  for (int v : {loop[0], loop[loop.size() / 2]}) known[v] = known[n + v] = 1;
  detail::EliminatedSystem::Factoring how;
  how.ill_conditioned = how.complex_form = true;
  const detail::EliminatedSystem sys(std::move(Q), known, used, how);
  EXPECT_EQ(Q.data().allocatedSize(), 0);  // freed once split
  EXPECT_TRUE(sys.factored());
}

// The natural map end to end: Auto (our complex factor) and --solver
// cholmod (CHOLMOD's complex factor), both refined in long double, agree to
// 1e-11 of the layout's size.
TEST(SupernodalCholeskyComplex, NaturalMapMatchesCholmod) {
#ifndef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
#else
  const Mesh mesh = test::wavy(60);
  ParamOptions o;
  o.boundary = BoundaryShape::Natural;
  const ParamResult ours = parameterize(mesh, o);
  o.solver = SolverKind::Cholmod;
  const ParamResult cholmod = parameterize(mesh, o);
  EXPECT_LT((ours.UV - cholmod.UV).cwiseAbs().maxCoeff(), 1e-11 * cholmod.UV.cwiseAbs().maxCoeff());
  EXPECT_LT(ours.residual, 1e-12);
  ASSERT_FALSE(ours.solvers.empty());
  EXPECT_EQ(ours.solvers[0], SolverKind::SupernodalCholesky);
  EXPECT_EQ(cholmod.solvers[0], SolverKind::Cholmod);
#endif
}

}  // namespace
}  // namespace intrinsic
