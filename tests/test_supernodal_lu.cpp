// The supernodal LU without pivoting (src/solve/supernodal_lu.h) against
// Eigen's SparseLU (partial pivoting, its own COLAMD ordering: a separate
// code path) on the authalic and mixed systems of generated meshes and on a
// matrix with a dense block (a supernode split in column blocks between
// threads), with several right-hand sides, plain and transposed; factors and
// solutions the same bit for bit with 1, 2 and 3 threads; and its fall-back
// to UMFPACK on matrices that need pivoting.
#include <random>

#include "weights/assemble.h"
#include "intrinsic/boundary.h"
#include "solve/linear_solver.h"
#include "intrinsic/parameterize.h"
#include "solve/supernodal_lu.h"
#include "util/parallel_for.h"
#include "test_support.h"

namespace intrinsic {
namespace {

struct System {
  SparseMatrix A;     // interior rows and columns
  Eigen::MatrixXd B;  // the circle boundary's contribution, u and v
};

// The method's weight matrix with the outer loop fixed on a circle.
System fixed_boundary_system(const Mesh& mesh, const WeightOptions& w) {
  const SparseMatrix K = assemble_weight_matrix(mesh.V, mesh.F, w);
  const std::vector<int>& loop = mesh.topology.boundary_loops[0];
  std::vector<char> fixed(mesh.V.rows(), 0);
  for (int v : loop) fixed[v] = 1;
  const Partition p = partition(static_cast<int>(mesh.V.rows()), fixed, mesh.topology.is_used);
  System s;
  SparseMatrix KB;
  split_matrix(K, p, s.A, KB);
  Eigen::MatrixXd UB = Eigen::MatrixXd::Zero(KB.cols(), 2);
  const std::vector<FixedVertex> circle = circle_boundary(mesh.V, loop, Spacing::ArcLength);
  Eigen::MatrixXd all = Eigen::MatrixXd::Zero(mesh.V.rows(), 2);
  for (const FixedVertex& f : circle) all.row(f.vertex) = f.uv.transpose();
  int k = 0;
  for (int v = 0; v < mesh.V.rows(); ++v)
    if (fixed[v]) UB.row(k++) = all.row(v);
  s.B = -(KB * UB);
  return s;
}

Eigen::MatrixXd reference_solve(const SparseMatrix& A, const Eigen::MatrixXd& B) {
  Eigen::SparseLU<SparseMatrix> lu(A);
  EXPECT_EQ(lu.info(), Eigen::Success);
  return lu.solve(B);
}

double relative_difference(const Eigen::MatrixXd& X, const Eigen::MatrixXd& ref) {
  return (X - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
}

WeightOptions weights(Method m, double lambda, double mu) {
  WeightOptions w;
  w.method = m;
  w.lambda = lambda;
  w.mu = mu;
  return w;
}

TEST(SupernodalLUSolver, AgreesWithPlainLUOnAuthalicAndMixed) {
  if (!solver_available(SolverKind::SupernodalLU)) GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
  // A jittered patch: obtuse angles, so the mixed weights include negative
  // cotangents and some rows are not diagonally dominant.
  const Mesh mesh = test::wavy(40, 0.5);
  for (const WeightOptions& w : {weights(Method::Authalic, 0, 1), weights(Method::Mixed, 0.5, 0.5)}) {
    SCOPED_TRACE(method_name(w.method));
    const System s = fixed_boundary_system(mesh, w);
    ASSERT_GT(s.A.rows(), 4000);
    ASSERT_GT((SparseMatrix(s.A.transpose()) - s.A).norm(), 1e-3 * s.A.norm());  // really not symmetric
    LinearSolver solver(SolverKind::SupernodalLU, false);
    solver.factor(s.A);
    const Eigen::MatrixXd X = solver.solve(s.B);
    EXPECT_EQ(solver.kind(), SolverKind::SupernodalLU);  // no fall-back needed
    EXPECT_LT(relative_difference(X, reference_solve(s.A, s.B)), 1e-9);
    // Adjoint solves reuse the factors.
    const Eigen::MatrixXd Y = solver.solve_transposed(s.B);
    EXPECT_LT(relative_difference(Y, reference_solve(SparseMatrix(s.A.transpose()), s.B)), 1e-9);
    EXPECT_EQ(solver.kind(), SolverKind::SupernodalLU);
  }
}

TEST(SupernodalLUSolver, ParameterizeAutoPicksItAndAgrees) {
  if (!solver_available(SolverKind::SupernodalLU)) GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
  const Mesh mesh = test::wavy(30);
  for (const test::MethodCase& c : test::kMethods) {
    if (c.m == Method::Conformal) continue;
    ParamOptions o = test::options_for(c);
    o.solver = SolverKind::EigenLU;
    const MatrixX2d ref = parameterize(mesh, o).UV;
    o.solver = SolverKind::Auto;
    const ParamResult r = parameterize(mesh, o);
    ASSERT_EQ(r.solvers.size(), 1u);
    EXPECT_EQ(r.solvers[0], SolverKind::SupernodalLU) << method_name(c.m);
    EXPECT_LT(relative_difference(r.UV, ref), 1e-9) << method_name(c.m);
  }
}

// A non-symmetric matrix with a symmetric pattern: a dense m x m block
// (random, diagonally dominant by rows) coupled to a path with different
// values above and below the diagonal. The analysis makes the block one
// supernode, several column blocks wide.
SparseMatrix dense_block_matrix(int m, int path) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) t.emplace_back(i, j, (i == j ? 2.0 : 0.0) + u(rng) / m);
  for (int k = 0; k < path; ++k) {
    const int v = m + k, prev = k == 0 ? 0 : v - 1;
    t.emplace_back(v, v, 3.0);
    t.emplace_back(v, prev, -1.0 + 0.5 * u(rng));
    t.emplace_back(prev, v, -0.5 + 0.25 * u(rng));
    t.emplace_back(prev, prev, 1.0);
  }
  SparseMatrix A(m + path, m + path);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

// Rings of a wavy patch whose top separators are wide enough to be split
// in column blocks between threads.
constexpr int kSplitRings = 150;

#ifdef INTRINSIC_HAVE_SUPERNODAL_LU
// The factorization alone (no refinement) on `threads` threads, each count
// in turn: A X = B and A^T Y = B against Eigen's SparseLU of A and of A^T.
void expect_solves_agree(const SparseMatrix& A, const Eigen::MatrixXd& B, std::initializer_list<int> threads,
                         double tolerance) {
  const Eigen::MatrixXd X = reference_solve(A, B), Y = reference_solve(SparseMatrix(A.transpose()), B);
  for (int t : threads) {
    detail::SupernodalLU f(t);
    ASSERT_TRUE(f.factor(A));
    EXPECT_LT(relative_difference(f.solve(B), X), tolerance) << t;
    EXPECT_LT(relative_difference(f.solve(B, true), Y), tolerance) << t;
  }
}
#endif

TEST(SupernodalLUSolver, FactorsAloneAgreeWithSparseLUForSeveralRightHandSides) {
#ifndef INTRINSIC_HAVE_SUPERNODAL_LU
  GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
#else
  const Mesh mesh = test::wavy(60, 0.3);
  for (const WeightOptions& w : {weights(Method::Authalic, 0, 1), weights(Method::Mixed, 0.5, 0.5)}) {
    SCOPED_TRACE(method_name(w.method));
    const System s = fixed_boundary_system(mesh, w);
    Eigen::MatrixXd B(s.A.rows(), 5);
    B << s.B, Eigen::MatrixXd::Random(s.A.rows(), 3);
    expect_solves_agree(s.A, B, {2}, 1e-10);
    expect_solves_agree(s.A, B.col(2), {1}, 1e-10);  // one column
  }
#endif
}

TEST(SupernodalLUSolver, WideSupernodeSplitInColumnBlocks) {
#ifndef INTRINSIC_HAVE_SUPERNODAL_LU
  GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
#else
  // A dense block factored as one supernode (a leaf: one thread) and a
  // mesh large enough that its top separators are split between threads.
  const SparseMatrix D = dense_block_matrix(700, 3000);
  ASSERT_GT((SparseMatrix(D.transpose()) - D).norm(), 1e-2 * D.norm());  // really not symmetric
  const Eigen::MatrixXd BD = Eigen::MatrixXd::Random(D.rows(), 3);
  expect_solves_agree(D, BD, {2}, 1e-11);
  detail::SupernodalLU f(2);
  ASSERT_TRUE(f.factor(D));
  EXPECT_GE(f.factor_nonzeros(), 700.0 * 700);            // the dense block alone (L and U)
  EXPECT_GE(f.flops(), 2.0 / 3 * 700.0 * 700 * 700);      // at least its LU
  const System s = fixed_boundary_system(test::wavy(kSplitRings, 0.3), weights(Method::Authalic, 0, 1));
  ASSERT_TRUE(f.factor(s.A));
  ASSERT_GT(f.split_supernodes(), 0);
  Eigen::MatrixXd B(s.A.rows(), 3);
  B << s.B, Eigen::MatrixXd::Random(s.A.rows(), 1);
  expect_solves_agree(s.A, B, {1, 2}, 1e-10);
#endif
}

TEST(SupernodalLUSolver, SameBitsWithOneTwoAndThreeThreads) {
#ifndef INTRINSIC_HAVE_SUPERNODAL_LU
  GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
#else
  const System mixed = fixed_boundary_system(test::wavy(kSplitRings, 0.3), weights(Method::Mixed, 0.5, 0.5));
  const SparseMatrix D = dense_block_matrix(600, 2000);
  for (const SparseMatrix* A : {&mixed.A, &D}) {
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A->rows(), 3);
    std::vector<double> factors1;
    Eigen::MatrixXd X1, Y1;
    for (int threads : {1, 2, 3}) {
      detail::SupernodalLU f(threads);
      ASSERT_TRUE(f.factor(*A));
      const std::vector<double> factors = f.factor_values();
      const Eigen::MatrixXd X = f.solve(B), Y = f.solve(B, true);
      if (threads == 1) {
        factors1 = factors;
        X1 = X;
        Y1 = Y;
        continue;
      }
      EXPECT_TRUE(factors == factors1) << threads;
      EXPECT_TRUE((X.array() == X1.array()).all()) << threads;
      EXPECT_TRUE((Y.array() == Y1.array()).all()) << threads;
    }
  }
#endif
}

// The mesh's adjacency (a symmetric pattern) with random values that differ
// between (i, j) and (j, i), and the given diagonal.
SparseMatrix scrambled_adjacency(const Mesh& mesh, double diagonal) {
  const SparseMatrix K = assemble_weight_matrix(mesh.V, mesh.F, WeightOptions());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(0.5, 2.0);
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < K.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(K, j); it; ++it)
      t.emplace_back(static_cast<int>(it.row()), j, it.row() == j ? diagonal : value(rng));
  SparseMatrix A(K.rows(), K.cols());
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

TEST(SupernodalLUSolver, FallsBackToUmfpackWhenPivotingIsNeeded) {
  if (!solver_available(SolverKind::SupernodalLU)) GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
  const Mesh mesh = test::wavy(12);
  // Zero diagonal: the first pivot of every elimination order is zero, which
  // the factorization itself reports.
  const SparseMatrix A = scrambled_adjacency(mesh, 0.0);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 2);
  for (SolverKind k : {SolverKind::Auto, SolverKind::SupernodalLU}) {
    LinearSolver solver(k, false);
    solver.factor(A);
    EXPECT_EQ(solver.kind(), SolverKind::Umfpack) << solver_name(k);
    EXPECT_LT(relative_difference(solver.solve(B), reference_solve(A, B)), 1e-9) << solver_name(k);
  }
}

