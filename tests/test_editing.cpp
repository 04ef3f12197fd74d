// Realtime boundary editing (SPEC section 5): superposing impulse responses
// equals a fresh solve, in every method and both bases, with the one kept
// factorization; the memory budget and the re-solve fallback.
#include <gtest/gtest.h>

#include <random>

#include "intrinsic/boundary_editor.h"
#include "intrinsic/error.h"
#include "test_support.h"

namespace intrinsic {
namespace {

struct MethodCase {
  Method m;
  double lambda, mu;
};
const MethodCase kMethods[] = {{Method::Conformal, 1, 0}, {Method::Authalic, 0, 1}, {Method::Mixed, 0.3, 0.7}};

ParamOptions options_for(const MethodCase& c) {
  ParamOptions o;
  o.weights.method = c.m;
  o.weights.lambda = c.lambda;
  o.weights.mu = c.mu;
  return o;
}

Mesh wavy() {
  GenerateOptions g;
  g.rings = 10;
  return make_mesh(generate_wavy_patch(g));
}

// k distinct fixed vertices moved by up to 0.05.
std::vector<FixedVertex> random_move(const std::vector<FixedVertex>& boundary, int k, std::mt19937& rng) {
  std::vector<FixedVertex> b = boundary;
  std::shuffle(b.begin(), b.end(), rng);
  std::uniform_real_distribution<double> d(-0.05, 0.05);
  b.resize(k);
  for (FixedVertex& fv : b) fv.uv += Eigen::Vector2d(d(rng), d(rng));
  return b;
}

MatrixX2d fresh_solve(const Mesh& mesh, const ParamOptions& o, const std::vector<FixedVertex>& boundary,
                      const Constraints& c = {}) {
  ParamOptions given = o;
  given.boundary = BoundaryShape::Given;
  given.given = boundary;
  Parameterizer p(mesh, given);
  if (!c.empty()) p.set_constraints(c);
  return p.solve().UV;
}

TEST(Editing, SuperpositionEqualsFullSolve) {
  const Mesh mesh = wavy();
  std::mt19937 rng(7);
  for (const MethodCase& mc : kMethods)
    for (BasisMode basis : {BasisMode::Full, BasisMode::Lazy}) {
      Parameterizer p(mesh, options_for(mc));
      EditOptions eo;
      eo.basis = basis;
      eo.resolve_above = 1 << 20;  // always superpose
      BoundaryEditor editor(p, eo);
      const int nb = static_cast<int>(p.boundary().size());
      for (int k : {1, 3, 10, nb}) {
        const MatrixX2d before = editor.uv();
        const MatrixX2d& uv = editor.move(random_move(editor.boundary(), k, rng));
        EXPECT_FALSE(editor.last_update().resolved);
        EXPECT_EQ(editor.last_update().moved, k);
        EXPECT_GT((uv - before).cwiseAbs().maxCoeff(), 1e-4);
        EXPECT_LT((uv - fresh_solve(mesh, p.options(), editor.boundary())).cwiseAbs().maxCoeff(), 1e-10)
            << method_name(mc.m) << " k=" << k << (basis == BasisMode::Full ? " full" : " lazy");
      }
      EXPECT_EQ(p.factorizations(), 1);
    }
}

TEST(Editing, SuperpositionKeepsConstraintsMet) {
  const Mesh mesh = wavy();
  std::mt19937 rng(3);
  for (const MethodCase& mc : kMethods) {
    Parameterizer p(mesh, options_for(mc));
    Constraints c;
    c.points.push_back({SurfacePoint::in_face(20, Eigen::Vector3d(0.2, 0.3, 0.5)), Eigen::Vector2d(0.45, 0.5), ""});
    c.points.push_back({SurfacePoint::in_face(150, Eigen::Vector3d(0.6, 0.3, 0.1)), Eigen::Vector2d(0.6, 0.55), ""});
    p.set_constraints(c);
    EditOptions eo;
    eo.basis = BasisMode::Lazy;
    BoundaryEditor editor(p, eo);
    for (int round = 0; round < 3; ++round) {
      const MatrixX2d& uv = editor.move(random_move(editor.boundary(), 5, rng));
      EXPECT_LT((uv - fresh_solve(mesh, p.options(), editor.boundary(), c)).cwiseAbs().maxCoeff(), 1e-10);
      for (const ConstraintResidual& r : p.residuals(uv)) EXPECT_LT(r.residual, 1e-10) << r.label;
    }
  }
}

TEST(Editing, TenBoundaryMovesOneFactorization) {
  const Mesh mesh = wavy();
  std::mt19937 rng(11);
  Parameterizer p(mesh, options_for(kMethods[1]));
  EXPECT_EQ(p.factorizations(), 1);
  for (int i = 0; i < 10; ++i) {
    std::vector<FixedVertex> b = p.boundary();
    for (const FixedVertex& m : random_move(b, 4, rng))
      for (FixedVertex& fv : b)
        if (fv.vertex == m.vertex) fv.uv = m.uv;
    const ParamResult r = p.solve_with_boundary(b);
    EXPECT_LT((r.UV - fresh_solve(mesh, p.options(), b)).cwiseAbs().maxCoeff(), 1e-10);
  }
  EXPECT_EQ(p.factorizations(), 1);
  BoundaryEditor editor(p);
  for (int i = 0; i < 10; ++i) editor.move(random_move(editor.boundary(), 2, rng));
  EXPECT_EQ(p.factorizations(), 1);
  // Fixing one more vertex changes K_II: the counter must see it.
  std::vector<FixedVertex> more = p.boundary();
  int interior = 0;
  while (mesh.topology.is_boundary[interior]) ++interior;
  more.push_back({interior, p.solve().UV.row(interior).transpose()});
  p.solve_with_boundary(more);
  EXPECT_EQ(p.factorizations(), 2);
}

TEST(Editing, LazyCachesAndFallsBackToResolve) {
  const Mesh mesh = wavy();
  std::mt19937 rng(5);
  Parameterizer p(mesh, options_for(kMethods[2]));
  EditOptions eo;
  eo.resolve_above = 8;
  BoundaryEditor editor(p, eo);
  EXPECT_EQ(editor.responses(), 0);
  const std::vector<FixedVertex> first = random_move(editor.boundary(), 3, rng);
  editor.move(first);
  EXPECT_EQ(editor.last_update().new_responses, 3);
  std::vector<FixedVertex> again = first;
  for (FixedVertex& fv : again) fv.uv += Eigen::Vector2d(0.01, -0.02);
  editor.move(again);
  EXPECT_EQ(editor.last_update().new_responses, 0) << "the second drag of the same vertices uses the cache";
  EXPECT_EQ(editor.responses(), 3);
  const MatrixX2d& uv = editor.move(random_move(editor.boundary(), 20, rng));
  EXPECT_TRUE(editor.last_update().resolved);
  EXPECT_EQ(editor.responses(), 3);
  EXPECT_LT((uv - fresh_solve(mesh, p.options(), editor.boundary())).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(Editing, FullBasisRefusedAboveMemoryBudget) {
  const Mesh mesh = wavy();
  Parameterizer p(mesh, ParamOptions{});
  EditOptions eo;
  eo.basis = BasisMode::Full;
  eo.memory_budget = 1000;
  try {
    BoundaryEditor editor(p, eo);
    ADD_FAILURE() << "expected refusal";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("above the memory budget"), std::string::npos) << e.what();
  }
  eo.memory_budget = std::size_t(1) << 30;
  BoundaryEditor editor(p, eo);
  EXPECT_EQ(editor.responses(), static_cast<int>(p.boundary().size()));
}

TEST(Editing, OnlyFixedVerticesMove) {
  const Mesh mesh = wavy();
  Parameterizer p(mesh, ParamOptions{});
  BoundaryEditor editor(p);
  int interior = 0;
  while (mesh.topology.is_boundary[interior]) ++interior;
  try {
    editor.move({{interior, Eigen::Vector2d(0.5, 0.5)}});
    ADD_FAILURE() << "expected refusal";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_NE(std::string(e.what()).find("vertex " + std::to_string(interior) + " is not a fixed"), std::string::npos);
  }
}

}  // namespace
}  // namespace intrinsic
