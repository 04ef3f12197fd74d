// `--weld EPS`: coincident vertices merged for the
// computation only. A hand-built square whose two triangles do not share
// vertices, and teapot.obj (unwelded seams), against counts made here by
// other means (exact duplicate positions in a std::set).
#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "atlas_test_support.h"
#include "cli_support.h"
#include "intrinsic/atlas.h"
#include "intrinsic/io.h"
#include "intrinsic/metrics.h"
#include "test_support.h"

namespace intrinsic {
namespace {

MeshData unwelded_square() {
  MeshData m;
  m.V.resize(6, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0,  // first triangle
      1, 0, 0, 1, 1, 0, 0, 1, 0;     // second, its own copies of (1,0,0) and (0,1,0)
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 3, 4, 5;
  return m;
}

UvAtlasMetrics measure(const MeshData& m, const AtlasResult& r) { return test::measure_atlas(m.V, m.F, r); }

TEST(AtlasWeld, UnweldedPairBecomesOneChart) {
  const MeshData m = unwelded_square();
  AtlasOptions none;
  none.charts.weld = 0;
  const AtlasResult apart = atlas(m, none);
  EXPECT_EQ(apart.components, 2);
  EXPECT_EQ(apart.charts.size(), 2u);
  EXPECT_EQ(apart.cleaning.welded_vertices, 0);
  AtlasOptions o;
  o.charts.weld = 1e-6;
  const AtlasResult r = atlas(m, o);
  EXPECT_EQ(r.cleaning.welded_vertices, 2);
  EXPECT_EQ(r.components, 1);
  ASSERT_EQ(r.charts.size(), 1u);
  ASSERT_EQ(r.FUV.rows(), 2);
  // Welded corners share a texture coordinate: the square's 4 corners.
  EXPECT_EQ(r.FUV(0, 1), r.FUV(1, 0));
  EXPECT_EQ(r.FUV(0, 2), r.FUV(1, 2));
  const UvAtlasMetrics um = measure(m, r);
  EXPECT_EQ(um.charts.size(), 1u);
  EXPECT_EQ(um.flipped_triangles + um.mirrored_charts + um.overlapping_triangles, 0);
  // A weld distance below the gap welds nothing: move the copies apart by 1e-3 of the diagonal.
  MeshData gap = m;
  gap.V(3, 0) += 1e-3 * std::sqrt(2.0);
  gap.V(5, 1) += 1e-3 * std::sqrt(2.0);
  o.charts.weld = 0.5e-3;
  EXPECT_EQ(atlas(gap, o).cleaning.welded_vertices, 0);
  o.charts.weld = 2e-3;
  EXPECT_EQ(atlas(gap, o).cleaning.welded_vertices, 2);
  o.charts.weld = -1;
  test::expect_error([&] { atlas(m, o); }, ErrorKind::Usage, "weld");
}

TEST(AtlasWeldCorpus, TeapotSeams) {
  REQUIRE_SHARED_MESHES();
  const std::string path = test::shared_mesh("assets/teapot.obj");
  const MeshData m = read_mesh(path);
  std::set<std::array<double, 3>> distinct;
  for (int v = 0; v < m.V.rows(); ++v) distinct.insert({m.V(v, 0), m.V(v, 1), m.V(v, 2)});
  const int duplicates = static_cast<int>(m.V.rows() - distinct.size());
  ASSERT_GT(duplicates, 0);
  AtlasOptions o;
  o.charts.weld = 1e-9;
  AtlasOptions none;
  none.charts.weld = 0;
  const AtlasResult plain = atlas(m, none);
  const AtlasResult r = atlas(m, o);
  EXPECT_EQ(r.cleaning.welded_vertices, duplicates);
  EXPECT_LT(r.components, plain.components);
  const UvAtlasMetrics um = measure(m, r);
  EXPECT_EQ(um.flipped_triangles, 0);
  EXPECT_EQ(um.mirrored_charts, 0);
  EXPECT_EQ(um.overlapping_triangles, 0);
  std::printf("  teapot: %d welded, components %d -> %d, charts %zu -> %zu\n", r.cleaning.welded_vertices,
              plain.components, r.components, plain.charts.size(), r.charts.size());

  // The CLI reports it and keeps the input's vertices.
  test::TempDir dir;
  const auto run = test::run_cli("atlas " + path + " -o " + (dir / "t.obj") + " --weld 1e-9 -q --report " +
                                     (dir / "r.json"),
                                 dir);
  ASSERT_EQ(run.code, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(test::slurp(dir / "r.json"));
  EXPECT_EQ(j.at("cleaning").at("welded_vertices"), duplicates);
  const MeshData out = read_mesh(dir / "t.obj");
  ASSERT_EQ(out.V.rows(), m.V.rows());
  EXPECT_EQ(out.V, m.V);
  EXPECT_EQ(out.F, m.F);
}

}  // namespace
}  // namespace intrinsic
