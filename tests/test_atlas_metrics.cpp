// Atlas measures of `metrics`: charts of per-corner UVs and
// triangle soups, mirrored charts apart from local folds, exact overlaps and
// utilization, against figures worked out here by other means (polygon
// clipping for overlap areas, hand counts), and `metrics`/`render` on a soup
// that make_mesh refuses.
#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include <nlohmann/json.hpp>

#include "atlas_test_support.h"
#include "cli_support.h"
#include "intrinsic/atlas.h"
#include "intrinsic/io.h"
#include "intrinsic/metrics.h"
#include "intrinsic/render.h"
#include "test_support.h"

namespace intrinsic {
namespace {

using Vec2 = Eigen::Vector2d;

// A chart: an n x n grid of unit squares in the plane z = 0 at `origin`,
// two triangles per square, UV = position * scale + offset.
struct Soup {
  MatrixX3d P;  // per texture coordinate
  MatrixX2d UV;
  MatrixX3i F;
};

void add_grid(Soup& s, int n, Eigen::Vector3d origin, double scale, Vec2 offset, bool mirror = false) {
  const int base = static_cast<int>(s.UV.rows()), nf = static_cast<int>(s.F.rows());
  s.P.conservativeResize(base + (n + 1) * (n + 1), 3);
  s.UV.conservativeResize(base + (n + 1) * (n + 1), 2);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const int v = base + j * (n + 1) + i;
      s.P.row(v) = origin + Eigen::Vector3d(i, j, 0);
      s.UV.row(v) = Vec2((mirror ? -i : i) * scale, j * scale) + offset;
    }
  s.F.conservativeResize(nf + 2 * n * n, 3);
  int f = nf;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = base + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      s.F.row(f++) << a, b, d;
      s.F.row(f++) << a, d, c;
    }
}

// Every face gets its own three texture coordinates (a soup, as many tools write).
Soup as_soup(const Soup& s) {
  Soup t;
  t.P.resize(3 * s.F.rows(), 3);
  t.UV.resize(3 * s.F.rows(), 2);
  t.F.resize(s.F.rows(), 3);
  for (int f = 0; f < s.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      t.P.row(3 * f + c) = s.P.row(s.F(f, c));
      t.UV.row(3 * f + c) = s.UV.row(s.F(f, c));
      t.F(f, c) = 3 * f + c;
    }
  return t;
}

// Area of the intersection of two triangles by Sutherland-Hodgman clipping
// (the overlap counter uses orientation signs only, never areas).
double intersection_area(std::array<Vec2, 3> a, std::array<Vec2, 3> b) {
  auto ccw = [](std::array<Vec2, 3>& t) {
    if ((t[1] - t[0]).x() * (t[2] - t[0]).y() - (t[1] - t[0]).y() * (t[2] - t[0]).x() < 0) std::swap(t[1], t[2]);
  };
  ccw(a), ccw(b);
  std::vector<Vec2> poly(a.begin(), a.end());
  for (int e = 0; e < 3 && !poly.empty(); ++e) {
    const Vec2 p = b[e], q = b[(e + 1) % 3];
    auto side = [&](const Vec2& x) { return (q - p).x() * (x - p).y() - (q - p).y() * (x - p).x(); };
    std::vector<Vec2> out;
    for (size_t i = 0; i < poly.size(); ++i) {
      const Vec2 u = poly[i], v = poly[(i + 1) % poly.size()];
      const double su = side(u), sv = side(v);
      if (su >= 0) out.push_back(u);
      if ((su >= 0) != (sv >= 0)) out.push_back(u + (v - u) * (su / (su - sv)));
    }
    poly = out;
  }
  double area = 0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec2 u = poly[i], v = poly[(i + 1) % poly.size()];
    area += 0.5 * (u.x() * v.y() - u.y() * v.x());
  }
  return area;
}

