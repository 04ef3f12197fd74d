// The packer's masks in their four quarter turns against the texel grid
// turned and dilated here by brute force (turns 2 and 3 are mirrored spans,
// not a rasterization), masks filled as they are made against masks filled
// afterwards, and the scale search's layout against the thread
// count (two packings at once on two cores must decide as one at a time).
// Charts are random polygons made here; nothing is read.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "atlas/atlas_internal.h"
#include "atlas/packing/chart_pose.h"
#include "atlas/packing/scale_search.h"
#include "atlas/packing/texel_mask.h"
#include "pack_test_support.h"
#include "util/parallel_for.h"

namespace intrinsic::detail::packing {
namespace {

using test::dilated_by_brute_force;
using test::Texels;
using test::texels_of;

// A star-shaped polygon around the origin (concave for some), fanned from
// its centre: UV = the polygon, 3D = the same in the plane z = 0.
FlatChart star_chart(std::mt19937& rng, double r, int n) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector2d> p{Eigen::Vector2d(0, 0)};
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n, rr = r * (0.3 + 0.7 * u(rng));
    p.emplace_back(rr * std::cos(a), rr * std::sin(a));
  }
  FlatChart c = test::fan_chart(p, true);
  orient_chart(c);
  return c;
}

// The largest all-dilated rectangle's area, by trying every corner pair
// (a rectangle is full when its count of dilated texels, from prefix sums,
// is its area).
long largest_box_by_brute_force(const Texels& t, int w, int h) {
  std::vector<long> sum(static_cast<size_t>(w + 1) * (h + 1), 0);
  auto at = [&](int x, int y) -> long& { return sum[static_cast<size_t>(y) * (w + 1) + x]; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) at(x + 1, y + 1) = t.count({x, y}) + at(x, y + 1) + at(x + 1, y) - at(x, y);
  long best = 0;
  for (int y0 = 0; y0 < h; ++y0)
    for (int x0 = 0; x0 < w; ++x0)
      for (int y1 = y0 + 1; y1 <= h; ++y1)
        for (int x1 = x0 + 1; x1 <= w; ++x1) {
          const long area = static_cast<long>(x1 - x0) * (y1 - y0);
          if (at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0) == area) best = std::max(best, area);
        }
  return best;
}

// Each turn k: its own texels are turn 0's turned k times by
// (x, y) -> (h - 1 - y, x) (the frame turns onto itself), its dilated texels
// every texel within `pad` of them (Chebyshev), and its per-row widths,
// row order and largest box agree with those texels.
TEST(PackMasks, FourTurnsAgreeWithTheGridTurnedAndDilatedByBruteForce) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 24; ++trial) {
    const FlatChart c = star_chart(rng, 1 + 4 * u(rng), 3 + trial % 7);
    const int pad = trial % 4;
    const double scale = 0.7 + 2.5 * u(rng);
    const std::vector<Mask> m = quarter_turn_masks(c.mesh.data.F, c.UV, scale, pad);
    ASSERT_EQ(m.size(), 4u);
    Texels turned = texels_of(m[0].own);
    int w = m[0].w, h = m[0].h;
    for (int k = 0; k < 4; ++k) {
      SCOPED_TRACE("trial " + std::to_string(trial) + " turn " + std::to_string(k));
      const Mask& mk = m[k];
      ASSERT_EQ(mk.w, w);
      ASSERT_EQ(mk.h, h);
      EXPECT_EQ(texels_of(mk.own), turned);
      EXPECT_EQ(mk.texels, static_cast<long>(turned.size()));
      const Texels dilated = dilated_by_brute_force(turned, pad);  // the mask's frame must hold it all
      for (const auto& [x, y] : dilated) ASSERT_TRUE(x >= 0 && x < w && y >= 0 && y < h);
      EXPECT_EQ(texels_of(mk.rows), dilated);
      for (int y = 0; y < h; ++y) {
        int widest = 0;
        for (const auto& s : mk.rows[y]) widest = std::max(widest, s.second - s.first);
        EXPECT_EQ(mk.widest[y], widest);
      }
      std::vector<int> rows = mk.by_width;
      std::sort(rows.begin(), rows.end());
      for (int y = 0; y < h; ++y) EXPECT_EQ(rows[y], y);
      for (int i = 1; i < h; ++i) EXPECT_GE(mk.widest[mk.by_width[i - 1]], mk.widest[mk.by_width[i]]);
      const auto& b = mk.inner;
      for (int y = b[1]; y < b[1] + b[3]; ++y)
        for (int x = b[0]; x < b[0] + b[2]; ++x) EXPECT_TRUE(dilated.count({x, y})) << x << "," << y;
      if (b[2] > 0 && w * h <= 40 * 40) EXPECT_EQ(static_cast<long>(b[2]) * b[3], largest_box_by_brute_force(dilated, w, h));
      Texels next;
      for (const auto& [x, y] : turned) next.insert({h - 1 - y, x});
      turned = next;
      std::swap(w, h);
    }
  }
}

