// Lightmap pages (atlas.h PackOptions::texels_per_unit, docs/cli.md
// "Lightmaps"): every chart at one texel density on fixed-size pages, page k
// at u in [k, k + 1]. Checked on scenes made here (two spheres of radius 1
// and 4; a glTF scene whose one mesh two nodes draw) by the test's own
// measures: each object's area-weighted median density from its triangles'
// UV and 3D areas, every chart inside one page, and no two triangles of a
// page overlapping (the exact pairwise test of metrics.h, not the packer's
// texel masks).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cli_support.h"
#include "gltf_support.h"
#include "intrinsic/atlas.h"
#include "intrinsic/error.h"
#include "intrinsic/generate.h"
#include "intrinsic/metrics.h"
#include "intrinsic/pipeline.h"

namespace intrinsic {
namespace {

// A sphere of `radius` at `x` along the x axis.
MeshData sphere(double radius, double x) {
  GenerateOptions g;
  g.rings = 14;
  g.jitter = 0.2;
  MeshData m = generate_bumpy_sphere(g);
  m.V *= radius;
  m.V.col(0).array() += x;
  return m;
}

MeshData both(const MeshData& a, const MeshData& b) {
  MeshData m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, b.V;
  m.F.resize(a.F.rows() + b.F.rows(), 3);
  m.F << a.F, b.F.array() + static_cast<int>(a.V.rows());
  return m;
}

// Texels per unit of surface length of faces [first, last): the
// area-weighted median of sqrt(UV area in texels / 3D area).
double median_density(const MeshData& m, const AtlasResult& r, int first, int last, int resolution) {
  std::vector<std::pair<double, double>> d;  // (density, 3D area)
  double total = 0;
  for (int f = first; f < last; ++f) {
    const Eigen::Vector3d e1 = m.V.row(m.F(f, 1)) - m.V.row(m.F(f, 0)), e2 = m.V.row(m.F(f, 2)) - m.V.row(m.F(f, 0));
    const double a3 = e1.cross(e2).norm() / 2;
    const Eigen::Vector2d u1 = r.UV.row(r.FUV(f, 1)) - r.UV.row(r.FUV(f, 0)),
                          u2 = r.UV.row(r.FUV(f, 2)) - r.UV.row(r.FUV(f, 0));
    const double a2 = std::abs(u1.x() * u2.y() - u1.y() * u2.x()) / 2 * resolution * resolution;
    if (a3 <= 0) continue;
    d.emplace_back(std::sqrt(a2 / a3), a3);
    total += a3;
  }
  std::sort(d.begin(), d.end());
  double run = 0;
  for (const auto& [density, area] : d)
    if ((run += area) >= total / 2) return density;
  return 0;
}

// Every chart inside one page, and per page no two triangles overlapping.
void expect_pages_clean(const AtlasResult& r) {
  ASSERT_EQ(r.chart_page.size(), r.charts.size());
  ASSERT_EQ(static_cast<int>(r.page_utilization.size()), r.pages);
  for (int f = 0; f < r.FUV.rows(); ++f) {
    const int c = r.face_chart[static_cast<std::size_t>(f)];
    if (c < 0) continue;
    const int page = r.chart_page[static_cast<std::size_t>(c)];
    for (int k = 0; k < 3; ++k) {
      const Eigen::RowVector2d uv = r.UV.row(r.FUV(f, k));
      ASSERT_GE(uv.x(), page - 1e-12) << "face " << f;
      ASSERT_LE(uv.x(), page + 1 + 1e-12) << "face " << f;
      ASSERT_GE(uv.y(), -1e-12);
      ASSERT_LE(uv.y(), 1 + 1e-12);
    }
  }
  const std::vector<char> over = overlapping_uv_triangles(r.FUV, r.UV);
  EXPECT_EQ(std::count(over.begin(), over.end(), 1), 0);
}

TEST(AtlasPages, TwoSpheresOfDifferentSizeGetOneDensity) {
  const MeshData small = sphere(1, 0), large = sphere(4, 20);
  const MeshData m = both(small, large);
  AtlasOptions o;
  o.pack.texels_per_unit = 40;
  o.pack.resolution = 512;
  const AtlasResult r = atlas(m, o);
  EXPECT_EQ(r.flipped, 0);
  EXPECT_GE(r.pages, 2);  // 4pi(1 + 16) * 40^2 texels: more than one 512 page holds
  expect_pages_clean(r);
  const int n = static_cast<int>(small.F.rows());
  EXPECT_NEAR(median_density(m, r, 0, n, o.pack.resolution), 40, 2.0);
  EXPECT_NEAR(median_density(m, r, n, static_cast<int>(m.F.rows()), o.pack.resolution), 40, 2.0);
  EXPECT_TRUE(r.shrunk_charts.empty());
  // Pages filled in turn: every page but the last at least half full.
  for (int p = 0; p + 1 < r.pages; ++p) EXPECT_GT(r.page_utilization[static_cast<std::size_t>(p)], 0.5) << "page " << p;
}

TEST(AtlasPages, DensityScalesWithTheAskedFigure) {
  const MeshData m = sphere(1, 0);
  AtlasOptions o;
  o.pack.resolution = 1024;
  for (double t : {16.0, 64.0}) {
    o.pack.texels_per_unit = t;
    const AtlasResult r = atlas(m, o);
    EXPECT_EQ(r.pages, 1);
    EXPECT_NEAR(median_density(m, r, 0, static_cast<int>(m.F.rows()), o.pack.resolution), t, 0.05 * t);
    expect_pages_clean(r);
  }
}

TEST(AtlasPages, ChartLargerThanAPageIsShrunkNeverDropped) {
  const MeshData m = generate_flat_disk(GenerateOptions{});  // one chart of diameter 2
  AtlasOptions o;
  o.pack.resolution = 128;
  o.pack.texels_per_unit = 200;  // 400 texels across: three pages wide
  const AtlasResult r = atlas(m, o);
  ASSERT_EQ(r.charts.size(), 1u);
  EXPECT_EQ(r.pages, 1);
  EXPECT_EQ(r.shrunk_charts, std::vector<int>{0});
  expect_pages_clean(r);
}

TEST(AtlasPages, MaxPagesRefusesAndWritesNothing) {
  const MeshData m = both(sphere(1, 0), sphere(4, 20));
  AtlasOptions o;
  o.pack.texels_per_unit = 40;
  o.pack.resolution = 512;
  o.pack.max_pages = 1;
  try {
    atlas(m, o);
    ADD_FAILURE() << "more pages than allowed";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_NE(std::string(e.what()).find("more than 1 pages"), std::string::npos) << e.what();
  }
  test::TempDir dir;
  write_mesh(dir / "two.obj", m.V, m.F, MatrixX2d());
  const test::CliResult c = test::run_cli("atlas '" + (dir / "two.obj") + "' -o '" + (dir / "o.obj") +
                                              "' --texels-per-unit 40 --resolution 512 --max-pages 1",
                                          dir);
  EXPECT_EQ(c.code, 2) << c.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "o.obj"));
}

