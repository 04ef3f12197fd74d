// The atlas packer's steps (src/atlas/packing/), each checked against a
// count or a layout worked out by hand or by brute force here: the covered
// texels of a square and a triangle, the padding dilation texel by texel,
// quarter turns landing on the turned mask, no two placed charts' padded
// texels meeting, the utilization of equal squares, and the UVs a single
// similarity per chart with one scale for all.
#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <random>
#include <set>

#include "atlas/atlas_internal.h"
#include "atlas/packing/bitmap.h"
#include "atlas/packing/chart_pose.h"
#include "atlas/packing/placement.h"
#include "atlas/packing/scale_search.h"
#include "atlas/packing/texel_mask.h"
#include "pack_test_support.h"

namespace intrinsic::detail::packing {
namespace {

using test::dilated_by_brute_force;
using test::Texels;
using test::texels_of;

// A chart of one polygon fanned from its first vertex, UV = the polygon.
FlatChart polygon_chart(const std::vector<Eigen::Vector2d>& p) { return test::fan_chart(p, false); }

FlatChart square_chart(double side) { return polygon_chart({{0, 0}, {side, 0}, {side, side}, {0, side}}); }

// A 3 x 3 square at scale 1 covers 9 texels (closed: its sides lie on texel
// sides and count in the texels inside); 2.5 x 2.5 covers the same 9.
TEST(AtlasPackingMask, SquareTexelCounts) {
  for (double side : {3.0, 2.5}) {
    const FlatChart c = square_chart(side);
    const std::vector<Mask> m = quarter_turn_masks(c.mesh.data.F, c.UV, 1.0, 2);
    ASSERT_EQ(m.size(), 4u);
    for (const Mask& k : m) {
      EXPECT_EQ(k.texels, 9);
      EXPECT_EQ(k.w, 7);
      EXPECT_EQ(k.h, 7);
      EXPECT_EQ(texels_of(k.rows).size(), 49u);  // 3 + 2 * 2 on each side
    }
  }
}

// The triangle x, y >= 0, x + y <= 4 at scale 1: texel (i, j) (its square
// [i, i+1] x [j, j+1]) touches it exactly when its corner (i, j) does, i.e.
// i + j <= 4, within the 4 x 4 box: 16 - 3 = 13 texels.
TEST(AtlasPackingMask, TriangleTexelsAndDilationByBruteForce) {
  const FlatChart c = polygon_chart({{0, 0}, {4, 0}, {0, 4}});
  for (int pad : {0, 1, 3}) {
    const std::vector<Mask> m = quarter_turn_masks(c.mesh.data.F, c.UV, 1.0, pad);
    Texels expect;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (i + j <= 4) expect.insert({i + pad, j + pad});
    EXPECT_EQ(texels_of(m[0].own), expect);
    for (const Mask& k : m) {
      EXPECT_EQ(k.texels, 13);
      EXPECT_EQ(texels_of(k.rows), dilated_by_brute_force(texels_of(k.own), pad, k.w, k.h));
    }
  }
}

// texel_coordinates turns the chart as quarter_turn turns its mask: every
// point of the turned triangles lies in a covered texel of the turned mask.
TEST(AtlasPackingMask, QuarterTurnsLandOnTheTurnedMask) {
  const FlatChart c = polygon_chart({{0, 0}, {5.3, 0.4}, {3.1, 2.2}, {0.7, 4.9}});
  const double scale = 1.7;
  const std::vector<Mask> m = quarter_turn_masks(c.mesh.data.F, turned_to(c.UV, 0), scale, 0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int turns = 0; turns < 4; ++turns) {
    const MatrixX2d T = texel_coordinates(turned_to(c.UV, 0), scale, turns);
    const Texels own = texels_of(m[turns].own);
    for (int f = 0; f < c.mesh.data.F.rows(); ++f)
      for (int k = 0; k < 200; ++k) {
        double a = u(rng), b = u(rng);
        if (a + b > 1) a = 1 - a, b = 1 - b;
        const Eigen::Vector2d p = T.row(c.mesh.data.F(f, 0)) * (1 - a - b) + T.row(c.mesh.data.F(f, 1)) * a +
                                  T.row(c.mesh.data.F(f, 2)) * b;
        EXPECT_TRUE(own.count({static_cast<int>(std::floor(p.x())), static_cast<int>(std::floor(p.y()))}))
            << "turns " << turns << " point " << p.transpose();
      }
  }
}

// Random charts of every size placed at one scale: no chart's covered
// texels lie within another's padding, checked texel by texel with the
// dilation done here by brute force.
TEST(AtlasPackingLayout, NoTwoPaddedMasksMeetByBruteForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<FlatChart> charts;
  for (int i = 0; i < 60; ++i) {
    const double r = 0.3 + 3 * u(rng) * u(rng);
    std::vector<Eigen::Vector2d> p;
    const int n = 3 + i % 6;
    for (int k = 0; k < n; ++k) {  // star-shaped: concave for some
      const double a = 2 * M_PI * k / n, rr = r * (0.4 + 0.6 * u(rng));
      p.emplace_back(rr * std::cos(a), rr * std::sin(a));
    }
    p.insert(p.begin(), Eigen::Vector2d(0, 0));
    p.push_back(p[1]);
    charts.push_back(polygon_chart(p));
  }
  std::vector<PackChart> pack(charts.size());
  double area = 0;
  for (size_t c = 0; c < charts.size(); ++c) {
    orient_chart(charts[c]);
    area += charts[c].summary.area_3d;
    pack[c].F = &charts[c].mesh.data.F;
    for (double angle : pose_angles(charts[c], 1.0, PoseOptions{})) pack[c].poses.push_back(turned_to(charts[c].UV, angle));
  }
  const int pad = 2, side = 160;
  std::vector<std::vector<Mask>> masks;
  add_masks(pack, 6.0, pad, 0, 16, masks);
  std::vector<Placement> at;
  int extent = 0;
  ASSERT_TRUE(place_all(masks, side, 16, at, extent));
  std::vector<Texels> own(charts.size()), padded(charts.size());
  for (size_t c = 0; c < charts.size(); ++c) {
    const Mask& m = masks[c][at[c].pose];
    ASSERT_GE(at[c].x, 0);
    ASSERT_GE(at[c].y, 0);
    ASSERT_LE(at[c].x + m.w, extent);
    ASSERT_LE(at[c].y + m.h, extent);
    own[c] = texels_of(m.own, at[c].x, at[c].y);
    const Texels d = dilated_by_brute_force(texels_of(m.own), pad, m.w, m.h);
    for (const auto& [x, y] : d) padded[c].insert({x + at[c].x, y + at[c].y});
  }
  for (size_t a = 0; a < charts.size(); ++a)
    for (size_t b = 0; b < charts.size(); ++b) {
      if (a == b) continue;
      for (const auto& t : own[b]) ASSERT_FALSE(padded[a].count(t)) << a << " " << b;
    }
}

// The placement rule written plainly, position by position over a texel
// set: the first pose (in order) that fits inside the current extent at its
// first position (rows bottom up, then x); else the position of any pose
// that grows the square least (the first such in the same order).
bool place_by_brute_force(const std::vector<std::vector<Mask>>& masks, int side, std::vector<Placement>& at,
                          int& extent) {
  std::set<std::pair<int, int>> taken;
  auto fits = [&](const Mask& m, int x, int y) {
    for (const auto& [tx, ty] : texels_of(m.rows, x, y))
      if (taken.count({tx, ty})) return false;
    return true;
  };
  at.assign(masks.size(), {});
  extent = 0;
  for (int c : placement_order(masks)) {
    Placement best;
    for (size_t p = 0; p < masks[c].size() && best.x < 0; ++p)
      for (int y = 0; y + masks[c][p].h <= extent && best.x < 0; ++y)
        for (int x = 0; x + masks[c][p].w <= extent && best.x < 0; ++x)
          if (fits(masks[c][p], x, y)) best = {x, y, static_cast<int>(p)};
    int e = extent;
    if (best.x < 0) {
      e = INT_MAX;
      for (size_t p = 0; p < masks[c].size(); ++p)
        for (int y = 0; y + masks[c][p].h <= side; ++y)
          for (int x = 0; x + masks[c][p].w <= side; ++x) {
            const int grown = std::max({extent, x + masks[c][p].w, y + masks[c][p].h});
            if (grown < e && fits(masks[c][p], x, y)) e = grown, best = {x, y, static_cast<int>(p)};
          }
    }
    if (best.x < 0) return false;
    for (const auto& t : texels_of(masks[c][best.pose].own, best.x, best.y)) taken.insert(t);
    at[c] = best;
    extent = e;
  }
  return true;
}

// The packer's shortcuts (the rows' widest free runs, the growth search
// past the extent only, the box cursors) change no placement: the same
// layout as the plain rule's, for charts of every size and at several scales.
TEST(AtlasPackingLayout, SameLayoutAsThePlainRule) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<FlatChart> charts;
  for (int i = 0; i < 30; ++i) {
    const double r = 0.2 + 1.5 * u(rng) * u(rng);
    std::vector<Eigen::Vector2d> p{{0, 0}};
    for (int k = 0; k < 5; ++k) {
      const double a = 2 * M_PI * k / 5, rr = r * (0.3 + 0.7 * u(rng));
      p.emplace_back(rr * std::cos(a), rr * std::sin(a));
    }
    p.push_back(p[1]);
    charts.push_back(polygon_chart(p));
    orient_chart(charts.back());
  }
  std::vector<PackChart> pack(charts.size());
  for (size_t c = 0; c < charts.size(); ++c) {
    pack[c].F = &charts[c].mesh.data.F;
    for (double angle : pose_angles(charts[c], 4.0, PoseOptions{})) pack[c].poses.push_back(turned_to(charts[c].UV, angle));
  }
  int layouts = 0;
  for (double scale : {3.0, 4.0, 5.0, 6.0}) {
    SCOPED_TRACE(scale);
    std::vector<std::vector<Mask>> masks;
    add_masks(pack, scale, 1, 0, 16, masks);
    std::vector<Placement> at, expect;
    int extent = 0, expect_extent = 0;
    const bool fitted = place_all(masks, 64, 16, at, extent);
    ASSERT_EQ(fitted, place_by_brute_force(masks, 64, expect, expect_extent));
    if (!fitted) continue;
    ++layouts;
    EXPECT_EQ(extent, expect_extent);
    for (size_t c = 0; c < charts.size(); ++c) {
      EXPECT_EQ(at[c].x, expect[c].x) << c;
      EXPECT_EQ(at[c].y, expect[c].y) << c;
      EXPECT_EQ(at[c].pose, expect[c].pose) << c;
    }
  }
  EXPECT_GE(layouts, 2);
}

// 16 equal squares, padding 2 of 1024, half of it at the border: the best
// layout is 4 x 4 squares of c whole texels with 4c + 3 * 2 + 2 * 1 <= 1024,
// so c = 254 and the utilization 16 * 254^2 / 1024^2; without padding c = 256
// and it is 1. The search finds its scale to well within 2%.
TEST(AtlasPackingLayout, EqualSquaresReachTheGridUtilization) {
  for (const auto& [padding, best] : {std::pair<double, double>{2, 16.0 * 254 * 254 / (1024.0 * 1024)}, {0, 1.0}}) {
    std::vector<FlatChart> charts;
    for (int i = 0; i < 16; ++i) charts.push_back(square_chart(1.0));
    PackOptions o;
    o.padding = padding;
    const double u = pack_flat_charts(charts, o);
    EXPECT_LE(u, best * (1 + 1e-9));
    EXPECT_GE(u, best * 0.98) << "padding " << padding;
  }
}

// After packing, every chart is its flattened map turned and moved (no
// mirror), all scaled by one factor, and inside [0,1]^2; packing the same
// charts twice gives the same UVs.
TEST(AtlasPackingLayout, OneSimilarityPerChartOneScaleDeterministic) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<FlatChart> input;
  for (int i = 0; i < 40; ++i) {
    const double r = 0.2 + 2 * u(rng);
    input.push_back(polygon_chart({{0, 0}, {r, 0.1 * u(rng)}, {r * u(rng), r * (0.3 + u(rng))}, {-0.2 * r, r * 0.5}}));
  }
  std::vector<FlatChart> a = input, b = input;
  PackOptions o;
  const double ua = pack_flat_charts(a, o);
  const double ub = pack_flat_charts(b, o);
  EXPECT_EQ(ua, ub);
  double scale = 0;
  for (size_t c = 0; c < input.size(); ++c) {
    EXPECT_EQ(a[c].UV, b[c].UV);
    EXPECT_GE(a[c].UV.minCoeff(), 0);
    EXPECT_LE(a[c].UV.maxCoeff(), 1);
    // The map from the input UV: a = s R x + t with R a rotation, found from
    // the first edge and checked on every vertex.
    const MatrixX2d& X = input[c].UV;
    const MatrixX2d& Y = a[c].UV;
    const Eigen::Vector2d ex = (X.row(1) - X.row(0)).transpose(), ey = (Y.row(1) - Y.row(0)).transpose();
    const double s = ey.norm() / ex.norm();
    const double angle = std::atan2(ey.y(), ey.x()) - std::atan2(ex.y(), ex.x());
    const Eigen::Matrix2d R = Eigen::Rotation2Dd(angle).toRotationMatrix();
    if (c == 0) scale = s;
    EXPECT_NEAR(s, scale, 1e-9 * scale);
    for (int v = 0; v < X.rows(); ++v) {
      const Eigen::Vector2d expect = Y.row(0).transpose() + s * R * (X.row(v) - X.row(0)).transpose();
      EXPECT_NEAR((Y.row(v).transpose() - expect).norm(), 0, 1e-9);
    }
  }
  EXPECT_NEAR(ua, scale * scale * [&] {
    double area = 0;
    for (const FlatChart& c : input) area += c.summary.area_3d;
    return area;
  }(), 1e-9);
}

}  // namespace
}  // namespace intrinsic::detail::packing