TEST(SupernodalLUSolver, TinyPivotsEndInUmfpack) {
  if (!solver_available(SolverKind::SupernodalLU)) GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
  // Diagonal 1e-13 or 2e-14 against off-diagonal entries near 1: elimination
  // without pivoting grows entries by about 1e13. Depending on the
  // cancellations either a later pivot falls below the floor (the
  // factorization fails) or the first solve's residual stays far above
  // rounding after refinement; both end in UMFPACK with an accurate answer.
  // (At 1e-12 which of the two answers depends on the elimination order:
  // refinement sometimes recovers; ModeratelySmallPivotsAreRefined covers
  // that side.)
  for (double diagonal : {1e-13, 2e-14}) {
    for (int rings : {8, 12, 16}) {
      const Mesh mesh = test::wavy(rings);
      const SparseMatrix A = scrambled_adjacency(mesh, diagonal);
      const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 2);
      LinearSolver solver(SolverKind::Auto, false);
      solver.factor(A);
      const Eigen::MatrixXd X = solver.solve(B);
      EXPECT_EQ(solver.kind(), SolverKind::Umfpack) << diagonal << " " << rings;
      EXPECT_LT(relative_difference(X, reference_solve(A, B)), 1e-9);
      EXPECT_LT(relative_difference(solver.solve_transposed(B), reference_solve(SparseMatrix(A.transpose()), B)),
                1e-9);
    }
  }
}

