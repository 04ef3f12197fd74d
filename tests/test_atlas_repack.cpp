// Re-packing an asset's own UVs (AtlasOptions::pack_only, `--pack-only`):
// every output chart must be its input chart turned by a multiple of 90
// degrees, scaled by the one factor all charts share and moved (checked edge
// by edge against the input, to 1e-9 of the layout), the charts may not
// overlap (the exact pairwise test of metrics.h), and the layout must fill
// at least as much of the square as the input's did. Inputs made here: the
// generated textured asset (many small square tiles in a loose grid) and a
// strip whose two halves share one UV patch (a mirrored-halves layout).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "cli_support.h"
#include "gltf_support.h"
#include "intrinsic/atlas.h"
#include "intrinsic/error.h"
#include "intrinsic/generate.h"
#include "intrinsic/metrics.h"
#include "intrinsic/pipeline.h"

namespace intrinsic {
namespace {

double uv_area(const MatrixX3i& FT, const MatrixX2d& UV) {
  double a = 0;
  for (int f = 0; f < FT.rows(); ++f) {
    const Eigen::Vector2d e1 = UV.row(FT(f, 1)) - UV.row(FT(f, 0)), e2 = UV.row(FT(f, 2)) - UV.row(FT(f, 0));
    a += std::abs(e1.x() * e2.y() - e1.y() * e2.x()) / 2;
  }
  return a;
}

// Per chart the quarter turn k and the common scale s with
// out_edge = s * R(k * 90 deg) * in_edge on every edge of its faces; fails
// the test when no such k exists to `tol`.
void expect_similar_charts(const MeshData& in, const AtlasResult& r, double tol) {
  // The common scale from the total areas (every chart shares it).
  const double s = std::sqrt(uv_area(r.FUV, r.UV) / uv_area(in.FTC, in.TC));
  const int charts = static_cast<int>(r.charts.size());
  for (int k = 0; k < charts; ++k) {
    int turn = -1;
    for (int q = 0; q < 4 && turn < 0; ++q) {
      const Eigen::Matrix2d R = Eigen::Rotation2Dd(q * M_PI / 2).toRotationMatrix();
      bool all = true;
      for (int f = 0; f < in.F.rows() && all; ++f) {
        if (r.face_chart[static_cast<std::size_t>(f)] != k) continue;
        for (int c = 0; c < 3 && all; ++c) {
          const Eigen::Vector2d ein = in.TC.row(in.FTC(f, (c + 1) % 3)) - in.TC.row(in.FTC(f, c));
          const Eigen::Vector2d eout = r.UV.row(r.FUV(f, (c + 1) % 3)) - r.UV.row(r.FUV(f, c));
          all = (eout - s * R * ein).norm() <= tol;
        }
      }
      if (all) turn = q;
    }
    EXPECT_GE(turn, 0) << "chart " << k << " is not a quarter turn, the common scale and a shift of its input";
  }
}

int overlaps(const AtlasResult& r) {
  const std::vector<char> o = overlapping_uv_triangles(r.FUV, r.UV);
  return static_cast<int>(std::count(o.begin(), o.end(), 1));
}

TEST(AtlasRepack, TilesKeepTheirShapeAndFillMore) {
  TexturedAssetOptions t;
  t.cells = 16;
  t.chart_cells = 4;
  const MeshData in = generate_textured_asset(t).mesh;
  AtlasOptions o;
  o.pack_only = true;
  const AtlasResult r = atlas(in, o);
  EXPECT_EQ(r.charts.size(), 6u * 4 * 4);
  expect_similar_charts(in, r, 1e-9);
  EXPECT_EQ(overlaps(r), 0);
  EXPECT_EQ(r.flipped, 0);
  const double before = uv_area(in.FTC, in.TC);  // the input lies in [0,1]^2
  EXPECT_GE(r.utilization, before);
  EXPECT_NEAR(r.utilization, uv_area(r.FUV, r.UV), 1e-9);
  EXPECT_GE(r.UV.minCoeff(), 0.0);
  EXPECT_LE(r.UV.maxCoeff(), 1.0);
}

// A strip of 2 x 8 quads whose left and right halves share one UV patch:
// as separate charts by default (pulled apart, no overlap), together with
// keep_overlaps (still exactly on each other).
MeshData mirrored_strip() {
  MeshData m;
  const int nx = 8, ny = 2;
  m.V.resize((nx + 1) * (ny + 1), 3);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.V.row(j * (nx + 1) + i) << i, j, 0;
  std::vector<Eigen::Vector3i> F, FT;
  // UV rows: one grid per half (columns 0..4 of the half), the halves' rows
  // apart so they are two pieces with the same coordinates.
  const int half = nx / 2 + 1;
  m.TC.resize(2 * half * (ny + 1), 2);
  for (int h = 0; h < 2; ++h)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i < half; ++i) m.TC.row(h * half * (ny + 1) + j * half + i) << 0.1 + 0.1 * i, 0.1 + 0.1 * j;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int v = j * (nx + 1) + i, h = i < nx / 2 ? 0 : 1, li = i - h * (nx / 2);
      const int t = h * half * (ny + 1) + j * half + li;
      F.emplace_back(v, v + 1, v + nx + 2), FT.emplace_back(t, t + 1, t + half + 1);
      F.emplace_back(v, v + nx + 2, v + nx + 1), FT.emplace_back(t, t + half + 1, t + half);
    }
  m.F.resize(static_cast<int>(F.size()), 3);
  m.FTC.resize(m.F.rows(), 3);
  for (std::size_t f = 0; f < F.size(); ++f) m.F.row(f) = F[f], m.FTC.row(f) = FT[f];
  return m;
}

