// Point and line constraints on the natural conformal map (paper sections
// 4.1 and 4.2; docs/maths.md §3 and §5): the natural boundary with default or
// given pins, and natural holes behind a fixed outer loop. Each constraint is
// a u row and a v row of the 2n x 2n system, eliminated with the kept
// factorization as in the fixed-boundary case.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "intrinsic/boundary_editor.h"
#include "intrinsic/constraints.h"
#include "intrinsic/error.h"
#include "intrinsic/generate.h"
#include "intrinsic/io.h"
#include "intrinsic/parameterizer.h"
#include "test_support.h"

namespace intrinsic {
namespace {

using test::expect_error;
using test::some_points;
using test::value_at;
using test::wavy;


struct Case {
  std::string name;
  const Mesh* mesh;
  ParamOptions o;
};

// Natural boundary with default pins (unit and surface scale) and given pins;
// natural holes behind a circle (conformal and mixed).
std::vector<Case> natural_cases(const Mesh& disk, const Mesh& holed) {
  std::vector<Case> cases;
  ParamOptions o;
  o.boundary = BoundaryShape::Natural;
  o.scale = ScaleMode::Unit;
  cases.push_back({"natural default pins unit", &disk, o});
  o.scale = ScaleMode::Surface;
  cases.push_back({"natural default pins surface", &disk, o});
  o.pins = {{0, Eigen::Vector2d(0.1, 0.2)}, {7, Eigen::Vector2d(0.9, 0.3)}};
  cases.push_back({"natural given pins", &disk, o});
  ParamOptions h;
  h.boundary = BoundaryShape::Circle;
  h.holes = HoleRule::Natural;
  cases.push_back({"natural holes unit", &holed, h});
  h.scale = ScaleMode::Surface;
  h.weights.method = Method::Mixed;
  h.weights.lambda = 0.6;
  h.weights.mu = 0.4;
  cases.push_back({"natural holes mixed surface", &holed, h});
  return cases;
}

double tol(const MatrixX2d& UV) { return 1e-10 * std::max(1.0, UV.cwiseAbs().maxCoeff()); }

// The holed cases run on a generated holed patch, and on fairing-cross.off
// (4 boundary loops) in the *Corpus tests.
const Mesh& holed_mesh() {
  static const Mesh mesh = make_mesh(test::holed_wavy(3));
  return mesh;
}

void expect_met_to_tolerance(const Mesh& holed) {
  const Mesh disk = wavy();
  for (const Case& c : natural_cases(disk, holed)) {
    SCOPED_TRACE(c.name);
    const Mesh& mesh = *c.mesh;
    Parameterizer p(mesh, c.o);
    const MatrixX2d free_uv = p.solve().UV;
    const double size = test::diameter(free_uv);
    Constraints cs;
    int k = 0;
    for (const SurfacePoint& sp : some_points(mesh)) {
      const Eigen::Vector2d shift = 0.03 * size * Eigen::Vector2d(k % 2 ? 1 : -1, 0.5 * (k - 1));
      cs.points.push_back({sp, value_at(free_uv, mesh, sp) + shift, ""});
      ++k;
    }
    // On the disk, a line between two face points, straightened onto a segment.
    if (mesh.topology.boundary_loops.size() == 1) {
      LineConstraint line;
      line.path = {SurfacePoint::in_face(static_cast<int>(mesh.F.rows()) / 4, Eigen::Vector3d(0.3, 0.3, 0.4)),
                   SurfacePoint::in_face(static_cast<int>(mesh.F.rows()) / 4 + 12, Eigen::Vector3d(0.3, 0.3, 0.4))};
      line.to = {value_at(free_uv, mesh, line.path[0]), value_at(free_uv, mesh, line.path[1])};
      cs.lines.push_back(line);
    }
    p.set_constraints(cs);
    const ParamResult r = p.solve();
    ASSERT_GE(r.constraints.size(), cs.points.size() + 2 * cs.lines.size());
    for (size_t i = 0; i < cs.points.size(); ++i)
      EXPECT_LT((value_at(r.UV, mesh, cs.points[i].point) - cs.points[i].uv).norm(), tol(r.UV)) << i;
    for (const ConstraintResidual& cr : r.constraints) EXPECT_LT(cr.residual, tol(r.UV)) << cr.label;
    EXPECT_GT((r.UV - free_uv).cwiseAbs().maxCoeff(), 1e-3 * size) << "the constraints must move the map";
    EXPECT_LT(r.residual, 1e-8);
    EXPECT_EQ(p.factorizations(), 1) << "constraints must not refactor the sparse system";
    EXPECT_EQ(r.holes, mesh.topology.boundary_loops.size() > 1 ? HolesApplied::Natural : HolesApplied::None);
    // New targets: a new right-hand side only.
    std::vector<Eigen::Vector2d> targets;
    for (const LinearConstraint& row : p.constraints()) targets.push_back(row.target + Eigen::Vector2d(0.01, 0) * size);
    p.set_constraint_targets(targets);
    const ParamResult r2 = p.solve();
    for (const ConstraintResidual& cr : r2.constraints) EXPECT_LT(cr.residual, tol(r2.UV)) << cr.label;
    EXPECT_EQ(p.factorizations(), 1);
  }
}

TEST(NaturalConstraints, MetToTolerance) { expect_met_to_tolerance(holed_mesh()); }

TEST(NaturalConstraintsCorpus, MetToTolerance) {
  REQUIRE_SHARED_MESHES();
  expect_met_to_tolerance(make_mesh(read_mesh(test::shared_mesh("fairing-cross.off"))));
}

void expect_none_equals_natural_map(const Mesh& holed) {
  const Mesh disk = wavy();
  for (const Case& c : natural_cases(disk, holed)) {
    SCOPED_TRACE(c.name);
    const Mesh& mesh = *c.mesh;
    const ParamResult plain = parameterize(mesh, c.o);
    Parameterizer p(mesh, c.o);
    const ParamResult none = p.solve();
    EXPECT_LT((none.UV - plain.UV).cwiseAbs().maxCoeff(), tol(plain.UV));
    EXPECT_EQ(none.placement, plain.placement);
    EXPECT_EQ(none.holes, plain.holes);
    EXPECT_EQ(none.free_vertices, plain.free_vertices);
    EXPECT_EQ(none.fixed_vertices, plain.fixed_vertices);
    ASSERT_EQ(none.pins.size(), plain.pins.size());
    for (size_t k = 0; k < plain.pins.size(); ++k) {
      EXPECT_EQ(none.pins[k].vertex, plain.pins[k].vertex);
      EXPECT_EQ(none.pins[k].uv, plain.pins[k].uv);
    }
    Constraints cs;
    for (const SurfacePoint& sp : some_points(mesh)) cs.points.push_back({sp, value_at(plain.UV, mesh, sp), ""});
    p.set_constraints(cs);
    EXPECT_LT((p.solve().UV - plain.UV).cwiseAbs().maxCoeff(), tol(plain.UV));
    p.clear_constraints();
    EXPECT_LT((p.solve().UV - plain.UV).cwiseAbs().maxCoeff(), tol(plain.UV));
  }
}

TEST(NaturalConstraints, NoneEqualsNaturalMapAndOwnValuesChangeNothing) {
  expect_none_equals_natural_map(holed_mesh());
}

TEST(NaturalConstraintsCorpus, NoneEqualsNaturalMapAndOwnValuesChangeNothing) {
  REQUIRE_SHARED_MESHES();
  expect_none_equals_natural_map(make_mesh(read_mesh(test::shared_mesh("fairing-cross.off"))));
}

TEST(NaturalConstraints, ContradictingPinsAreRefused) {
  const Mesh mesh = wavy();
  ParamOptions o;
  o.boundary = BoundaryShape::Natural;
  o.pins = {{0, Eigen::Vector2d(0, 0)}, {7, Eigen::Vector2d(1, 0)}};
  Parameterizer p(mesh, o);
  // Agreeing with a pin is fine; contradicting it is refused (and leaves no
  // constraints, as for fixed boundaries).
  const Constraints agree{{{SurfacePoint::at_vertex(7), Eigen::Vector2d(1, 0), ""}}, {}};
  p.set_constraints(agree);
  EXPECT_LT(p.solve().constraints[0].residual, 1e-12);
  expect_error([&] { p.set_constraints(Constraints{{{SurfacePoint::at_vertex(0), Eigen::Vector2d(0.5, 0.5), ""}}, {}}); },
               ErrorKind::Input, "points[0] lies on pinned vertices only (0) and asks for (0.5");
  EXPECT_TRUE(p.constraints().empty());
  p.set_constraints(agree);
  expect_error([&] { p.set_constraint_targets({Eigen::Vector2d(2, 0)}); }, ErrorKind::Input, "pinned vertices only");
  // The same surface point twice with different targets.
  const SurfacePoint sp = SurfacePoint::in_face(40, Eigen::Vector3d(0.2, 0.3, 0.5));
  expect_error([&] { p.set_constraints(Constraints{{{sp, Eigen::Vector2d(0.3, 0.3), ""}, {sp, Eigen::Vector2d(0.4, 0.3), ""}}, {}}); },
               ErrorKind::Input, "points[1]");
  // The natural boundary still needs the conformal method.
  o.weights.method = Method::Authalic;
  expect_error([&] { Parameterizer q(mesh, o); }, ErrorKind::Usage, "conformal method");
}

TEST(NaturalConstraints, NewPinsReuseTheFactorization) {
  const Mesh mesh = wavy();
  ParamOptions o;
  o.boundary = BoundaryShape::Natural;
  o.pins = {{0, Eigen::Vector2d(0, 0)}, {7, Eigen::Vector2d(1, 0)}};
  Parameterizer p(mesh, o);
  const SurfacePoint sp = SurfacePoint::in_face(60, Eigen::Vector3d(0.2, 0.3, 0.5));
  p.set_constraints(Constraints{{{sp, Eigen::Vector2d(0.4, 0.2), ""}}, {}});
  const std::vector<FixedVertex> moved = {{0, Eigen::Vector2d(0, 0.1)}, {7, Eigen::Vector2d(1.2, 0)}};
  const ParamResult r = p.solve_with_boundary(moved);
  EXPECT_EQ(p.factorizations(), 1);
  EXPECT_LT(r.constraints[0].residual, 1e-10);
  ParamOptions fresh = o;
  fresh.pins = moved;
  Parameterizer q(mesh, fresh);
  q.set_constraints(Constraints{{{sp, Eigen::Vector2d(0.4, 0.2), ""}}, {}});
  EXPECT_LT((q.solve().UV - r.UV).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(NaturalConstraints, CliReportsResiduals) {
  test::TempDir dir;
  GenerateOptions g;
  g.rings = 10;
  const MeshData data = generate_wavy_patch(g);
  const Mesh mesh = make_mesh(data);
  write_mesh(dir / "in.obj", data.V, data.F, MatrixX2d());
  int interior = -1;
  for (int v = 20; v < mesh.V.rows() && interior < 0; ++v)
    if (!mesh.topology.is_boundary[v]) interior = v;
  test::write_text(dir / "c.json", R"({"points": [{"face": 30, "bary": [0.2, 0.3, 0.5], "uv": [0.42, 0.47]},
      {"vertex": )" + std::to_string(interior) + R"(, "uv": [0.55, 0.5]}],
    "lines": [{"path": [{"face": 100, "bary": [0.3, 0.3, 0.4]}, {"face": 250, "bary": [0.3, 0.3, 0.4]}],
               "to": [[0.3, 0.3], [0.6, 0.7]]}]})");
  for (const std::string extra : {"", "--scale surface", "--pin 0:0,0 --pin 7:1,0"}) {
    SCOPED_TRACE(extra);
    const auto r = test::run_cli("param " + (dir / "in.obj") + " -q -o " + (dir / "out.obj") +
                                     " --boundary natural --constraints " + (dir / "c.json") + " " + extra +
                                     " --report " + (dir / "r.json"),
                                 dir);
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json report = nlohmann::json::parse(test::slurp(dir / "r.json"));
    ASSERT_TRUE(report.contains("constraints"));
    ASSERT_GT(report["constraints"].size(), 4u);
    EXPECT_EQ(report["constraints"][0]["label"], "points[0]");
    for (const auto& c : report["constraints"]) EXPECT_LT(c["residual"].get<double>(), 1e-10) << c.dump();
    EXPECT_EQ(report["boundary"], "natural");
    EXPECT_TRUE(report.contains("pins"));
    const MeshData out = read_mesh(dir / "out.obj");
    const Eigen::Vector2d x = 0.2 * out.TC.row(out.FTC(30, 0)) + 0.3 * out.TC.row(out.FTC(30, 1)) +
                              0.5 * out.TC.row(out.FTC(30, 2));
    EXPECT_LT((x - Eigen::Vector2d(0.42, 0.47)).norm(), 1e-10);
  }
  // A constraint against a pin: a clear input error, no output.
  test::write_text(dir / "bad.json", R"({"points": [{"vertex": 0, "uv": [0.5, 0.5]}]})");
  const auto bad = test::run_cli("param " + (dir / "in.obj") + " -o " + (dir / "x.obj") +
                                     " --boundary natural --pin 0:0,0 --pin 7:1,0 --constraints " + (dir / "bad.json"),
                                 dir);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("lies on pinned vertices only"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.obj"));
}

// `intrinsic param IN --holes natural` with a point constraint on face 500.
void expect_cli_natural_holes(const std::string& in, const test::TempDir& dir) {
  const Mesh mesh = make_mesh(read_mesh(in));
  const auto plain = test::run_cli("param " + in + " -q -o " + (dir / "plain.obj") + " --holes natural", dir);
  ASSERT_EQ(plain.code, 0) << plain.err;
  const MeshData p = read_mesh(dir / "plain.obj");
  // Constrain face 500 to where the plain map puts it, shifted a little.
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  for (int c = 0; c < 3; ++c) x += (1.0 / 3) * p.TC.row(p.FTC(500, c)).transpose();
  x += Eigen::Vector2d(0.01, -0.01);
  test::write_text(dir / "c.json", R"({"points": [{"face": 500, "bary": [0.33333333333333333, 0.33333333333333333, 0.33333333333333334], "uv": [)" +
                                       std::to_string(x.x()) + ", " + std::to_string(x.y()) + "]}]}");
  const auto r = test::run_cli("param " + in + " -q -o " + (dir / "out.obj") + " --holes natural --constraints " +
                                   (dir / "c.json") + " --report " + (dir / "r.json"),
                               dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(test::slurp(dir / "r.json"));
  EXPECT_EQ(report["holes"], "natural");
  ASSERT_EQ(report["constraints"].size(), 1u);
  EXPECT_LT(report["constraints"][0]["residual"].get<double>(), 1e-10);
  EXPECT_GT(mesh.topology.boundary_loops.size(), 1u);
}

TEST(NaturalConstraints, CliNaturalHoles) {
  test::TempDir dir;
  const MeshData holed = test::holed_wavy(3);
  write_mesh(dir / "holed.obj", holed.V, holed.F, MatrixX2d());
  expect_cli_natural_holes(dir / "holed.obj", dir);
}

TEST(NaturalConstraintsCorpus, CliNaturalHoles) {
  REQUIRE_SHARED_MESHES();
  test::TempDir dir;
  expect_cli_natural_holes(test::shared_mesh("fairing-cross.off"), dir);
}

}  // namespace
}  // namespace intrinsic