TEST(SupernodalLUSolver, ModeratelySmallPivotsAreRefined) {
  if (!solver_available(SolverKind::SupernodalLU)) GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
  // Diagonal 0.05 against off-diagonal entries of 0.5 to 2: no longer
  // diagonally dominant, some growth; whichever path answers (the LU with
  // refinement, or UMFPACK), the answer is accurate.
  const Mesh mesh = test::wavy(12);
  const SparseMatrix A = scrambled_adjacency(mesh, 0.05);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 2);
  LinearSolver solver(SolverKind::Auto, false);
  solver.factor(A);
  EXPECT_LT(relative_difference(solver.solve(B), reference_solve(A, B)), 1e-9) << solver.name();
  EXPECT_LT(relative_difference(solver.solve_transposed(B), reference_solve(SparseMatrix(A.transpose()), B)), 1e-9)
      << solver.name();
}

TEST(SupernodalLUSolver, EntryWithoutMirrorIsRefusedAndUmfpackAnswers) {
#ifndef INTRINSIC_HAVE_SUPERNODAL_LU
  GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
#else
  // The analysis reads the lower triangle only: an entry above the diagonal
  // whose mirror is absent may fall outside the factor's pattern. With the
  // entry in the last column and first row of a path (a tridiagonal matrix:
  // no fill), it does in every elimination order that keeps the path's
  // pattern, and in the others the factors are still exact.
  const int n = 200;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 4.0);
    if (i > 0) {
      t.emplace_back(i, i - 1, -1.0);
      t.emplace_back(i - 1, i, -1.5);
    }
  }
  t.emplace_back(0, n - 1, 0.5);
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, 2);
  detail::SupernodalLU f(2);
  if (f.factor(A)) EXPECT_LT(relative_difference(f.solve(B), reference_solve(A, B)), 1e-12);
  LinearSolver solver(SolverKind::Auto, false);
  solver.factor(A);
  EXPECT_LT(relative_difference(solver.solve(B), reference_solve(A, B)), 1e-12) << solver.name();
