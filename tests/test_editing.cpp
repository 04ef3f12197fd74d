// Realtime boundary editing (docs/maths.md §6): superposing impulse responses
// equals a fresh solve, in every method and both bases, with the one kept
// factorization; the memory budget and the re-solve fallback.
#include <gtest/gtest.h>

#include <random>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "intrinsic/boundary_editor.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "test_support.h"

namespace intrinsic {
namespace {

using test::kMethods;
using test::MethodCase;
using test::options_for;
using test::wavy;

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
  test::expect_error([&] { BoundaryEditor editor(p, eo); }, ErrorKind::Usage, "above the memory budget");
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
  test::expect_error([&] { editor.move({{interior, Eigen::Vector2d(0.5, 0.5)}}); }, ErrorKind::Input,
                     "vertex " + std::to_string(interior) + " is not a fixed");
}

ParamOptions natural_pins(std::vector<FixedVertex> pins) {
  ParamOptions o;
  o.boundary = BoundaryShape::Natural;
  o.pins = std::move(pins);
  return o;
}

// The natural map is linear in the pin positions: moving pins through two
// responses each equals a fresh Parameterizer built with the moved pins
// (its own factorization), with and without constraints, in both bases.
TEST(Editing, NaturalPinsSuperposeAsFreshSolve) {
  const Mesh mesh = wavy();
  const int b = mesh.topology.boundary_loops[0][5];
  const std::vector<FixedVertex> pins = {{b, Eigen::Vector2d(0.1, 0.2)}, {60, Eigen::Vector2d(0.8, 0.3)},
                                         {130, Eigen::Vector2d(0.4, 0.9)}};
  Constraints c;
  c.points.push_back({SurfacePoint::in_face(20, Eigen::Vector3d(0.2, 0.3, 0.5)), Eigen::Vector2d(0.45, 0.5), ""});
  for (const bool constrained : {false, true})
    for (BasisMode basis : {BasisMode::Full, BasisMode::Lazy}) {
      Parameterizer p(mesh, natural_pins(pins));
      if (constrained) p.set_constraints(c);
      EditOptions eo;
      eo.basis = basis;
      BoundaryEditor editor(p, eo);
      if (basis == BasisMode::Lazy && constrained) {
        editor.prepare({pins[0].vertex, pins[1].vertex, pins[2].vertex});
        EXPECT_EQ(editor.responses(), 6) << "two responses per pin, computed up front";
      }
      std::vector<FixedVertex> moved = pins;
      for (int round = 0; round < 3; ++round) {
        moved[round % 3].uv += Eigen::Vector2d(0.03 * (round + 1), -0.02);
        moved[(round + 1) % 3].uv += Eigen::Vector2d(-0.01, 0.04);
        const MatrixX2d before = editor.uv();
        const MatrixX2d& uv = editor.move(moved);
        EXPECT_FALSE(editor.last_update().resolved);
        EXPECT_EQ(editor.last_update().moved, 2);
        if (basis == BasisMode::Lazy && constrained) EXPECT_EQ(editor.last_update().new_responses, 0);
        EXPECT_GT((uv - before).cwiseAbs().maxCoeff(), 1e-3);
        Parameterizer fresh(mesh, natural_pins(moved));
        if (constrained) fresh.set_constraints(c);
        EXPECT_LT((uv - fresh.solve().UV).cwiseAbs().maxCoeff(), 1e-9)
            << "round " << round << (constrained ? " constrained" : "") << (basis == BasisMode::Full ? " full" : " lazy");
        for (const FixedVertex& q : moved) EXPECT_EQ(uv.row(q.vertex), q.uv.transpose()) << "pins sit exactly";
        if (constrained) EXPECT_LT(p.residuals(uv)[0].residual, 1e-9);
      }
      EXPECT_EQ(editor.responses(), 6) << "two responses per pin (lazy: every pin was moved)";
      EXPECT_EQ(p.factorizations(), 1);
      EXPECT_EQ(p.boundary().size(), 3u);
    }
}

// The map is affine in the constraint targets: new targets through the
// target responses equal a fresh solve with those targets (fixed boundary
// in every method, and the natural layout), the responses computed once.
TEST(Editing, ConstraintTargetsSuperposeAsFreshSolve) {
  const Mesh mesh = wavy();
  Constraints c;
  c.points.push_back({SurfacePoint::in_face(20, Eigen::Vector3d(0.2, 0.3, 0.5)), Eigen::Vector2d(0.45, 0.5), ""});
  c.points.push_back({SurfacePoint::in_face(150, Eigen::Vector3d(0.6, 0.3, 0.1)), Eigen::Vector2d(0.6, 0.55), ""});
  std::vector<ParamOptions> cases;
  for (const MethodCase& mc : kMethods) cases.push_back(options_for(mc));
  cases.push_back(natural_pins({{0, Eigen::Vector2d(0, 0)}, {7, Eigen::Vector2d(1, 0)}}));
  for (size_t k = 0; k < cases.size(); ++k) {
    Parameterizer p(mesh, cases[k]);
    p.set_constraints(c);
    BoundaryEditor editor(p);
    std::vector<Eigen::Vector2d> targets = {c.points[0].uv, c.points[1].uv};
    for (int round = 0; round < 3; ++round) {
      targets[0] += Eigen::Vector2d(0.02, -0.01 * round);
      if (round == 2) targets[1] += Eigen::Vector2d(-0.03, 0.01);
      const MatrixX2d before = editor.uv();
      const MatrixX2d& uv = editor.move_targets(targets);
      EXPECT_FALSE(editor.last_update().resolved);
      EXPECT_EQ(editor.last_update().moved, round == 2 ? 2 : 1);
      EXPECT_EQ(editor.last_update().new_responses, round == 0 || round == 2 ? (k == 3 ? 2 : 1) : 0) << round;
      EXPECT_GT((uv - before).cwiseAbs().maxCoeff(), 1e-3);
      Constraints moved = c;
      moved.points[0].uv = targets[0];
      moved.points[1].uv = targets[1];
      Parameterizer fresh(mesh, p.options());
      fresh.set_constraints(moved);
      EXPECT_LT((uv - fresh.solve().UV).cwiseAbs().maxCoeff(), 1e-9) << "case " << k << " round " << round;
      for (const ConstraintResidual& r : p.residuals(uv)) EXPECT_LT(r.residual, 1e-9) << r.label;
    }
    // Boundary (or pin) moves after target moves still superpose correctly.
    const std::vector<FixedVertex> b = editor.boundary();
    std::vector<FixedVertex> m = {b[1]};
    m[0].uv += Eigen::Vector2d(0.02, 0.03);
    const MatrixX2d& uv = editor.move(m);
    Parameterizer fresh(mesh, p.options());
    Constraints moved = c;
    moved.points[0].uv = targets[0];
    moved.points[1].uv = targets[1];
    fresh.solve_with_boundary(editor.boundary());
    fresh.set_constraints(moved);
    EXPECT_LT((uv - fresh.solve().UV).cwiseAbs().maxCoeff(), 1e-9) << "case " << k;
    EXPECT_EQ(p.factorizations(), 1);
  }
}

// Circle <-> square on the kept factorization equals a Parameterizer built
// with the other shape, in both scale modes and with constraints kept.
TEST(Editing, BoundaryShapeSwapsWithoutRefactoring) {
  const Mesh mesh = wavy();
  Constraints c;
  c.points.push_back({SurfacePoint::in_face(20, Eigen::Vector3d(0.2, 0.3, 0.5)), Eigen::Vector2d(0.45, 0.5), ""});
  for (const ScaleMode scale : {ScaleMode::Unit, ScaleMode::Surface})
    for (const bool constrained : {false, true}) {
      ParamOptions o = options_for(kMethods[2]);
      o.scale = scale;
      Parameterizer p(mesh, o);
      if (constrained) p.set_constraints(c);
      for (const BoundaryShape shape : {BoundaryShape::Square, BoundaryShape::Circle}) {
        p.set_boundary_shape(shape);
        ParamOptions other = o;
        other.boundary = shape;
        Parameterizer fresh(mesh, other);
        if (constrained) fresh.set_constraints(c);
        const ParamResult want = fresh.solve();
        EXPECT_LT((p.solve().UV - want.UV).cwiseAbs().maxCoeff(), 1e-9)
            << (shape == BoundaryShape::Square ? "square" : "circle") << (constrained ? " constrained" : "");
        EXPECT_EQ(p.options().boundary, shape);
        EXPECT_EQ(p.boundary().size(), fresh.boundary().size());
      }
      EXPECT_EQ(p.factorizations(), 1);
    }
  Parameterizer q(mesh, natural_pins({}));
  test::expect_error([&] { q.set_boundary_shape(BoundaryShape::Square); }, ErrorKind::Usage, "circle and square");
}

std::string boundary_text(const std::vector<FixedVertex>& b) {
  std::string s;
  char line[128];
  for (const FixedVertex& fv : b) {
    std::snprintf(line, sizeof line, "%d %.17g %.17g\n", fv.vertex, fv.uv.x(), fv.uv.y());
    s += line;
  }
  return s;
}

// `intrinsic edit` with two moves equals `intrinsic param` with each moved
// boundary (each move applies to the base, not to the previous move).
TEST(Editing, CliMatchesFreshParam) {
  test::TempDir dir;
  GenerateOptions g;
  g.rings = 10;
  const MeshData data = generate_wavy_patch(g);
  write_mesh(dir / "in.obj", data.V, data.F, MatrixX2d());
  const Mesh mesh = make_mesh(data);
  std::vector<FixedVertex> base = circle_boundary(mesh.V, mesh.topology.boundary_loops[0], Spacing::ArcLength);
  test::write_text(dir / "base.txt", boundary_text(base));
  std::mt19937 rng(2);
  const std::vector<FixedVertex> m1 = random_move(base, 3, rng), m2 = random_move(base, 5, rng);
  test::write_text(dir / "m1.txt", boundary_text(m1));
  test::write_text(dir / "m2.txt", boundary_text(m2));
  for (const char* basis : {"full", "lazy"}) {
    const auto r = test::run_cli("edit " + (dir / "in.obj") + " --boundary " + (dir / "base.txt") + " -o " +
                                     (dir / "out.obj") + " --move " + (dir / "m1.txt") + " --move " +
                                     (dir / "m2.txt") + " --method authalic --basis " + basis + " --report " +
                                     (dir / "r.json"),
                                 dir);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("update"), std::string::npos) << r.out;
    const nlohmann::json report = nlohmann::json::parse(test::slurp(dir / "r.json"));
    ASSERT_EQ(report["updates"].size(), 2u);
    EXPECT_EQ(report["updates"][0]["moved"], 3);
    EXPECT_EQ(report["updates"][1]["moved"], 5 + 3 - 0) << "move 2 also puts move 1's vertices back";
    EXPECT_TRUE(report["timings_ms"].contains("precompute"));
    EXPECT_TRUE(report["updates"][0].contains("update_ms"));
    EXPECT_EQ(report["factorizations"], 1);
    int k = 0;
    for (const std::vector<FixedVertex>* m : {&m1, &m2}) {
      std::vector<FixedVertex> moved = base;
      for (FixedVertex& fv : moved)
        for (const FixedVertex& q : *m)
          if (q.vertex == fv.vertex) fv.uv = q.uv;
      const std::string name = "b" + std::to_string(++k) + ".txt";
      test::write_text(dir / name, boundary_text(moved));
      const auto p = test::run_cli("param " + (dir / "in.obj") + " --method authalic --boundary " + (dir / name) +
                                       " -q -o " + (dir / "fresh.obj"),
                                   dir);
      ASSERT_EQ(p.code, 0) << p.err;
      const MeshData edited = read_mesh(dir / ("out_" + std::to_string(k) + ".obj"));
      const MeshData fresh = read_mesh(dir / "fresh.obj");
      ASSERT_TRUE(edited.has_uv() && fresh.has_uv());
      EXPECT_LT((edited.TC - fresh.TC).cwiseAbs().maxCoeff(), 1e-10) << basis << " move " << k;
    }
  }
  // A move of a vertex outside the base boundary is refused, leaving nothing.
  int interior = 0;
  while (mesh.topology.is_boundary[interior]) ++interior;
  test::write_text(dir / "bad.txt", std::to_string(interior) + " 0.5 0.5\n");
  const auto bad = test::run_cli("edit " + (dir / "in.obj") + " --boundary " + (dir / "base.txt") + " -o " +
                                     (dir / "x.obj") + " --move " + (dir / "bad.txt"),
                                 dir);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("is not in the base boundary"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.obj"));
}

}  // namespace
}  // namespace intrinsic