std::array<Vec2, 3> uv_triangle(const Soup& s, int f) {
  return {s.UV.row(s.F(f, 0)).transpose(), s.UV.row(s.F(f, 1)).transpose(), s.UV.row(s.F(f, 2)).transpose()};
}

TEST(AtlasMetrics, Orient2dIsExactOnNearlyCollinearPoints) {
  const Vec2 a(0.5, 0.5), b(12, 12);
  EXPECT_EQ(orient2d_sign(a, b, Vec2(24, 24)), 0);
  // det = 11.5 * ulp(24) > 0 exactly; the rounded formula cannot see it.
  EXPECT_EQ(orient2d_sign(a, b, Vec2(24, std::nextafter(24.0, 25.0))), 1);
  EXPECT_EQ(orient2d_sign(a, b, Vec2(24, std::nextafter(24.0, 23.0))), -1);
  EXPECT_EQ(orient2d_sign(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)), 1);
}

TEST(AtlasMetrics, TwoSquaresOverlappingByAKnownArea) {
  // Unit squares, the second shifted by (0.5, 0.25): they share 0.5 x 0.75.
  Soup s;
  add_grid(s, 1, {0, 0, 0}, 1, {0.0, 0.0});
  add_grid(s, 1, {5, 0, 0}, 1, {0.5, 0.25});
  double total = 0;
  std::vector<char> expected(4, 0);
  for (int f = 0; f < 2; ++f)
    for (int g = 2; g < 4; ++g) {
      const double a = intersection_area(uv_triangle(s, f), uv_triangle(s, g));
      total += a;
      if (a > 1e-12) expected[f] = expected[g] = 1;
    }
  ASSERT_NEAR(total, 0.375, 1e-12);  // the clipper agrees with the hand figure
  const UvAtlasMetrics m = uv_atlas_metrics(s.P, s.F, s.UV);
  EXPECT_EQ(m.charts.size(), 2u);
  EXPECT_EQ(m.face_overlapping, expected);
  EXPECT_EQ(m.overlapping_triangles, 4);
  EXPECT_EQ(m.overlapping_pairs_within_charts, 0);
  EXPECT_GT(m.overlapping_pairs_between_charts, 0);
  EXPECT_EQ(m.flipped_triangles, 0);
  EXPECT_EQ(m.mirrored_charts, 0);
}

TEST(AtlasMetrics, TouchingIsNotOverlapping) {
  // Side by side, sharing the edge u = 1 exactly; then a few ulps apart either way.
  for (double gap : {0.0, 1e-15, -1e-15}) {
    Soup s;
    add_grid(s, 3, {0, 0, 0}, 1.0 / 3, {0.0, 0.0});
    add_grid(s, 3, {9, 0, 0}, 1.0 / 3, {1 + gap, 0.0});
    const UvAtlasMetrics m = uv_atlas_metrics(s.P, s.F, s.UV);
    EXPECT_EQ(m.charts.size(), 2u);
    if (gap < 0) EXPECT_GE(m.overlapping_triangles, 6) << gap;  // at least the triangles with an edge on u = 1
    else EXPECT_EQ(m.overlapping_triangles, 0) << gap;
  }
}

TEST(AtlasMetrics, OverlapsAgreeWithClippingOnRandomTriangles) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1), r(0.005, 0.05);
  Soup s;
  const int n = 300;
  s.P = MatrixX3d::Random(3 * n, 3);
  s.UV.resize(3 * n, 2);
  s.F.resize(n, 3);
  for (int f = 0; f < n; ++f) {
    const Vec2 c(u(rng), u(rng));
    for (int k = 0; k < 3; ++k) {
      s.UV.row(3 * f + k) = c + Vec2(r(rng) * std::cos(2.1 * k + f), r(rng) * std::sin(2.1 * k + f));
      s.F(f, k) = 3 * f + k;
    }
  }
  std::vector<char> expected(n, 0);
  for (int f = 0; f < n; ++f)
    for (int g = f + 1; g < n; ++g)
      if (intersection_area(uv_triangle(s, f), uv_triangle(s, g)) > 1e-14) expected[f] = expected[g] = 1;
  const std::vector<char> got = overlapping_uv_triangles(s.F, s.UV);
  EXPECT_EQ(got, expected);
  EXPECT_GT(std::count(expected.begin(), expected.end(), 1), 20);
  EXPECT_GT(std::count(expected.begin(), expected.end(), 0), 20);
}