#endif
}

TEST(SupernodalLUSolver, EntriesWithoutMirrorAreNeverLost) {
#ifndef INTRINSIC_HAVE_SUPERNODAL_LU
  GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
#else
  // The assembly reads the entries of P^T A P above the diagonal that lie
  // right of a supernode at their mirror places in A's columns (no
  // transpose): such an entry whose mirror is absent would be lost, so the
  // factorization must then refuse the matrix (it counts the entries it
  // placed), and UMFPACK answers. Elsewhere the entry is read from its own
  // column and the factors stay exact. One entry of a diagonally dominant
  // matrix on a mesh's adjacency loses its mirror, below or above the
  // diagonal, in columns spread over the matrix: whichever case each falls
  // in, the factors solve the matrix or are refused.
  const SparseMatrix full = scrambled_adjacency(test::wavy(12), 20.0);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(full.rows(), 2);
  int refused = 0, cases = 0;
  for (bool below : {true, false})
    for (int step = 0; step < 8; ++step) {
      const int column = static_cast<int>(full.cols() - 1) * step / 7;
      std::vector<Eigen::Triplet<double>> t;
      int dropped = -1;
      for (int j = 0; j < full.outerSize(); ++j)
        for (SparseMatrix::InnerIterator it(full, j); it; ++it) {
          const bool drop = dropped < 0 && j == column && (below ? it.row() > j : it.row() < j);
          if (drop) dropped = static_cast<int>(it.row());
          else t.emplace_back(static_cast<int>(it.row()), j, it.value());
        }
      if (dropped < 0) continue;  // no entry on that side of the diagonal
      SparseMatrix A(full.rows(), full.cols());
      A.setFromTriplets(t.begin(), t.end());
      A.makeCompressed();
      ASSERT_NE(A.coeff(column, dropped), 0.0);  // its mirror stays
      const Eigen::MatrixXd ref = reference_solve(A, B);
      ++cases;
      detail::SupernodalLU f(2);
      if (f.factor(A)) EXPECT_LT(relative_difference(f.solve(B), ref), 1e-10) << column << " " << below;
      else ++refused;
      LinearSolver solver(SolverKind::Auto, false);
      solver.factor(A);
      EXPECT_LT(relative_difference(solver.solve(B), ref), 1e-10) << column << " " << below;
    }
  EXPECT_GE(cases, 14);
  // Which kept entries land above the diagonal right of a supernode
  // depends on the ordering; among 16 some do and some do not (both paths
  // of the check are taken).
  EXPECT_GT(refused, 0);
  EXPECT_LT(refused, cases);
#endif
}