// A glTF scene whose one sphere two nodes draw (one scaled by 3): with
// unique instances each gets its own charts at the one density.
TEST(AtlasPages, InstancedSceneAtOneDensity) {
  test::TempDir dir;
  gltf_test::Doc d = gltf_test::simple_doc(sphere(1, 0));
  d.j["nodes"] = nlohmann::json::array({{{"mesh", 0}}, {{"mesh", 0}, {"translation", {10.0, 0.0, 0.0}},
                                                        {"scale", {3.0, 3.0, 3.0}}}});
  d.j["scenes"] = nlohmann::json::array({{{"nodes", {0, 1}}}});
  test::write_text(dir / "scene.gltf", d.gltf());
  AtlasRequest req;
  req.read.instances = InstanceMode::Unique;
  req.options.pack.texels_per_unit = 24;
  req.options.pack.resolution = 512;
  const AtlasOutcome o = atlas_file(dir / "scene.gltf", req);
  const int n = static_cast<int>(o.input.mesh.F.rows()) / 2;
  ASSERT_EQ(2 * n, o.input.mesh.F.rows());
  expect_pages_clean(o.result);
  EXPECT_NEAR(median_density(o.input.mesh, o.result, 0, n, 512), 24, 1.2);
  EXPECT_NEAR(median_density(o.input.mesh, o.result, n, 2 * n, 512), 24, 1.2);
}

}  // namespace
}  // namespace intrinsic