TEST(AtlasMetrics, MirroredChartApartFromLocalFolds) {
  Soup s;
  add_grid(s, 4, {0, 0, 0}, 0.1, {0.05, 0.05});
  add_grid(s, 4, {10, 0, 0}, 0.1, {0.95, 0.55}, /*mirror=*/true);  // u from 0.95 down to 0.55
  UvAtlasMetrics m = uv_atlas_metrics(s.P, s.F, s.UV);
  ASSERT_EQ(m.charts.size(), 2u);
  EXPECT_EQ(m.mirrored_charts, 1);
  EXPECT_EQ(m.mirrored_faces, 32);
  EXPECT_TRUE(m.charts[1].mirrored);
  EXPECT_EQ(m.flipped_triangles, 0);
  EXPECT_EQ(m.overlapping_triangles, 0);
  // Fold the first chart: drag interior vertex (1,1) past (2,2). Count by hand
  // the faces whose signed UV area turned negative.
  s.UV.row(1 * 5 + 1) = Vec2(0.05 + 0.25, 0.05 + 0.25);
  int negative = 0;
  for (int f = 0; f < 32; ++f) {
    const auto t = uv_triangle(s, f);
    negative += (t[1] - t[0]).x() * (t[2] - t[0]).y() - (t[1] - t[0]).y() * (t[2] - t[0]).x() < 0;
  }
  ASSERT_GT(negative, 0);
  m = uv_atlas_metrics(s.P, s.F, s.UV);
  EXPECT_EQ(m.flipped_triangles, negative);
  EXPECT_EQ(m.charts[0].flipped, negative);
  EXPECT_EQ(m.mirrored_charts, 1);
  EXPECT_GT(m.overlapping_pairs_within_charts, 0);  // a fold overlaps its own chart
  EXPECT_EQ(m.overlapping_pairs_between_charts, 0);
}

TEST(AtlasMetrics, ChartsOfASoupAndUtilization) {
  Soup s;
  add_grid(s, 3, {0, 0, 0}, 0.1, {0.1, 0.1});
  add_grid(s, 2, {10, 0, 0}, 0.1, {0.6, 0.6});
  const UvAtlasMetrics indexed = uv_atlas_metrics(s.P, s.F, s.UV);
  const Soup soup = as_soup(s);
  const UvAtlasMetrics m = uv_atlas_metrics(soup.P, soup.F, soup.UV);
  EXPECT_EQ(indexed.charts.size(), 2u);
  ASSERT_EQ(m.charts.size(), 2u);
  EXPECT_EQ(m.charts[0].faces, 18);
  EXPECT_EQ(m.charts[1].faces, 8);
  // Areas 0.3^2 + 0.2^2 in the unit square.
  EXPECT_TRUE(m.utilization_in_unit_square);
  EXPECT_NEAR(m.utilization, 0.09 + 0.04, 1e-12);
  EXPECT_NEAR(m.utilization_bbox, 0.13 / (0.7 * 0.7), 1e-12);
  EXPECT_NEAR(m.charts[0].area_3d, 9, 1e-12);
  // Outside [0,1]^2: over the bounding square instead.
  Soup moved = soup;
  moved.UV.col(0).array() += 3;
  const UvAtlasMetrics out = uv_atlas_metrics(moved.P, moved.F, moved.UV);
  EXPECT_FALSE(out.utilization_in_unit_square);
  EXPECT_NEAR(out.utilization, 0.13 / 0.49, 1e-12);
}

