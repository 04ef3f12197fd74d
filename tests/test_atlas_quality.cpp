// What a person sees on an atlas (docs/maths.md §9.7, §9.9), checked from
// the outside with the stretch written here (Eigen's SVD of each face's
// Jacobian in a frame of the test's own): the stretch bound holds face by
// face, a cube unfolds without distortion, hard edges are never crossed, a
// long tube is not cut into slivers, and welded and unwelded exports of one
// model give the same charts.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <algorithm>
#include <map>
#include <numeric>
#include <set>

#include "intrinsic/atlas.h"
#include "intrinsic/generate.h"
#include "intrinsic/metrics.h"
#include "atlas_test_support.h"
#include "independent_stretch.h"

namespace intrinsic {
namespace {

using test::face_stretch;
using test::quantile;
using test::Stretch;

// A cube [-1, 1]^3, each side an n x n grid of squares cut into two triangles, outward.
MeshData cube(int n) {
  MeshData m;
  std::map<std::array<int, 3>, int> index;
  std::vector<Eigen::Vector3d> V;
  std::vector<Eigen::Vector3i> F;
  auto vertex = [&](std::array<int, 3> g) {
    auto [it, fresh] = index.emplace(g, static_cast<int>(V.size()));
    if (fresh) V.emplace_back(2.0 * g[0] / n - 1, 2.0 * g[1] / n - 1, 2.0 * g[2] / n - 1);
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          int q[4];
          const int corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
          for (int c = 0; c < 4; ++c) {
            std::array<int, 3> g;
            g[axis] = side * n;
            g[(axis + 1) % 3] = i + corners[c][0];
            g[(axis + 2) % 3] = j + corners[c][1];
            q[c] = vertex(g);
          }
          // (axis+1, axis+2, axis) is right-handed: counter-clockwise seen from +axis.
          if (side == 1) F.emplace_back(q[0], q[1], q[2]), F.emplace_back(q[0], q[2], q[3]);
          else F.emplace_back(q[0], q[2], q[1]), F.emplace_back(q[0], q[3], q[2]);
        }
  m.V.resize(V.size(), 3);
  for (size_t i = 0; i < V.size(); ++i) m.V.row(i) = V[i];
  m.F.resize(F.size(), 3);
  for (size_t i = 0; i < F.size(); ++i) m.F.row(i) = F[i];
  return m;
}

// An open tube of radius r and length l along z, `around` x `along` quads.
MeshData tube(double r, double l, int around, int along) {
  MeshData m;
  m.V.resize(around * (along + 1), 3);
  for (int j = 0; j <= along; ++j)
    for (int i = 0; i < around; ++i) {
      const double t = 2 * M_PI * i / around;
      m.V.row(j * around + i) << r * std::cos(t), r * std::sin(t), l * j / along;
    }
  m.F.resize(2 * around * along, 3);
  int f = 0;
  for (int j = 0; j < along; ++j)
    for (int i = 0; i < around; ++i) {
      const int a = j * around + i, b = j * around + (i + 1) % around, c = a + around, d = b + around;
      m.F.row(f++) << a, b, d;
      m.F.row(f++) << a, d, c;
    }
  return m;
}

TEST(AtlasQuality, StretchBoundHoldsFaceByFaceOnClosedSurfaces) {
  for (const char* name : {"sphere", "torus", "genus2"}) {
    GenerateOptions g;
    g.rings = 16;
    const MeshData m = generate_surface(name, g);
    for (bool budget : {false, true}) {
      AtlasOptions o;
      o.charts.atlas_stretch_budget = budget;
      const AtlasResult r = atlas(m, o);
      const Stretch s = face_stretch(m, r);
      EXPECT_LE(quantile(s, 0.95), o.charts.max_stretch + 1e-9) << name;
      EXPECT_LE(*std::max_element(s.stretch.begin(), s.stretch.end()), o.charts.max_face_stretch + 1e-9) << name;
      for (const AtlasChart& c : r.charts) {
        if (!budget) EXPECT_LE(c.face_stretch_p95, o.charts.max_stretch) << name;
        EXPECT_LE(c.face_stretch_max, o.charts.max_face_stretch) << name;
      }
    }
  }
}

TEST(AtlasQuality, CubeUnfoldsWithoutDistortion) {
  const MeshData m = cube(6);
  const AtlasResult r = atlas(m);
  const Stretch s = face_stretch(m, r);
  for (double x : s.stretch) EXPECT_NEAR(x, 1, 1e-6);
  EXPECT_LE(r.charts.size(), 6u);
}

TEST(AtlasQuality, HardAngleNeverCrossesTheCubesEdges) {
  const MeshData m = cube(6);
  AtlasOptions o;
  o.charts.hard_angle_deg = 80;
  const AtlasResult r = atlas(m, o);
  EXPECT_EQ(r.cleaning.hard_edges, 12 * 6);
  // Every chart lies on one side of the cube: its faces share one normal.
  std::map<int, Eigen::Vector3d> normal;
  for (int f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    auto [it, fresh] = normal.emplace(r.face_chart[f], n);
    EXPECT_GT(it->second.dot(n), 1 - 1e-12) << "face " << f << " chart " << r.face_chart[f];
  }
  EXPECT_EQ(r.charts.size(), 6u);
  const Stretch s = face_stretch(m, r);
  for (double x : s.stretch) EXPECT_NEAR(x, 1, 1e-6);
}

TEST(AtlasQuality, LongTubeIsNotCutIntoSlivers) {
  // Unrolled, a strip 12 x 1.57: it fills its box but only 13% of the
  // square on its longer side. No piece may be a thin ring cut across it
  // or a sliver along it.
  const MeshData m = tube(0.25, 12, 24, 192);
  const AtlasResult r = atlas(m);
  EXPECT_LE(r.charts.size(), 4u);
  std::map<int, std::pair<double, double>> zrange;  // per chart: extent along the tube
  for (int f = 0; f < m.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const double z = m.V(m.F(f, c), 2);
      auto [it, fresh] = zrange.emplace(r.face_chart[f], std::make_pair(z, z));
      it->second.first = std::min(it->second.first, z), it->second.second = std::max(it->second.second, z);
    }
  for (const auto& [chart, range] : zrange) EXPECT_GE(range.second - range.first, 3.0) << "chart " << chart;
  for (const AtlasChart& c : r.charts) EXPECT_GE(c.faces, m.F.rows() / 8) << "a sliver";
}

TEST(AtlasQuality, WeldedAndUnweldedExportsGiveTheSameCharts) {
  GenerateOptions g;
  g.rings = 9;
  const MeshData welded = generate_surface("torus", g);
  // The same faces with every corner a vertex of its own (an export split at
  // every face, as with per-face normals).
  MeshData soup;
  soup.V.resize(3 * welded.F.rows(), 3);
  soup.F.resize(welded.F.rows(), 3);
  for (int f = 0; f < welded.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) soup.V.row(3 * f + c) = welded.V.row(welded.F(f, c)), soup.F(f, c) = 3 * f + c;
  const AtlasResult a = atlas(welded), b = atlas(soup);
  ASSERT_EQ(a.charts.size(), b.charts.size());
  std::set<std::pair<int, int>> pairs;
  for (int f = 0; f < welded.F.rows(); ++f) pairs.emplace(a.face_chart[f], b.face_chart[f]);
  EXPECT_EQ(pairs.size(), a.charts.size()) << "the two partitions into charts differ";
  // Turned off, the soup falls apart into its faces.
  AtlasOptions off;
  off.charts.weld = 0;
  off.charts.min_chart_faces = 0;
  EXPECT_EQ(atlas(soup, off).charts.size(), static_cast<size_t>(welded.F.rows()));
}

// A flat square of n x n cells, each cut into two triangles, with a slit of
// one edge from the middle of the bottom side inward: the bottom middle
// vertex is duplicated (weld off), the right cell taking the copy. The slit's
// two sides lie on each other, so the natural map of the whole square (the
// identity) touches itself along the slit: its tip's faces cover a full turn.
MeshData slit_square(int n) {
  MeshData m;
  m.V.resize((n + 1) * (n + 1) + 1, 3);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.V.row(j * (n + 1) + i) << double(i) / n, double(j) / n, 0;
  const int b = n / 2, copy = (n + 1) * (n + 1);
  m.V.row(copy) = m.V.row(b);
  m.F.resize(2 * n * n, 3);
  int f = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      int a = j * (n + 1) + i, c = a + 1, d = a + n + 1, e = d + 1;
      if (j == 0 && i == n / 2 && a == b) a = copy;  // the right cell of the slit
      m.F.row(f++) << a, c, e;
      m.F.row(f++) << a, e, d;
    }
  return m;
}

TEST(AtlasQuality, ChartsNeverTouchThemselvesAtASlit) {
  const MeshData m = slit_square(8);
  AtlasOptions o;
  o.charts.weld = 0;
  const AtlasResult r = atlas(m, o);
  const UvAtlasMetrics um = test::measure_atlas(m.V, m.F, r);  // exact overlap test
  EXPECT_EQ(um.overlapping_triangles, 0);
  EXPECT_EQ(um.flipped_triangles, 0);
  EXPECT_GE(r.charts.size(), 2u);
  // Welded, the slit closes and the square is one flat chart.
  EXPECT_EQ(atlas(m).charts.size(), 1u);
}

}  // namespace
}  // namespace intrinsic
