// Point and line constraints (docs/maths.md §5): met exactly, neutral when
// placed at the free map's own values, lines constrained at their edge
// crossings, and bad inputs refused with messages that say what and where.
#include <gtest/gtest.h>

#include <random>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "intrinsic/constraints.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "intrinsic/parameterizer.h"
#include "test_support.h"

namespace intrinsic {
namespace {

using test::kMethods;
using test::MethodCase;
using test::options_for;
using test::some_points;
using test::value_at;
using test::wavy;

template <class F>
void expect_input_error(F&& f, const std::string& fragment) {
  test::expect_error(std::forward<F>(f), ErrorKind::Input, fragment);
}

TEST(Constraints, MetInEveryMethod) {
  const Mesh mesh = wavy();
  for (const MethodCase& mc : kMethods) {
    Parameterizer p(mesh, options_for(mc));
    const MatrixX2d free_uv = p.solve().UV;
    Constraints c;
    int k = 0;
    for (const SurfacePoint& sp : some_points(mesh)) {
      const Eigen::Vector2d shift(0.03 * (k % 2 ? 1 : -1), 0.02 * (k - 1));
      c.points.push_back({sp, value_at(free_uv, mesh, sp) + shift, ""});
      ++k;
    }
    p.set_constraints(c);
    const ParamResult r = p.solve();
    ASSERT_EQ(r.constraints.size(), c.points.size());
    for (size_t i = 0; i < c.points.size(); ++i) {
      EXPECT_LT((value_at(r.UV, mesh, c.points[i].point) - c.points[i].uv).norm(), 1e-10) << method_name(mc.m) << i;
      EXPECT_LT(r.constraints[i].residual, 1e-10);
    }
    EXPECT_GT((r.UV - free_uv).cwiseAbs().maxCoeff(), 1e-3) << "the constraints must move the map";
    EXPECT_LT(r.residual, 1e-10);
    EXPECT_EQ(p.factorizations(), 1) << "constraints must not refactor the sparse system";
  }
}

TEST(Constraints, NoneEqualsParameterizeAndOwnValuesChangeNothing) {
  const Mesh mesh = wavy();
  for (const MethodCase& mc : kMethods)
    for (BoundaryShape shape : {BoundaryShape::Circle, BoundaryShape::Square}) {
      ParamOptions o = options_for(mc);
      o.boundary = shape;
      const MatrixX2d plain = parameterize(mesh, o).UV;
      Parameterizer p(mesh, o);
      Constraints c;
      for (const SurfacePoint& sp : some_points(mesh)) c.points.push_back({sp, value_at(plain, mesh, sp), ""});
      p.set_constraints(c);
      EXPECT_LT((p.solve().UV - plain).cwiseAbs().maxCoeff(), 1e-10) << method_name(mc.m);
      p.clear_constraints();
      EXPECT_LT((p.solve().UV - plain).cwiseAbs().maxCoeff(), 1e-12) << method_name(mc.m);
    }
}

TEST(Constraints, TargetsAreInOutputCoordinatesForEveryScale) {
  const Mesh mesh = wavy();
  for (ScaleMode scale : {ScaleMode::Unit, ScaleMode::Surface}) {
    ParamOptions o;
    o.scale = scale;
    Parameterizer p(mesh, o);
    const SurfacePoint sp = SurfacePoint::in_face(10, Eigen::Vector3d(1.0 / 3, 1.0 / 3, 1.0 / 3));
    const Eigen::Vector2d target = value_at(p.solve().UV, mesh, sp) + Eigen::Vector2d(0.01, 0);
    p.set_constraints(Constraints{{{sp, target, ""}}, {}});
    const ParamResult r = p.solve();
    EXPECT_LT((value_at(r.UV, mesh, sp) - target).norm(), 1e-10);
  }
}

TEST(Constraints, NewTargetsReuseEverything) {
  const Mesh mesh = wavy();
  Parameterizer p(mesh, options_for(kMethods[1]));
  Constraints c;
  for (const SurfacePoint& sp : some_points(mesh)) c.points.push_back({sp, Eigen::Vector2d(0.5, 0.5), ""});
  c.points.resize(1);
  p.set_constraints(c);
  const int setups = p.constraint_setups();
  for (double x : {0.4, 0.45, 0.55}) {
    p.set_constraint_targets({Eigen::Vector2d(x, 0.5)});
    const ParamResult r = p.solve();
    EXPECT_LT((value_at(r.UV, mesh, c.points[0].point) - Eigen::Vector2d(x, 0.5)).norm(), 1e-10);
  }
  EXPECT_EQ(p.constraint_setups(), setups);
  EXPECT_EQ(p.factorizations(), 1);
}

// A line between two far-apart faces: every row (end points and crossings)
// lands on the target segment, in order, and on a flat mesh the crossings lie
// on the straight 3D segment.
TEST(Constraints, LineCrossingsLandOnTheSegment) {
  GenerateOptions g;
  g.rings = 10;
  g.jitter = 0.5;
  const Mesh flat = make_mesh(generate_flat_disk(g));
  const Mesh curved = wavy();
  for (const Mesh* mesh : {&flat, &curved}) {
    // Faces nearest two points across the disk.
    auto nearest_face = [&](const Eigen::Vector2d& q) {
      int best = 0;
      double d = INFINITY;
      for (int f = 0; f < mesh->F.rows(); ++f) {
        Eigen::Vector2d c = Eigen::Vector2d::Zero();
        for (int k = 0; k < 3; ++k) c += mesh->V.row(mesh->F(f, k)).head<2>().transpose() / 3;
        if ((c - q).norm() < d) { d = (c - q).norm(); best = f; }
      }
      return best;
    };
    const Eigen::Vector3d third(1.0 / 3, 1.0 / 3, 1.0 / 3);
    LineConstraint line;
    line.path = {SurfacePoint::in_face(nearest_face({-0.6, -0.3}), third),
                 SurfacePoint::in_face(nearest_face({0.6, 0.4}), third)};
    const Eigen::Vector2d a(0.3, 0.35), b(0.7, 0.6);
    line.to = {a, b};
    for (const MethodCase& mc : kMethods) {
      Parameterizer p(*mesh, options_for(mc));
      p.set_constraints(Constraints{{}, {line}});
      const std::vector<LinearConstraint>& rows = p.constraints();
      ASSERT_GT(rows.size(), 6u) << "the line must cross several edges";
      const ParamResult r = p.solve();
      const Eigen::Vector2d dir = (b - a).normalized();
      double last = -1;
      for (const LinearConstraint& row : rows) {
        Eigen::Vector2d x = Eigen::Vector2d::Zero();
        for (auto [v, w] : row.terms) x += w * r.UV.row(v).transpose();
        const Eigen::Vector2d rel = x - a;
        EXPECT_LT(std::abs(rel.x() * dir.y() - rel.y() * dir.x()), 1e-10) << row.label;  // on the line
        EXPECT_LT((x - row.target).norm(), 1e-10) << row.label;
        const double s = rel.dot(dir);
        EXPECT_GE(s, last - 1e-12) << row.label;
        EXPECT_LE(s, (b - a).norm() + 1e-12);
        last = s;
      }
    }
    if (mesh == &flat) {
      Parameterizer p(*mesh, ParamOptions{});
      p.set_constraints(Constraints{{}, {line}});
      const std::vector<LinearConstraint>& rows = p.constraints();
      const Eigen::Vector3d p0 = rows.front().position, p1 = rows.back().position;
      for (const LinearConstraint& row : rows)
        EXPECT_LT((row.position - p0).cross(p1 - p0).norm() / (p1 - p0).norm(), 1e-12) << row.label;
    }
  }
}

TEST(Constraints, FixedBoundaryVertexMustAgree) {
  const Mesh mesh = wavy();
  Parameterizer p(mesh, ParamOptions{});
  const FixedVertex b = p.boundary()[0];
  p.set_constraints(Constraints{{{SurfacePoint::at_vertex(b.vertex), b.uv, ""}}, {}});
  EXPECT_LT(p.solve().constraints[0].residual, 1e-12);
  expect_input_error([&] { p.set_constraints(Constraints{{{SurfacePoint::at_vertex(b.vertex), b.uv + Eigen::Vector2d(0.1, 0), ""}}, {}}); },
                     "lies on fixed boundary vertices only (" + std::to_string(b.vertex) + ")");
  // The failed call leaves no constraint behind.
  EXPECT_TRUE(p.constraints().empty());
}

TEST(Constraints, BadInputsAreRefused) {
  const Mesh mesh = wavy();
  Parameterizer p(mesh, ParamOptions{});
  auto set = [&](const std::string& json) { p.set_constraints(parse_constraints_json(json, "c.json")); };
  expect_input_error([&] { set(R"({"points": [{"vertex": 1, "uv": [0, 0]},)"); }, "c.json: malformed JSON");
  expect_input_error([&] { set("{\"points\": [\n  {\"vertex\" 1}]}"); }, "line 2");
  expect_input_error([&] {
    set(R"({"points": [{"vertex": 1, "uv": [0, 0]}, {"vertex": 2, "uv": [0, 0]}, {"vertex": 3, "uvw": [0, 0]}]})");
  }, "c.json: points[2]: unknown key 'uvw'");
  expect_input_error([&] { set(R"({"point": []})"); }, "c.json: top level: unknown key 'point'");
  expect_input_error([&] { set(R"({"lines": [{"path": [{"vertex": 1, "uv": [0, 0]}], "to": []}]})"); },
                     "lines[0].path[0]: unknown key 'uv'");
  expect_input_error([&] { set(R"({"points": [{"face": 999999, "bary": [0.2, 0.3, 0.5], "uv": [0, 0]}]})"); },
                     "points[0]: face 999999 is out of range");
  expect_input_error([&] { set(R"({"points": [{"vertex": 999999, "uv": [0, 0]}]})"); },
                     "points[0]: vertex 999999 is out of range");
  expect_input_error([&] { set(R"({"points": [{"face": 3, "bary": [0.2, 0.3, 0.6], "uv": [0, 0]}]})"); },
                     "points[0]: barycentric coordinates sum to 1.1");
  expect_input_error([&] { set(R"({"points": [{"face": 3, "bary": [-0.2, 0.6, 0.6], "uv": [0, 0]}]})"); },
                     "points[0]: negative barycentric coordinate");
  expect_input_error([&] { set(R"({"points": [{"face": 3, "bary": [0.2, 0.3], "uv": [0, 0]}]})"); },
                     "points[0].bary: expected [b1, b2, b3]");
  expect_input_error([&] { set(R"({"points": [{"vertex": 7, "uv": [0, "a"]}]})"); }, "points[0].uv[1]: expected a number");
  expect_input_error([&] { set(R"({"points": [{"vertex": 7, "uv": [0, 1e999]}]})"); }, "malformed JSON: [json.exception.out_of_range.406] number overflow");
  expect_input_error([&] {
    set(R"({"points": [{"vertex": 20, "uv": [0.5, 0.5]}, {"vertex": 20, "uv": [0.5, 0.6]}]})");
  }, "points[1] and points[0] constrain the same point to different positions");
  // The same point given as a face corner and as a vertex, with different targets.
  const int v = mesh.F(40, 1);
  expect_input_error([&] {
    set(R"({"points": [{"face": 40, "bary": [0, 1, 0], "uv": [0.5, 0.5]}, {"vertex": )" + std::to_string(v) +
        R"(, "uv": [0.4, 0.5]}]})");
  }, "constrain the same point to different positions");
  // Three points on one interior edge: only two independent rows.
  int h = 0;
  while (mesh.topology.twin[h] < 0 || mesh.topology.is_boundary[mesh.source(h)] ||
         mesh.topology.is_boundary[mesh.target(h)])
    ++h;
  const int f = Topology::face_of(h), c0 = h % 3, c1 = (h % 3 + 1) % 3;
  Constraints dependent;
  for (double t : {0.2, 0.5, 0.8}) {
    Eigen::Vector3d bary = Eigen::Vector3d::Zero();
    bary[c0] = 1 - t;
    bary[c1] = t;
    dependent.points.push_back({SurfacePoint::in_face(f, bary), Eigen::Vector2d(0.4 + 0.1 * t, 0.5), ""});
  }
  expect_input_error([&] { p.set_constraints(dependent); }, "linearly dependent");
  // Duplicates with equal targets are merged, not refused.
  set(R"({"points": [{"vertex": 20, "uv": [0.5, 0.5]}, {"vertex": 20, "uv": [0.5, 0.5]}]})");
  EXPECT_EQ(p.constraints().size(), 1u);
}

// Found while writing fuzz_constraints: the walk looked up the faces around a
// path's next point before checking it, so a line to an out-of-range vertex
// read past the end of an array (a crash) instead of being refused.
TEST(Constraints, LinePointsAreCheckedBeforeTheWalk) {
  const Mesh mesh = wavy();
  const int nv = static_cast<int>(mesh.V.rows()), nf = static_cast<int>(mesh.F.rows());
  int interior = 0;
  while (mesh.topology.is_boundary[interior]) ++interior;
  const auto line_to = [&](const SurfacePoint& end) {
    LineConstraint l;
    l.path = {SurfacePoint::at_vertex(interior), end};
    l.to = {Eigen::Vector2d(0.2, 0.3), Eigen::Vector2d(0.8, 0.3)};
    return Constraints{{}, {l}};
  };
  for (int v : {nv, 999999})
    expect_input_error([&] { resolve_constraints(mesh, line_to(SurfacePoint::at_vertex(v))); },
                       "lines[0].path[1]: vertex " + std::to_string(v) + " is out of range");
  expect_input_error([&] { resolve_constraints(mesh, line_to(SurfacePoint::in_face(nf, Eigen::Vector3d(1, 0, 0)))); },
                     "lines[0].path[1]: face " + std::to_string(nf) + " is out of range");
  expect_input_error([&] { resolve_constraints(mesh, line_to(SurfacePoint{})); }, "lines[0].path[1]: no vertex or face");
  // The same through the file parser, as `param --constraints` reads it.
  const std::string text = R"({"lines": [{"path": [{"vertex": )" + std::to_string(interior) +
                           R"(}, {"vertex": 999999}], "to": [[0, 0], [1, 1]]}]})";
  expect_input_error([&] { resolve_constraints(mesh, parse_constraints_json(text, "c.json")); },
                     "lines[0].path[1]: vertex 999999 is out of range");
}

TEST(Constraints, FaceCornersFollowReorientation) {
  const Mesh mesh = wavy(4);
  MatrixX3i file_faces = mesh.F;
  file_faces.row(5) = Eigen::RowVector3i(mesh.F(5, 0), mesh.F(5, 2), mesh.F(5, 1));  // as if the file had it flipped
  Constraints c{{{SurfacePoint::in_face(5, Eigen::Vector3d(0.1, 0.2, 0.7)), Eigen::Vector2d(0.5, 0.5), ""}}, {}};
  match_face_corners(c, file_faces, mesh);
  EXPECT_EQ(c.points[0].point.bary, Eigen::Vector3d(0.1, 0.7, 0.2));
}

TEST(Constraints, CliReportsResidualsAndRefusesBadFiles) {
  test::TempDir dir;
  GenerateOptions g;
  g.rings = 10;
  const MeshData data = generate_wavy_patch(g);
  write_mesh(dir / "in.obj", data.V, data.F, MatrixX2d());
  test::write_text(dir / "c.json", R"({"points": [{"face": 30, "bary": [0.2, 0.3, 0.5], "uv": [0.42, 0.47]},
      {"vertex": 5, "uv": [0.55, 0.5]}],
    "lines": [{"path": [{"face": 100, "bary": [0.3, 0.3, 0.4]}, {"face": 250, "bary": [0.3, 0.3, 0.4]}],
               "to": [[0.3, 0.3], [0.6, 0.7]]}]})");
  for (const char* scale : {"unit", "surface"}) {
    const auto r = test::run_cli("param " + (dir / "in.obj") + " -q -o " + (dir / "out.obj") + " --constraints " +
                                     (dir / "c.json") + " --scale " + scale + " --report " + (dir / "r.json"),
                                 dir);
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json report = nlohmann::json::parse(test::slurp(dir / "r.json"));
    ASSERT_TRUE(report.contains("constraints"));
    ASSERT_GT(report["constraints"].size(), 4u);
    EXPECT_EQ(report["constraints"][0]["label"], "points[0]");
    for (const auto& c : report["constraints"]) EXPECT_LT(c["residual"].get<double>(), 1e-10) << c.dump();
    // The written UVs meet the targets: constraint targets are output coordinates.
    const MeshData out = read_mesh(dir / "out.obj");
    const Eigen::Vector2d x = 0.2 * out.TC.row(out.FTC(30, 0)) + 0.3 * out.TC.row(out.FTC(30, 1)) +
                              0.5 * out.TC.row(out.FTC(30, 2));
    EXPECT_LT((x - Eigen::Vector2d(0.42, 0.47)).norm(), 1e-10) << scale;
  }
  test::write_text(dir / "bad.json", R"({"points": [{"vertex": 5, "uv": [0.5, 0.5], "weight": 2}]})");
  const auto bad = test::run_cli("param " + (dir / "in.obj") + " -o " + (dir / "x.obj") + " --constraints " +
                                     (dir / "bad.json"),
                                 dir);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("bad.json: points[0]: unknown key 'weight'"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.obj"));
}

}  // namespace
}  // namespace intrinsic