TEST(AtlasMetrics, CornersJoinOnlyThroughEdgesWithTheSamePosition) {
  // Two triangles sharing one UV corner (a bowtie): two charts. Two sharing an
  // edge in UV but not in 3D (a seam whose sides happen to coincide): two charts.
  Soup s;
  s.P.resize(6, 3);
  s.P << 0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 0, 6, 5, 0, 5, 6, 0;
  s.UV.resize(6, 2);
  s.UV << 0, 0, 0.4, 0, 0, 0.4, 0.4, 0, 0.8, 0, 0.4, 0.4;  // second triangle starts where the first's corner is
  s.F.resize(2, 3);
  s.F << 0, 1, 2, 3, 4, 5;
  EXPECT_EQ(uv_atlas_metrics(s.P, s.F, s.UV).charts.size(), 2u);
  s.P.row(3) = s.P.row(1);  // now the corner is shared in 3D too: still only a corner
  EXPECT_EQ(uv_atlas_metrics(s.P, s.F, s.UV).charts.size(), 2u);
  s.UV.row(5) = s.UV.row(2);  // an edge in UV (1-2 and 3-5) but corner 5 sits elsewhere in 3D
  EXPECT_EQ(uv_atlas_metrics(s.P, s.F, s.UV).charts.size(), 2u);
  s.P.row(5) = s.P.row(2);  // and now the same in 3D: one chart
  EXPECT_EQ(uv_atlas_metrics(s.P, s.F, s.UV).charts.size(), 1u);
}

TEST(AtlasMetrics, AtlasWithoutPaddingNeverOverlaps) {
  // fuzz_atlas's first finding: with padding 0 a chart was placed at
  // (top - height) of the box below it, which rounded an ulp into that box.
  const std::string text =
      "# seed\n"
      "v 0.7 0 -0\n"
      "v 1.3 0 0\n"
      "v 0.511122 0.511122 -0.114805\n"
      "v 0.903091 0.903092 0.114805\n"
      "v 4.8243e-17 0.787868 -0.212132\n"
      "v 7.42217e-17 1.21213 0.212132\n"
      "v -0.625927 0.625927 -0.277164\n"
      "v -0.788286 0.788286 0.277164\n"
      "v -1 1.22465e-16 -0.3\n"
      "v -1 1.22465e-16 0.3\n"
      "v -0.788286 -0.788286 -0.277164\n"
      "v -0.625927 -0.625927 0.277164\n"
      "v -2.22665e-16 -1.21213 -0.212132\n"
      "v -1.44729e-16 -0.787868 0.212132\n"
      "v 0.903091 -0.903091 -0.114805\n"
      "v 0.511122 -0.0 11 12\n"
      "f 11 13 12\n"
      "f 12 13 14\n"
      "f 13 15 14\n"
      "f 14 15 16\n"
      "f 15 2 16\n"
      "f 16 2 1\n";
  const MeshData m = read_mesh_from_memory(text, "finding.obj");
  for (double padding : {0.0, 2.0}) {
    AtlasOptions o;
    o.pack.padding = padding;
    o.charts.min_chart_faces = 0;
    const AtlasResult r = atlas(m, o);
    EXPECT_EQ(r.overlapping, 0) << padding;
    const UvAtlasMetrics um = test::measure_atlas(m.V, m.F, r);
    EXPECT_GT(um.charts.size(), 1u);
    EXPECT_EQ(um.overlapping_triangles, 0) << padding;
  }
}

// An OBJ soup like xatlas's output (vertices split at seams, v/vt per corner)
// with a chart pinched at one vertex, which make_mesh refuses as non-manifold.
std::string pinched_soup_obj() {
  return "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nv 3 0 0\nv 4 0 0\nv 3 1 0\n"
         "vt 0.2 0.2\nvt 0.4 0.2\nvt 0.2 0.4\nvt 0.0 0.2\nvt 0.2 0.0\nvt 0.6 0.6\nvt 0.8 0.6\nvt 0.6 0.8\n"
         "f 1/1 2/2 3/3\nf 1/1 4/4 5/5\nf 6/6 7/7 8/8\n";
}