// The refined solve of LinearSolver on a system large enough that the
// backward error's columns run on their own threads: the answer does not
// depend on the thread count, and agrees with Eigen's SparseLU, plain and
// transposed, with as many columns as threads and more.
TEST(SupernodalLUSolver, RefinedSolveSameBitsWithOneTwoAndThreeThreads) {
  if (!solver_available(SolverKind::SupernodalLU)) GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
  const System s = fixed_boundary_system(test::wavy(150, 0.3), weights(Method::Authalic, 0, 1));
  ASSERT_GE(s.A.nonZeros(), 200000);  // past the size where the columns get threads
  Eigen::MatrixXd B(s.A.rows(), 3);
  B << s.B, Eigen::VectorXd::Random(s.A.rows());
  const Eigen::MatrixXd ref = reference_solve(s.A, B), ref_t = reference_solve(SparseMatrix(s.A.transpose()), B);
  Eigen::MatrixXd X1, Y1;
  for (int threads : {1, 2, 3}) {
    detail::thread_limit() = threads;
    LinearSolver solver(SolverKind::Auto, false);
    solver.factor(s.A);
    EXPECT_EQ(solver.kind(), SolverKind::SupernodalLU);
    const Eigen::MatrixXd X = solver.solve(B), Y = solver.solve_transposed(B);
    EXPECT_LT(relative_difference(X, ref), 1e-10) << threads;
    EXPECT_LT(relative_difference(Y, ref_t), 1e-10) << threads;
    if (threads == 1) {
      X1 = X;
      Y1 = Y;
      continue;
    }
    EXPECT_TRUE((X.array() == X1.array()).all()) << threads;
    EXPECT_TRUE((Y.array() == Y1.array()).all()) << threads;
  }
  detail::thread_limit() = 0;
}

TEST(SupernodalLUSolver, TinySystems) {
  if (!solver_available(SolverKind::SupernodalLU)) GTEST_SKIP() << "built without SuiteSparse and OpenBLAS";
  // One unknown (a fan with one interior vertex) and none (every vertex fixed).
  SparseMatrix one(1, 1);
  one.insert(0, 0) = 4;
  LinearSolver solver(SolverKind::Auto, false);
  solver.factor(one);
  EXPECT_EQ(solver.kind(), SolverKind::SupernodalLU);
  EXPECT_DOUBLE_EQ(solver.solve(Eigen::MatrixXd::Constant(1, 2, 2.0))(0, 1), 0.5);
  LinearSolver empty(SolverKind::Auto, false);
  empty.factor(SparseMatrix(0, 0));
  EXPECT_EQ(empty.solve(Eigen::MatrixXd(0, 2)).rows(), 0);
}

}  // namespace
}  // namespace intrinsic
