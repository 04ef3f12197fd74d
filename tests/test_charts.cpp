// Several components as charts: each parameterized on its own, laid out
// without overlap at a common scale, per-chart figures reported.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "intrinsic/charts.h"
#include "intrinsic/io.h"
#include "intrinsic/error.h"
#include "intrinsic/metrics.h"
#include "test_support.h"

namespace intrinsic {
namespace {

bool disjoint(const ChartSummary& a, const ChartSummary& b) {
  return a.box_max.x() < b.box_min.x() || b.box_max.x() < a.box_min.x() || a.box_max.y() < b.box_min.y() ||
         b.box_max.y() < a.box_min.y();
}

// The bounding box of a chart's vertices, recomputed from the UVs.
void check_boxes(const Mesh& mesh, const ParamResult& r) {
  for (const ChartSummary& c : r.charts) {
    Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
    for (int f = 0; f < mesh.F.rows(); ++f)
      if (mesh.topology.face_component[f] == c.component)
        for (int k = 0; k < 3; ++k) {
          lo = lo.cwiseMin(r.UV.row(mesh.F(f, k)).transpose());
          hi = hi.cwiseMax(r.UV.row(mesh.F(f, k)).transpose());
        }
    EXPECT_EQ(lo, c.box_min);
    EXPECT_EQ(hi, c.box_max);
  }
}

TEST(Charts, TwoDisksGiveTwoDisjointChartsWithoutFlips) {
  const Mesh mesh = test::two_disks();
  ASSERT_EQ(mesh.topology.num_components, 2);
  for (BoundaryShape s : {BoundaryShape::Circle, BoundaryShape::Square, BoundaryShape::Natural}) {
    ParamOptions o;
    o.boundary = s;
    const ParamResult r = parameterize_charts(mesh, o);
    ASSERT_EQ(r.charts.size(), 2u);
    check_boxes(mesh, r);
    EXPECT_TRUE(disjoint(r.charts[0], r.charts[1]));
    EXPECT_EQ(summarize_distortion(mesh.V, mesh.F, r.UV).flipped_triangles, 0);
    int faces = 0;
    for (const ChartSummary& c : r.charts) {
      EXPECT_EQ(c.flipped_triangles, 0);
      EXPECT_GE(c.angle_distortion_mean, 1.0);
      EXPECT_TRUE(c.packed);
      faces += c.faces;
    }
    EXPECT_EQ(faces, mesh.F.rows());
    EXPECT_EQ(r.placement, Placement::Unit);
    EXPECT_GE(r.UV.minCoeff(), -1e-12);
    EXPECT_LE(r.UV.maxCoeff(), 1 + 1e-12);
  }
}

TEST(Charts, CommonScaleAndNaturalChartsAreExactCopies) {
  // Two identical flat disks, natural map: each chart is its disk up to a
  // similarity, and both have the same size (one scale for all charts).
  const Mesh mesh = test::two_disks();
  ParamOptions o;
  o.boundary = BoundaryShape::Natural;
  o.scale = ScaleMode::Surface;
  const ParamResult r = parameterize_charts(mesh, o);
  EXPECT_EQ(r.placement, Placement::Surface);
  EXPECT_NEAR(parameter_area(mesh.F, r.UV), surface_area(mesh.V, mesh.F), 1e-9 * surface_area(mesh.V, mesh.F));
  for (const ChartSummary& c : r.charts) {
    EXPECT_EQ(c.boundary, BoundaryShape::Natural);
    EXPECT_NEAR(c.angle_distortion_mean, 1.0, 1e-9);  // a flat disk maps by a similarity
  }
}

TEST(Charts, PinnedChartStaysWhereThePinsPutIt) {
  const Mesh mesh = test::two_disks();
  const int a = mesh.F(0, 0), b = mesh.F(0, 1);  // in component 0
  ParamOptions o;
  o.boundary = BoundaryShape::Natural;
  o.pins = {{a, Eigen::Vector2d(5, 5)}, {b, Eigen::Vector2d(5, 6)}};
  const ParamResult r = parameterize_charts(mesh, o);
  EXPECT_EQ(r.UV.row(a), Eigen::RowVector2d(5, 5));
  EXPECT_EQ(r.UV.row(b), Eigen::RowVector2d(5, 6));
  EXPECT_FALSE(r.charts[mesh.topology.face_component[0]].packed);
  EXPECT_TRUE(disjoint(r.charts[0], r.charts[1]));
  EXPECT_EQ(r.placement, Placement::Given);
  // One pin in a chart is refused, naming the chart.
  o.pins.pop_back();
  o.pins.push_back({mesh.F(mesh.F.rows() - 1, 0), Eigen::Vector2d(0, 0)});
  test::expect_error([&] { parameterize_charts(mesh, o); }, ErrorKind::Usage, "has one pin");
}

TEST(Charts, ClosedComponentIsRefusedAndLargestIsFound) {
  // A disk plus a closed tetrahedron far away.
  GenerateOptions g;
  g.rings = 5;
  MeshData d = generate_flat_disk(g);
  const int n = static_cast<int>(d.V.rows()), m = static_cast<int>(d.F.rows());
  d.V.conservativeResize(n + 4, 3);
  d.V.bottomRows(4) << 10, 0, 0, 11, 0, 0, 10, 1, 0, 10, 0, 1;
  d.F.conservativeResize(m + 4, 3);
  d.F.bottomRows(4) << n, n + 2, n + 1, n, n + 1, n + 3, n + 1, n + 2, n + 3, n, n + 3, n + 2;
  ValidateOptions vo;
  vo.allow_several_components = true;
  vo.allow_closed = true;
  const Mesh mesh = make_mesh(d, vo);
  ASSERT_EQ(mesh.topology.num_components, 2);
  test::expect_error([&] { parameterize_charts(mesh, ParamOptions{}); }, ErrorKind::Input, "closed");
  const int largest = largest_component(mesh);
  EXPECT_EQ(mesh.topology.component_faces[largest], m);
  const Mesh kept = make_mesh(component_data(mesh, largest));
  EXPECT_EQ(kept.topology.num_components, 1);
  EXPECT_EQ(kept.V.rows(), mesh.V.rows());  // numbering unchanged
  EXPECT_EQ(kept.F.rows(), m);
}

TEST(Charts, CliRunsChartsOrKeepsTheLargest) {
  test::TempDir dir;
  ASSERT_EQ(test::run_cli("generate two-disks --rings 6 -o " + (dir / "two.obj"), dir).code, 0);
  auto r = test::run_cli("param " + (dir / "two.obj") + " -o " + (dir / "out.obj") + " --report " + (dir / "r.json"), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("2 charts"), std::string::npos) << r.out;
  nlohmann::json report = nlohmann::json::parse(test::slurp(dir / "r.json"));
  ASSERT_EQ(report["charts"].size(), 2u);
  EXPECT_EQ(report["flipped_triangles"], 0);
  for (const auto& c : report["charts"]) {
    EXPECT_EQ(c["flipped_triangles"], 0);
    EXPECT_GT(c["faces"].get<int>(), 0);
    EXPECT_GE(c["angle_distortion_mean"].get<double>(), 1.0);
  }
  const auto& a = report["charts"][0]["uv_box"], &b = report["charts"][1]["uv_box"];
  EXPECT_TRUE(a["max"][0] < b["min"][0] || b["max"][0] < a["min"][0] || a["max"][1] < b["min"][1] ||
              b["max"][1] < a["min"][1]);
  r = test::run_cli("param " + (dir / "two.obj") + " -o " + (dir / "one.obj") + " --largest-component --report " +
                        (dir / "r1.json"),
                    dir);
  ASSERT_EQ(r.code, 0) << r.err;
  report = nlohmann::json::parse(test::slurp(dir / "r1.json"));
  EXPECT_EQ(report["components"], 1);
  EXPECT_FALSE(report.contains("charts"));
  const MeshData one = read_mesh(dir / "one.obj"), two = read_mesh(dir / "two.obj");
  EXPECT_EQ(one.V.rows(), two.V.rows());  // numbering unchanged
  EXPECT_LT(one.F.rows(), two.F.rows());
}

}  // namespace
}  // namespace intrinsic