TEST(AtlasRepack, OverlappingChartsSeparatedOrKeptOnRequest) {
  const MeshData in = mirrored_strip();
  ASSERT_GT(overlaps([&] {
              AtlasResult r;
              r.FUV = in.FTC, r.UV = in.TC;
              return r;
            }()),
            0);
  AtlasOptions o;
  o.pack_only = true;
  const AtlasResult apart = atlas(in, o);
  EXPECT_EQ(apart.charts.size(), 2u);
  EXPECT_EQ(overlaps(apart), 0);
  EXPECT_EQ(apart.overlapping, 0);
  expect_similar_charts(in, apart, 1e-9);
  o.keep_overlaps = true;
  const AtlasResult kept = atlas(in, o);
  EXPECT_EQ(kept.charts.size(), 1u);
  // The report measures the layout: the kept halves' 16 faces lie on each
  // other pairwise (at least the 8 twins), which it counts.
  EXPECT_GE(kept.overlapping, 8);
  expect_similar_charts(in, kept, 1e-9);
  // Still one on the other: the two halves' corresponding corners coincide.
  for (int f = 0; f < 8; ++f) {  // face f of the left half and its twin in the right half
    const int j = f / 8, twin = f + 8;
    (void)j;
    for (int c = 0; c < 3; ++c)
      EXPECT_LE((kept.UV.row(kept.FUV(f, c)) - kept.UV.row(kept.FUV(twin, c))).norm(), 1e-12) << "face " << f;
  }
}

TEST(AtlasRepack, NoUvsIsRefusedByName) {
  MeshData m = generate_flat_disk(GenerateOptions{});
  m.path = "disk.obj";
  AtlasOptions o;
  o.pack_only = true;
  try {
    atlas(m, o);
    ADD_FAILURE() << "re-packed nothing";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_NE(std::string(e.what()).find("disk.obj: no texture coordinates"), std::string::npos) << e.what();
  }
}

// The command line on the asset written as glTF: TEXCOORD_0 re-packed into
// the same set, the output valid.
TEST(AtlasRepack, GltfSetRepackedInPlace) {
  test::TempDir dir;
  TexturedAssetOptions t;
  t.cells = 8;
  t.chart_cells = 4;
  t.texture_size = 64;
  write_textured_asset(dir / "a.glb", generate_textured_asset(t));
  const test::CliResult c = test::run_cli("atlas '" + (dir / "a.glb") + "' -o '" + (dir / "b.glb") +
                                              "' --pack-only --uv-set 0 --transfer-textures --texture-size 64",
                                          dir);
  ASSERT_EQ(c.code, 0) << c.err;
  gltf_test::expect_valid(dir / "b.glb");
  AtlasRequest req;
  req.options.pack_only = true;
  const AtlasOutcome o = atlas_file(dir / "a.glb", req);
  EXPECT_EQ(o.result.charts.size(), 6u * 2 * 2);
  expect_similar_charts(o.input.mesh, o.result, 1e-9);
  EXPECT_EQ(overlaps(o.result), 0);
}

}  // namespace
}  // namespace intrinsic