TEST(AtlasMetricsCli, MetricsAcceptsANonManifoldSoup) {
  test::TempDir dir;
  std::ofstream(dir / "soup.obj") << pinched_soup_obj();
  const auto r = test::run_cli("metrics " + (dir / "soup.obj") + " --report " + (dir / "m.json"), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(test::slurp(dir / "m.json"));
  EXPECT_TRUE(j.contains("not_a_manifold_mesh"));
  const nlohmann::json& a = j.at("atlas");
  EXPECT_EQ(a.at("charts"), 3);  // the pinched pair meets at a corner only
  EXPECT_EQ(a.at("flipped_triangles"), 0);
  EXPECT_EQ(a.at("mirrored_charts"), 0);
  EXPECT_EQ(a.at("overlapping_triangles"), 0);
  EXPECT_EQ(a.at("utilization_of"), "unit_square");
  EXPECT_NEAR(a.at("utilization").get<double>(), 3 * 0.5 * 0.04, 1e-12);
  EXPECT_EQ(j.at("flipped_triangles"), 0);
  EXPECT_NEAR(j.at("angle_distortion").at("mean").get<double>(), 1.0, 1e-9);
}

TEST(AtlasMetricsCli, OneCoordinateAtSeveralPositions) {
  // As `intrinsic atlas` writes a zero-area face: all its corners on one
  // coordinate of a neighbour (here face 3, on a line, all at vt 1).
  test::TempDir dir;
  std::ofstream(dir / "c.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
                                  "vt 0.1 0.1\nvt 0.5 0.1\nvt 0.5 0.5\nvt 0.1 0.5\n"
                                  "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\nf 1/1 2/1 5/1\n";
  const auto r = test::run_cli("metrics " + (dir / "c.obj") + " --report " + (dir / "m.json"), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(test::slurp(dir / "m.json"));
  EXPECT_EQ(j.at("texture_coordinates"), 4);
  const nlohmann::json& a = j.at("atlas");
  EXPECT_EQ(a.at("degenerate_faces"), 1);
  EXPECT_EQ(a.at("flipped_triangles"), 0);
  EXPECT_EQ(a.at("collapsed_triangles"), 0);
  EXPECT_EQ(a.at("overlapping_triangles"), 0);
  EXPECT_NEAR(a.at("uv_area").get<double>(), 0.16, 1e-12);
}

TEST(AtlasMetricsCli, LayoutGivesEachChartItsOwnColour) {
  test::TempDir dir;
  std::ofstream(dir / "soup.obj") << pinched_soup_obj();
  const auto r = test::run_cli("render " + (dir / "soup.obj") + " -o " + (dir / "l.png") +
                                   " --mode layout --supersample 1 --size 200,200 -q --report " + (dir / "r.json"),
                               dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(test::slurp(dir / "r.json")).at("charts"), 3);
  const Image img = decode_png(test::slurp(dir / "l.png"));
  // The UV box [0,0.8]^2 fills the picture but for a 4% margin: sample the
  // middle of each triangle.
  auto at = [&](double u, double v) {
    const double x = 8 + u / 0.8 * 184, y = 192 - v / 0.8 * 184;
    const std::uint8_t* p = img.pixel(static_cast<int>(x), static_cast<int>(y));
    return std::array<int, 3>{p[0], p[1], p[2]};
  };
  const auto c1 = at(0.26, 0.26), c2 = at(0.14, 0.14), c3 = at(0.66, 0.66);
  EXPECT_NE(c1, c2);
  EXPECT_NE(c1, c3);
  EXPECT_NE(c2, c3);
  for (const auto& c : {c1, c2, c3}) EXPECT_FALSE(c[0] == c[1] && c[1] == c[2]) << "grey, not a chart colour";
}

}  // namespace
}  // namespace intrinsic
