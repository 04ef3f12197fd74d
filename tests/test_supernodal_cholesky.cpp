// The supernodal Cholesky (src/solve/supernodal_cholesky.h) against Eigen's
// SimplicialLDLT (its own AMD ordering and a simplicial, unblocked
// factorization: a separate code path) on the conformal systems of generated
// meshes and on a matrix with a dense block (a supernode wide enough to be
// split in column blocks between threads); its fall-back when the matrix is
// not positive definite; tiny and disconnected systems; and results that are
// the same bit for bit with 1, 2 and 3 threads.
#include <random>

#include "weights/assemble.h"
#include "intrinsic/boundary.h"
#include "intrinsic/error.h"
#include "solve/linear_solver.h"
#include "intrinsic/parameterize.h"
#include "solve/supernodal_cholesky.h"
#include "solve/supernodal_lu.h"
#include "test_support.h"

namespace intrinsic {
namespace {

struct System {
  SparseMatrix A;     // interior rows and columns
  Eigen::MatrixXd B;  // the fixed boundary's contribution, u and v
};

// The conformal matrix with every boundary loop fixed on a circle (each
// component of the mesh its own, so disconnected meshes stay definite).
System conformal_system(const Mesh& mesh, const WeightOptions& w = WeightOptions()) {
  const SparseMatrix K = assemble_weight_matrix(mesh.V, mesh.F, w);
  std::vector<char> fixed(mesh.V.rows(), 0);
  Eigen::MatrixXd all = Eigen::MatrixXd::Zero(mesh.V.rows(), 2);
  for (const std::vector<int>& loop : mesh.topology.boundary_loops) {
    for (int v : loop) fixed[v] = 1;
    for (const FixedVertex& f : circle_boundary(mesh.V, loop, Spacing::ArcLength)) all.row(f.vertex) = f.uv.transpose();
  }
  const Partition p = partition(static_cast<int>(mesh.V.rows()), fixed, mesh.topology.is_used);
  System s;
  SparseMatrix KB;
  split_matrix(K, p, s.A, KB);
  Eigen::MatrixXd UB = Eigen::MatrixXd::Zero(KB.cols(), 2);
  int k = 0;
  for (int v = 0; v < mesh.V.rows(); ++v)
    if (fixed[v]) UB.row(k++) = all.row(v);
  s.B = -(KB * UB);
  s.A.makeCompressed();
  return s;
}

Eigen::MatrixXd reference_solve(const SparseMatrix& A, const Eigen::MatrixXd& B) {
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(A);
  EXPECT_EQ(ldlt.info(), Eigen::Success);
  return ldlt.solve(B);
}

double relative_difference(const Eigen::MatrixXd& X, const Eigen::MatrixXd& ref) {
  return (X - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
}

// A sparse SPD matrix with a dense m x m block coupled to a path: the
// analysis makes the block one supernode, wider than one column block.
SparseMatrix dense_block_matrix(int m, int path) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = m + path;
  Eigen::MatrixXd G(m, m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) G(i, j) = u(rng);
  const Eigen::MatrixXd D = G * G.transpose() / m + Eigen::MatrixXd::Identity(m, m);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) t.emplace_back(i, j, D(i, j));
  for (int k = 0; k < path; ++k) {
    const int v = m + k, prev = k == 0 ? 0 : v - 1;
    t.emplace_back(v, v, 3.0);
    t.emplace_back(v, prev, -1.0);
    t.emplace_back(prev, v, -1.0);
    t.emplace_back(prev, prev, 1.0);
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

#ifdef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
Eigen::MatrixXd factor_and_solve(const SparseMatrix& A, const Eigen::MatrixXd& B, int threads) {
  detail::SupernodalCholesky f(threads);
  EXPECT_TRUE(f.factor(A));
  return f.solve(B);
}
#endif

TEST(SupernodalCholeskySolver, AgreesWithLDLTOnConformal) {
  if (!solver_available(SolverKind::SupernodalCholesky)) GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
  for (int rings : {6, 30, 90}) {
    const System s = conformal_system(test::wavy(rings));
    const Eigen::MatrixXd ref = reference_solve(s.A, s.B);
    LinearSolver solver(SolverKind::Auto, true);
    solver.factor(s.A);
    EXPECT_EQ(solver.kind(), SolverKind::SupernodalCholesky);
    EXPECT_LT(relative_difference(solver.solve(s.B), ref), 1e-10) << rings;
#ifdef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
    // Without the solver's refinement: the factorization itself.
    EXPECT_LT(relative_difference(factor_and_solve(s.A, s.B, 2), ref), 1e-9) << rings;
#endif
  }
}

TEST(SupernodalCholeskySolver, WideSupernodeSplitInColumnBlocks) {
#ifndef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
#else
  const SparseMatrix A = dense_block_matrix(700, 3000);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 3);
  const Eigen::MatrixXd ref = reference_solve(A, B);
  EXPECT_LT(relative_difference(factor_and_solve(A, B, 2), ref), 1e-11);
  detail::SupernodalCholesky f(2);
  ASSERT_TRUE(f.factor(A));
  // The dense block alone stores 700 * 701 / 2 entries.
  EXPECT_GE(f.factor_nonzeros(), 700.0 * 701 / 2);
#endif
}

TEST(SupernodalCholeskySolver, SameBitsWithOneTwoAndThreeThreads) {
#ifndef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
#else
  const System s = conformal_system(test::wavy(90));
  const SparseMatrix D = dense_block_matrix(600, 2000);
  const Eigen::MatrixXd BD = Eigen::MatrixXd::Random(D.rows(), 2);
  const Eigen::MatrixXd X1 = factor_and_solve(s.A, s.B, 1), D1 = factor_and_solve(D, BD, 1);
  for (int threads : {2, 3}) {
    EXPECT_TRUE((factor_and_solve(s.A, s.B, threads).array() == X1.array()).all()) << threads;
    EXPECT_TRUE((factor_and_solve(D, BD, threads).array() == D1.array()).all()) << threads;
  }
#endif
}

TEST(SupernodalCholeskySolver, LUSubtreesGiveTheSameBitsWithOneTwoAndThreeThreads) {
#ifndef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
#else
  // The supernodal LU shares the subtree schedule (authalic: not symmetric).
  WeightOptions w;
  w.method = Method::Authalic;
  const System s = conformal_system(test::wavy(90), w);
  Eigen::SparseLU<SparseMatrix> lu(s.A);
  ASSERT_EQ(lu.info(), Eigen::Success);
  const Eigen::MatrixXd ref = lu.solve(s.B);
  Eigen::MatrixXd X1;
  for (int threads : {1, 2, 3}) {
    detail::SupernodalLU f(threads);
    ASSERT_TRUE(f.factor(s.A));
    const Eigen::MatrixXd X = f.solve(s.B);
    EXPECT_LT(relative_difference(X, ref), 1e-9);
    if (threads == 1) X1 = X;
    else EXPECT_TRUE((X.array() == X1.array()).all()) << threads;
  }
#endif
}

TEST(SupernodalCholeskySolver, NotPositiveDefiniteFallsBack) {
  if (!solver_available(SolverKind::SupernodalCholesky)) GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
  System s = conformal_system(test::wavy(12));
  // One negative diagonal entry: symmetric, indefinite, still nonsingular.
  s.A.coeffRef(5, 5) = -s.A.coeff(5, 5);
  Eigen::SparseLU<SparseMatrix> lu(s.A);
  ASSERT_EQ(lu.info(), Eigen::Success);
  const Eigen::MatrixXd ref = lu.solve(s.B);
#ifdef INTRINSIC_HAVE_SUPERNODAL_CHOLESKY
  detail::SupernodalCholesky f;
  EXPECT_FALSE(f.factor(s.A));
#endif
  LinearSolver solver(SolverKind::Auto, true);
  solver.factor(s.A);
  EXPECT_NE(solver.kind(), SolverKind::SupernodalCholesky);
  EXPECT_NE(solver.kind(), SolverKind::Cholmod);
  EXPECT_LT(relative_difference(solver.solve(s.B), ref), 1e-9) << solver.name();
  LinearSolver explicit_choice(SolverKind::SupernodalCholesky, true);
  EXPECT_THROW(explicit_choice.factor(s.A), Error);
}

TEST(SupernodalCholeskySolver, TinySystems) {
  if (!solver_available(SolverKind::SupernodalCholesky)) GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
  SparseMatrix one(1, 1);
  one.insert(0, 0) = 4;
  one.makeCompressed();
  LinearSolver solver(SolverKind::Auto, true);
  solver.factor(one);
  EXPECT_EQ(solver.kind(), SolverKind::SupernodalCholesky);
  EXPECT_DOUBLE_EQ(solver.solve(Eigen::MatrixXd::Constant(1, 2, 2.0))(0, 1), 0.5);
  LinearSolver empty(SolverKind::SupernodalCholesky, true);
  empty.factor(SparseMatrix(0, 0));
  EXPECT_EQ(empty.solve(Eigen::MatrixXd(0, 2)).rows(), 0);
}

TEST(SupernodalCholeskySolver, DisconnectedPiecesAreSeveralRoots) {
  if (!solver_available(SolverKind::SupernodalCholesky)) GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
  // Two disks (two trees), and a block-diagonal matrix of 40 copies of a
  // small system (40 trees, each its own subtree task).
  const System two = conformal_system(test::two_disks());
  LinearSolver solver(SolverKind::SupernodalCholesky, true);
  solver.factor(two.A);
  EXPECT_LT(relative_difference(solver.solve(two.B), reference_solve(two.A, two.B)), 1e-10);
  const System small = conformal_system(test::wavy(4));
  const int m = static_cast<int>(small.A.rows()), copies = 40;
  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < copies; ++c)
    for (int j = 0; j < m; ++j)
      for (SparseMatrix::InnerIterator it(small.A, j); it; ++it)
        t.emplace_back(c * m + static_cast<int>(it.row()), c * m + j, it.value() * (1 + c));
  SparseMatrix A(m * copies, m * copies);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 2);
  solver.factor(A);
  EXPECT_EQ(solver.kind(), SolverKind::SupernodalCholesky);
  EXPECT_LT(relative_difference(solver.solve(B), reference_solve(A, B)), 1e-10);
}

}  // namespace
}  // namespace intrinsic