// Masks made with a box predicate (filled as they are made, no search for
// a largest box) against the masks made without one and filled afterwards,
// as the scale search made them before: every field equal, rows of filled
// masks listed as fill_frame lists them. The predicate accepts about half
// the masks (by a hash of their size), so both kinds are compared.
bool some_as_box(const Mask& m, int pad) { return (m.w * 31 + m.h * 17 + pad) % 2 == 0; }
TEST(PackMasks, FilledAsMadeEqualFilledAfterwards) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  int filled = 0, kept = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const FlatChart c = star_chart(rng, 1 + 6 * u(rng), 3 + trial % 7);
    const int pad = trial % 4;
    const double scale = 0.7 + 4 * u(rng);
    std::vector<Mask> before = quarter_turn_masks(c.mesh.data.F, c.UV, scale, pad);
    for (Mask& m : before)
      if (some_as_box(m, pad)) fill_frame(m);
    const std::vector<Mask> made = quarter_turn_masks(c.mesh.data.F, c.UV, scale, pad, some_as_box);
    ASSERT_EQ(made.size(), before.size());
    for (size_t k = 0; k < made.size(); ++k) {
      SCOPED_TRACE("trial " + std::to_string(trial) + " turn " + std::to_string(k));
      const Mask &a = made[k], &b = before[k];
      (some_as_box(b, pad) ? filled : kept) += 1;
      EXPECT_EQ(a.w, b.w);
      EXPECT_EQ(a.h, b.h);
      EXPECT_EQ(a.rows, b.rows);
      EXPECT_EQ(a.own, b.own);
      EXPECT_EQ(a.texels, b.texels);
      EXPECT_EQ(a.widest, b.widest);
      EXPECT_EQ(a.by_width, b.by_width);
      EXPECT_EQ(a.box, b.box);
      EXPECT_EQ(a.inner, b.inner);
    }
  }
  EXPECT_GT(filled, 20);
  EXPECT_GT(kept, 20);
}

// The scale search with one thread and with two (two packings at once,
// speculating on the next one) gives the same layout: the packings decide
// in the same order. On the half-bitmap path (side >= 256) and the direct
// one, with extra pose angles for the large concave charts.
TEST(PackSearch, SameLayoutWithOneAndTwoThreads) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<FlatChart> charts;
  for (int i = 0; i < 70; ++i) charts.push_back(star_chart(rng, 0.2 + 3 * u(rng) * u(rng), 3 + i % 8));
  double area = 0;
  for (const FlatChart& c : charts) area += c.summary.area_3d;
  const std::vector<std::vector<double>> angles = all_pose_angles(charts, area, PoseOptions{});
  std::vector<PackChart> pack(charts.size());
  for (size_t c = 0; c < charts.size(); ++c) {
    pack[c].F = &charts[c].mesh.data.F;
    for (double a : angles[c]) pack[c].poses.push_back(turned_to(charts[c].UV, a));
  }
  const int saved = thread_limit().load();
  for (int side : {130, 514}) {
    Layout one, two;
    int side1 = side, side2 = side;
    thread_limit() = 1;
    one = search_layout(pack, area, side1, 2);
    thread_limit() = 2;
    two = search_layout(pack, area, side2, 2);
    thread_limit() = saved;
    SCOPED_TRACE("side " + std::to_string(side));
    EXPECT_EQ(side1, side2);
    EXPECT_EQ(one.scale, two.scale);
    EXPECT_EQ(one.extent, two.extent);
    EXPECT_EQ(one.zoom, two.zoom);
    EXPECT_EQ(one.pad, two.pad);
    ASSERT_EQ(one.at.size(), charts.size());
    ASSERT_EQ(two.at.size(), charts.size());
    for (size_t c = 0; c < charts.size(); ++c) {
      EXPECT_EQ(one.at[c].x, two.at[c].x);
      EXPECT_EQ(one.at[c].y, two.at[c].y);
      EXPECT_EQ(one.at[c].pose, two.at[c].pose);
    }
    EXPECT_GT(one.extent, 0);
    EXPECT_LE(one.extent * one.zoom, side1);
  }
}

}  // namespace
}  // namespace intrinsic::detail::packing
