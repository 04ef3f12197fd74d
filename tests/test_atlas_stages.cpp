// The staged atlas (atlas.h: compute_charts, charts_from_ids, pack_charts)
// on generated surfaces: the stages give exactly the one-call atlas(), the
// same charts pack again at other resolutions and paddings as a fresh
// atlas() would, the pack stage only moves each chart by one similarity
// shared by all charts (checked per face against the charts' own UVs, at
// surface scale: UV area = 3D area), given chart ids are kept, and bad ids
// or broken charts give a typed error naming the face or chart.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "intrinsic/atlas.h"
#include "intrinsic/error.h"
#include "intrinsic/generate.h"
#include "test_support.h"

namespace intrinsic {
namespace {

MeshData sphere() {
  GenerateOptions g;
  g.rings = 16;
  return generate_bumpy_sphere(g);
}

MeshData torus() {
  GenerateOptions g;
  g.rings = 12;
  return generate_torus(g);
}

double area_3d(const MeshData& m, int f) {
  const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
  return 0.5 * (b - a).cross(c - a).norm();
}

void expect_same_atlas(const AtlasResult& a, const AtlasResult& b) {
  EXPECT_TRUE(a.UV == b.UV);
  EXPECT_TRUE(a.FUV == b.FUV);
  EXPECT_TRUE(a.F == b.F);
  EXPECT_EQ(a.face_chart, b.face_chart);
  ASSERT_EQ(a.charts.size(), b.charts.size());
  for (size_t k = 0; k < a.charts.size(); ++k) EXPECT_EQ(a.charts[k].rotated, b.charts[k].rotated) << k;
  EXPECT_EQ(a.utilization, b.utilization);
  EXPECT_EQ(a.splits, b.splits);
  EXPECT_EQ(a.seam_length, b.seam_length);
}

TEST(AtlasStages, ComputeThenPackIsAtlas) {
  for (const MeshData& m : {sphere(), torus()}) {
    AtlasOptions o;
    o.pack.resolution = 512;
    o.pack.padding = 3;
    const AtlasCharts charts = compute_charts(m, o.charts);
    expect_same_atlas(pack_charts(charts, pack_options(o)), atlas(m, o));
  }
}

// Re-packing the same charts at another resolution or padding equals a fresh
// atlas() with those packing options: the charts do not depend on them.
TEST(AtlasStages, RepackEqualsFreshAtlas) {
  const MeshData m = torus();
  const AtlasCharts charts = compute_charts(m);
  for (auto [resolution, padding] : {std::pair{256, 4.0}, std::pair{2048, 1.0}, std::pair{64, 0.0}}) {
    AtlasOptions o;
    o.pack.resolution = resolution;
    o.pack.padding = padding;
    PackOptions p;
    p.resolution = resolution;
    p.padding = padding;
    expect_same_atlas(pack_charts(charts, p), atlas(m, o));
  }
}

// The charts stage's UVs are at surface scale (every chart's UV area equals
// its 3D area, no face flipped), and packing moves each chart by a
// similarity with one scale for all: per face, packed UV area over stage UV
// area is the same everywhere, and its sign is kept.
TEST(AtlasStages, PackingScalesAllChartsAlike) {
  const MeshData m = sphere();
  const AtlasCharts charts = compute_charts(m);
  ASSERT_GT(charts.charts.size(), 1u);
  std::vector<double> chart_uv(charts.charts.size(), 0.0), chart_3d(charts.charts.size(), 0.0);
  for (int f = 0; f < m.F.rows(); ++f) {
    const int k = charts.face_chart[f];
    if (k < 0) continue;
    const double a = test::signed_uv_area(charts.UV, charts.FUV, f);
    EXPECT_GT(a, 0) << "face " << f;
    chart_uv[k] += a, chart_3d[k] += area_3d(m, f);
  }
  for (size_t k = 0; k < chart_uv.size(); ++k) EXPECT_NEAR(chart_uv[k], chart_3d[k], 1e-9 * chart_3d[k]) << k;
  const AtlasResult r = pack_charts(charts);
  double ratio = 0;
  for (int f = 0; f < m.F.rows(); ++f) {
    if (charts.face_chart[f] < 0) continue;
    const double a = test::signed_uv_area(charts.UV, charts.FUV, f);
    if (a < 1e-12) continue;
    const double q = test::signed_uv_area(r.UV, r.FUV, f) / a;
    if (ratio == 0) ratio = q;
    EXPECT_NEAR(q, ratio, 1e-6 * ratio) << "face " << f;
  }
  EXPECT_GT(ratio, 0);
}

// Chart ids from planes: every output chart lies within one given chart,
// a chart count is the given charts plus the splits reported, and a small
// cap (a disk whose natural map is valid) comes out as exactly one chart.
TEST(AtlasStages, GivenChartsAreKept) {
  const MeshData m = sphere();
  std::vector<int> ids(m.F.rows());
  std::set<int> cap;
  for (int f = 0; f < m.F.rows(); ++f) {
    double z = 0;
    for (int c = 0; c < 3; ++c) z += m.V(m.F(f, c), 2) / 3;
    ids[f] = z > 0.6 ? 0 : (z > -0.2 ? 1 : 2);
    if (ids[f] == 0) cap.insert(f);
  }
  ASSERT_GT(cap.size(), 10u);
  const AtlasCharts charts = charts_from_ids(m, ids);
  std::map<int, std::set<int>> given_of;  // output chart -> given ids among its faces
  std::map<int, std::set<int>> faces_of;  // output chart -> faces
  for (int f = 0; f < m.F.rows(); ++f) {
    ASSERT_GE(charts.face_chart[f], 0) << "face " << f;
    given_of[charts.face_chart[f]].insert(ids[f]);
    faces_of[charts.face_chart[f]].insert(f);
  }
  for (const auto& [k, given] : given_of) EXPECT_EQ(given.size(), 1u) << "chart " << k;
  EXPECT_EQ(charts.charts.size(), 3u + charts.splits);
  EXPECT_EQ(faces_of[charts.face_chart[*cap.begin()]], cap);
  // Packed, each face keeps its chart.
  const AtlasResult r = pack_charts(charts);
  EXPECT_EQ(r.face_chart, charts.face_chart);
  EXPECT_EQ(r.splits, charts.splits);
}

// A given chart in two pieces (two caps with one id) becomes two charts,
// reported as a not-disk split.
TEST(AtlasStages, GivenChartInPiecesIsSplit) {
  const MeshData m = sphere();
  std::vector<int> ids(m.F.rows());
  for (int f = 0; f < m.F.rows(); ++f) {
    double z = 0;
    for (int c = 0; c < 3; ++c) z += m.V(m.F(f, c), 2) / 3;
    ids[f] = std::abs(z) > 0.6 ? 7 : 3;  // the band between (id 3) is an annulus: split too
  }
  const AtlasCharts charts = charts_from_ids(m, ids);
  EXPECT_GE(charts.split_reasons.not_disk, 2);
  EXPECT_EQ(static_cast<int>(charts.charts.size()), 2 + charts.splits);
  std::map<int, std::set<int>> given_of;
  for (int f = 0; f < m.F.rows(); ++f) given_of[charts.face_chart[f]].insert(ids[f]);
  for (const auto& [k, given] : given_of) EXPECT_EQ(given.size(), 1u) << "chart " << k;
}

// compute_charts' own charts given back as ids: every one is a valid disk,
// so each comes out as one chart with the same faces and the same UVs.
TEST(AtlasStages, OwnChartsGivenBackAreUnchanged) {
  const MeshData m = torus();
  const AtlasCharts first = compute_charts(m);
  const AtlasCharts again = charts_from_ids(m, first.face_chart);
  EXPECT_EQ(again.splits, 0);
  ASSERT_EQ(again.charts.size(), first.charts.size());
  std::map<int, int> to_first;
  for (int f = 0; f < m.F.rows(); ++f) {
    const auto [it, added] = to_first.emplace(again.face_chart[f], first.face_chart[f]);
    EXPECT_EQ(it->second, first.face_chart[f]) << "face " << f;
    for (int c = 0; c < 3; ++c)
      EXPECT_TRUE(again.UV.row(again.FUV(f, c)) == first.UV.row(first.FUV(f, c))) << "face " << f << " corner " << c;
  }
  EXPECT_EQ(to_first.size(), first.charts.size());
}

TEST(AtlasStages, BadIds) {
  MeshData m = sphere();
  std::vector<int> ids(m.F.rows(), 0);
  test::expect_error([&] { charts_from_ids(m, std::vector<int>(m.F.rows() - 1, 0)); }, ErrorKind::Usage,
                     "chart ids number");
  ids[5] = -2;
  test::expect_error([&] { charts_from_ids(m, ids); }, ErrorKind::Usage, "face 5: chart id -2");
  ids[5] = 0, ids[7] = -1;
  test::expect_error([&] { charts_from_ids(m, ids); }, ErrorKind::Usage, "face 7: chart id -1, but the face is not degenerate");
  // -1 is accepted on a degenerate face (a repeated vertex), which gets UVs
  // but no chart.
  ids[7] = 0;
  m.F.conservativeResize(m.F.rows() + 1, 3);
  m.F.row(m.F.rows() - 1) << 0, 1, 1;
  ids.push_back(-1);
  const AtlasResult r = pack_charts(charts_from_ids(m, ids));
  EXPECT_EQ(r.face_chart.back(), -1);
  EXPECT_GE(r.FUV.row(m.F.rows() - 1).minCoeff(), 0);
}

TEST(AtlasStages, BadPackInput) {
  const MeshData m = torus();
  const AtlasCharts charts = compute_charts(m);
  PackOptions p;
  p.resolution = 0;
  test::expect_error([&] { pack_charts(charts, p); }, ErrorKind::Usage, "resolution");
  AtlasCharts broken = charts;
  broken.FUV(3, 1) = -1;
  test::expect_error([&] { pack_charts(broken); }, ErrorKind::Usage, "face 3");
  broken = charts;
  broken.face_chart.pop_back();
  test::expect_error([&] { pack_charts(broken); }, ErrorKind::Usage, "one row per face");
  broken = charts;
  broken.UV.conservativeResize(broken.UV.rows() + 1, 2);
  test::expect_error([&] { pack_charts(broken); }, ErrorKind::Usage, "rows no chart uses");
  // atlas() checks the packing options before computing any chart.
  AtlasOptions o;
  o.pack.padding = -1;
  test::expect_error([&] { atlas(m, o); }, ErrorKind::Usage, "padding");
}

// The one call runs the pack stage with the orientation kept exactly when
// it re-packs the input's own UVs; every other pack option is its own.
TEST(AtlasStages, PackOptionsOfTheOneCall) {
  AtlasOptions o;
  o.pack.resolution = 77, o.pack.padding = 5, o.pack.keep_orientation = true;
  EXPECT_FALSE(pack_options(o).keep_orientation);
  EXPECT_EQ(pack_options(o).resolution, 77);
  EXPECT_EQ(pack_options(o).padding, 5);
  o.pack_only = true;
  EXPECT_TRUE(pack_options(o).keep_orientation);
}

}  // namespace
}  // namespace intrinsic
