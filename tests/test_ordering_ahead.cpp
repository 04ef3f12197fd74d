// The ordering and analysis computed ahead of the weights
// (src/solve/ordering_ahead.h): the pattern built from the faces or from
// K's is the assembled free block's, the analysis taken is the one
// analysing A gives (also from a pattern handed over built),
// a different pattern is refused, and the factorizations and maps through
// that path are the plain path's bit for bit (conformal: supernodal
// Cholesky; authalic and mixed: supernodal LU), with holes filled or free,
// for 1 to 3 threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <climits>
#include <set>
#include <vector>

#include "weights/assemble.h"
#include "intrinsic/generate.h"
#include "intrinsic/mesh.h"
#include "intrinsic/parameterizer.h"
#include "solve/ordering_ahead.h"
#include "solve/suitesparse.h"
#include "test_support.h"
#include "util/parallel_for.h"
#include "weights/assemble_stages.h"

#ifdef INTRINSIC_HAVE_SUITESPARSE

namespace intrinsic {
namespace {

struct Split {
  std::vector<char> known, used;
  SparseMatrix A, B;
};

// The free block of the assembled matrix, the outer loop known.
Split assembled_split(const Mesh& mesh, const WeightOptions& w) {
  Split s;
  const int n = static_cast<int>(mesh.V.rows());
  s.known.assign(n, 0);
  for (int v : mesh.topology.boundary_loops[0]) s.known[v] = 1;
  s.used.assign(mesh.topology.is_used.begin(), mesh.topology.is_used.end());
  const SparseMatrix K = assemble_weight_matrix(mesh.V, mesh.F, w);
  split_matrix(K, partition(n, s.known, s.used), s.A, s.B);
  s.A.makeCompressed();
  return s;
}

void expect_same_analysis(const detail::SupernodalSymbolic& a, const detail::SupernodalSymbolic& b) {
  EXPECT_EQ(a.n, b.n);
  EXPECT_EQ(a.nsuper, b.nsuper);
  EXPECT_EQ(a.perm, b.perm);
  EXPECT_EQ(a.super, b.super);
  EXPECT_EQ(a.pi, b.pi);
  EXPECT_EQ(a.px, b.px);
  EXPECT_EQ(a.rows, b.rows);
  EXPECT_EQ(a.super_of, b.super_of);
  EXPECT_EQ(a.parent, b.parent);
  EXPECT_EQ(a.flops, b.flops);
  EXPECT_EQ(a.nonzeros, b.nonzeros);
}

// Sets the size threshold for the test's duration (0: always ahead).
struct AheadAbove {
  int saved;
  explicit AheadAbove(int v) : saved(detail::analysis_ahead_min_vertices().exchange(v)) {}
  ~AheadAbove() { detail::analysis_ahead_min_vertices() = saved; }
};

void expect_same_pattern(const SparseMatrix& P, const SparseMatrix& A, const char* what) {
  ASSERT_EQ(P.rows(), A.rows()) << what;
  ASSERT_EQ(P.cols(), A.cols()) << what;
  ASSERT_EQ(P.nonZeros(), A.nonZeros()) << what;
  EXPECT_TRUE(std::equal(P.outerIndexPtr(), P.outerIndexPtr() + P.cols() + 1, A.outerIndexPtr())) << what;
  EXPECT_TRUE(std::equal(P.innerIndexPtr(), P.innerIndexPtr() + P.nonZeros(), A.innerIndexPtr())) << what;
}

// A holed disk: the centre vertices of the removed fans are unused, so the
// free numbering skips vertices as partition() does. Both ways of building
// the pattern (from the faces; from K's pattern, as the Parameterizer does)
// give the free block that split_matrix cuts from the assembled K, and that
// block is the free vertices' adjacency as a set written here.
TEST(OrderingAhead, PatternIsTheAssembledFreeBlock) {
  const Mesh mesh = make_mesh(test::holed_wavy(3));
  const Split s = assembled_split(mesh, WeightOptions{});
  const int n = static_cast<int>(mesh.V.rows());
  ASSERT_LT(std::count(s.used.begin(), s.used.end(), 1), n);  // some unused
  expect_same_pattern(detail::free_block_pattern(mesh.F, s.known, s.used), s.A, "from the faces");
  const SparseMatrix K = detail::weight_matrix_pattern(mesh.F, n);
  expect_same_pattern(detail::free_block_pattern(K, s.known, s.used), s.A, "from K's pattern");
  std::vector<int> free_index(n, -1);
  int nf = 0;
  for (int v = 0; v < n; ++v)
    if (s.used[v] && !s.known[v]) free_index[v] = nf++;
  std::vector<std::set<int>> sets(nf);
  for (int j = 0; j < nf; ++j) sets[j].insert(j);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      for (int e = 0; e < 3; ++e) {
        const int a = free_index[mesh.F(f, c)], b = free_index[mesh.F(f, e)];
        if (a >= 0 && b >= 0) sets[a].insert(b);
      }
  ASSERT_EQ(s.A.cols(), nf);
  for (int j = 0; j < nf; ++j) {
    const std::vector<int> column(s.A.innerIndexPtr() + s.A.outerIndexPtr()[j],
                                  s.A.innerIndexPtr() + s.A.outerIndexPtr()[j + 1]);
    ASSERT_EQ(column, std::vector<int>(sets[j].begin(), sets[j].end())) << "column " << j;
  }
}

// A pattern handed over built (the Parameterizer's way): its analysis is
// the one analysing A gives, and the pattern given is taken, not copied.
TEST(OrderingAhead, TakesTheAnalysisOfAGivenPattern) {
  const Mesh mesh = make_mesh(test::holed_wavy(2));
  const Split s = assembled_split(mesh, WeightOptions{});
  detail::SupernodalSymbolic plain, ahead_result;
  ASSERT_TRUE(detail::supernodal_analysis(s.A, plain));
  SparseMatrix P = detail::free_block_pattern(detail::weight_matrix_pattern(mesh.F, static_cast<int>(mesh.V.rows())),
                                              s.known, s.used);
  detail::AnalysisAhead ahead(std::move(P));
  EXPECT_EQ(P.nonZeros(), 0);
  ASSERT_TRUE(ahead.take(s.A, ahead_result));
  expect_same_analysis(plain, ahead_result);
}

TEST(OrderingAhead, TakesTheAnalysisOfA) {
  GenerateOptions g;
  g.rings = 60;
  const Mesh mesh = make_mesh(generate_wavy_patch(g));
  const Split s = assembled_split(mesh, WeightOptions{});
  detail::SupernodalSymbolic plain, ahead_result;
  ASSERT_TRUE(detail::supernodal_analysis(s.A, plain));
  detail::AnalysisAhead ahead(detail::free_block_pattern(mesh.F, s.known, s.used));
  ASSERT_TRUE(ahead.take(s.A, ahead_result));
  expect_same_analysis(plain, ahead_result);
  EXPECT_FALSE(ahead.take(s.A, ahead_result));  // once only
}

// One more known vertex: another pattern, which the analysis ahead refuses
// (and leaves `out` alone); a LinearSolver given it analyses A itself.
TEST(OrderingAhead, RefusesAnotherPattern) {
  const Mesh mesh = make_mesh(test::holed_wavy(1));
  const Split s = assembled_split(mesh, WeightOptions{});
  std::vector<char> more_known = s.known;
  for (int v = 0; v < static_cast<int>(more_known.size()); ++v)
    if (s.used[v] && !more_known[v]) {
      more_known[v] = 1;
      break;
    }
  detail::AnalysisAhead ahead(detail::free_block_pattern(mesh.F, more_known, s.used));
  detail::SupernodalSymbolic out;
  out.nsuper = -7;
  EXPECT_FALSE(ahead.take(s.A, out));
  EXPECT_EQ(out.nsuper, -7);
  // Given to a LinearSolver: refused there too, A analysed as without it.
  const Eigen::MatrixXd rhs = -(s.B * Eigen::MatrixXd::Random(s.B.cols(), 2));
  LinearSolver plain(SolverKind::Auto, true), refused(SolverKind::Auto, true);
  plain.factor(s.A);
  const long before = detail::analysis_ahead_taken().load();
  refused.set_analysis_ahead(
      std::make_shared<detail::AnalysisAhead>(detail::free_block_pattern(mesh.F, more_known, s.used)));
  refused.factor(s.A);
  EXPECT_EQ(detail::analysis_ahead_taken().load(), before);
  EXPECT_TRUE(plain.solve(rhs) == refused.solve(rhs));
}

// LinearSolver with and without the analysis ahead: the same solution bit
// for bit, and the path ahead was taken.
TEST(OrderingAhead, LinearSolverSameSolutionToTheBit) {
  GenerateOptions g;
  g.rings = 50;
  const Mesh mesh = make_mesh(generate_wavy_patch(g));
  for (const test::MethodCase& c : test::kMethods) {
    const ParamOptions o = test::options_for(c);
    const Split s = assembled_split(mesh, o.weights);
    const Eigen::MatrixXd rhs = -(s.B * Eigen::MatrixXd::Random(s.B.cols(), 2));
    const bool symmetric = is_symmetric(o.weights);
    LinearSolver plain(SolverKind::Auto, symmetric), ahead(SolverKind::Auto, symmetric);
    plain.factor(s.A);
    const long before = detail::analysis_ahead_taken().load();
    ahead.set_analysis_ahead(
        std::make_shared<detail::AnalysisAhead>(detail::free_block_pattern(mesh.F, s.known, s.used)));
    ahead.factor(s.A);
    EXPECT_EQ(detail::analysis_ahead_taken().load(), before + 1) << method_name(c.m);
    EXPECT_EQ(ahead.kind(), plain.kind());
    const Eigen::MatrixXd x = plain.solve(rhs), y = ahead.solve(rhs);
    EXPECT_TRUE(x == y) << method_name(c.m) << ": max difference " << (x - y).cwiseAbs().maxCoeff();
  }
}

ParamResult solve_with_ahead_above(const Mesh& mesh, const ParamOptions& o, int above) {
  const AheadAbove guard(above);
  return Parameterizer(mesh, o).solve();
}

// The Parameterizer's maps with the analysis ahead (threshold 0) and
// without (INT_MAX): equal to the bit, every method, holes filled (the
// pattern of the filled surface) or free.
TEST(OrderingAhead, ParameterizerSameUVsToTheBit) {
  const Mesh mesh = make_mesh(test::holed_wavy(3));
  for (const test::MethodCase& c : test::kMethods)
    for (HoleRule holes : {HoleRule::Fill, HoleRule::Free}) {
      ParamOptions o = test::options_for(c);
      o.holes = holes;
      const ParamResult plain = solve_with_ahead_above(mesh, o, INT_MAX);
      const long before = detail::analysis_ahead_taken().load();
      const ParamResult ahead = solve_with_ahead_above(mesh, o, 0);
      EXPECT_EQ(detail::analysis_ahead_taken().load(), before + 1);
      EXPECT_EQ(ahead.filled_holes, plain.filled_holes);
      EXPECT_TRUE(ahead.UV == plain.UV) << method_name(c.m) << " " << hole_rule_name(holes);
    }
}

// Above the default threshold (about 22k vertices), on 1, 2 and 3 threads:
// the path ahead is taken by default and gives the plain path's map.
TEST(OrderingAhead, DefaultPathSameUVsForAnyThreadCount) {
  GenerateOptions g;
  g.rings = 85;
  const Mesh mesh = make_mesh(generate_wavy_patch(g));
  ASSERT_GE(mesh.V.rows(), detail::analysis_ahead_min_vertices().load());
  const ParamOptions o;
  const ParamResult plain = solve_with_ahead_above(mesh, o, INT_MAX);
  std::atomic<int>& limit = detail::thread_limit();
  for (int threads : {1, 2, 3}) {
    limit = threads;
    const long before = detail::analysis_ahead_taken().load();
    const ParamResult ahead = Parameterizer(mesh, o).solve();
    EXPECT_EQ(detail::analysis_ahead_taken().load(), before + 1) << threads << " threads";
    EXPECT_TRUE(ahead.UV == plain.UV) << threads << " threads";
  }
  limit = 0;
}

}  // namespace
}  // namespace intrinsic

#endif
