// Packing, step 4 (placement.h): greedy placement on the bitmap.
#include "atlas/packing/placement.h"

#include <algorithm>
#include <climits>
#include <numeric>
#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace intrinsic::detail::packing {

std::vector<int> placement_order(const std::vector<std::vector<Mask>>& masks) {
  std::vector<int> order(masks.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const Mask& ma = masks[a][0];
    const Mask& mb = masks[b][0];
    if (ma.texels != mb.texels) return ma.texels > mb.texels;
    return std::max(ma.w, ma.h) > std::max(mb.w, mb.h);
  });
  return order;
}

namespace {

// The first position (rows bottom up, first fit in each row) at or after
// row-major position `from` where the mask fits inside an `extent` square,
// as y * side + x; -1 when there is none.
long first_inside(const Bitmap& bm, const Mask& m, long from, int extent) {
  const int side = bm.side();
  for (int y = static_cast<int>(from / side); y + m.h <= extent; ++y) {
    if (!bm.may_fit(m, y)) continue;
    const int x = bm.first_fit(m, y, y == from / side ? static_cast<int>(from % side) : 0, extent);
    if (x >= 0) return static_cast<long>(y) * side + x;
  }
  return -1;
}

// The placement of a chart that fits nowhere inside the extent: the
// smallest max(x + w, y + h) over poses and positions, the first found on
// ties (poses in order, rows bottom up, first fit in each row). Inside the
// extent every position was refused, so the search looks only at positions
// reaching past it: a strip along its right side and the rows above it. No
// position can give less than `floor`: the search stops at it.
Placement best_placement(const Bitmap& bm, const std::vector<Mask>& poses, int extent, int& best_extent) {
  Placement best;
  best_extent = INT_MAX;
  int smallest = INT_MAX;
  for (const Mask& m : poses) smallest = std::min(smallest, std::max(m.w, m.h));
  const int floor = std::max(extent, smallest);
  const int side = bm.side();
  for (size_t p = 0; p < poses.size() && best_extent > floor; ++p) {
    const Mask& m = poses[p];
    for (int y = 0; y + m.h <= side && std::max(extent, y + m.h) < best_extent && best_extent > floor; ++y) {
      if (!bm.may_fit(m, y)) continue;
      // Only positions past the extent that would beat the best so far.
      const int x0 = y + m.h <= extent ? std::max(0, extent - m.w + 1) : 0;
      const int x = bm.first_fit(m, y, x0, static_cast<int>(std::min<long>(side, static_cast<long>(best_extent) - 1)));
      if (x < 0) continue;
      const int e = std::max({extent, x + m.w, y + m.h});
      if (e < best_extent) best_extent = e, best = {x, y, static_cast<int>(p)};
    }
  }
  return best;
}

// Where a chart may first fit inside the extent, from boxes: per box size,
// the row-major position before which no box of that size fits. Taken
// texels stay taken, so a position that refused a box refuses it for good,
// and refuses every box at least as wide and as high, and every mask that
// holds such a box (texel_mask.h: Mask::inner). A mask's search thus starts
// where its inner box first fits (found from the furthest cursor of the
// boxes that box holds), and is skipped when that box fits nowhere: the
// search for thousands of charts costs about one pass over the bitmap per
// box size, not one per chart. Valid while the extent stays: reset when it grows.
class BoxCursors {
 public:
  static constexpr int kMax = 32;
  BoxCursors() : at_(kMax * kMax, 0), boxes_(kMax * kMax) {}
  // The first row-major position inside `extent` where the mask's inner box
  // (clamped to kMax) fits, minus the box's offset in the mask: no position
  // before it fits the mask. -1: the mask fits nowhere inside.
  long start(const Bitmap& bm, const Mask& m, int extent) {
    const int w = std::min(m.inner[2], kMax), h = std::min(m.inner[3], kMax);
    if (w == 0 || h == 0) return 0;
    long from = 0;
    for (int j = 1; j <= h; ++j)
      for (int i = 1; i <= w; ++i) from = std::max(from, at_[(j - 1) * kMax + i - 1]);
    long pos = first_inside(bm, box(w, h), from, extent);
    at_[(h - 1) * kMax + w - 1] = pos < 0 ? static_cast<long>(extent) * bm.side() : pos;
    if (pos < 0) return -1;
    const int side = bm.side();
    const long y = pos / side - m.inner[1], x = pos % side - m.inner[0];
    return y < 0 ? 0 : y * side + std::max(0L, x);
  }
  void reset() { std::fill(at_.begin(), at_.end(), 0); }

 private:
  const Mask& box(int w, int h) {
    Mask& b = boxes_[(h - 1) * kMax + w - 1];
    if (b.w == 0) {
      b.w = w, b.h = h;
      b.rows.assign(h, Spans{{0, w}});
      b.widest.assign(h, w);
      b.by_width.resize(h);
      for (int r = 0; r < h; ++r) b.by_width[r] = r;
      b.box = true;
    }
    return b;
  }
  std::vector<long> at_;
  std::vector<Mask> boxes_;
};

// A chart inside the current extent: the first pose that fits, at its first
// position, each searched from where its inner box first fits.
Placement first_inside_all(const Bitmap& bm, const std::vector<Mask>& poses, int extent, BoxCursors& cursors) {
  for (size_t p = 0; p < poses.size(); ++p) {
    const long from = cursors.start(bm, poses[p], extent);
    if (from < 0) continue;
    const long pos = first_inside(bm, poses[p], from, extent);
    if (pos >= 0) return {static_cast<int>(pos % bm.side()), static_cast<int>(pos / bm.side()), static_cast<int>(p)};
  }
  return {};
}

}  // namespace

bool place_all(const std::vector<std::vector<Mask>>& masks, int side, std::vector<Placement>& at, int& extent) {
  Bitmap bm(side);
  at.assign(masks.size(), {});
  static const bool fixed = std::getenv("PACK_FIXED");  // TEMP
  static const int step = std::getenv("PACK_STEP") ? std::atoi(std::getenv("PACK_STEP")) : 0;  // TEMP
  extent = fixed ? side : 0;
  BoxCursors cursors;
  static const bool dbg = std::getenv("PACK_DEBUG");  // TEMP
  double tb = 0, tf = 0; int nb = 0, nf = 0, ng = 0;
  for (int c : placement_order(masks)) {
    auto t0 = std::chrono::steady_clock::now();
    Placement p = first_inside_all(bm, masks[c], extent, cursors);
    auto t1 = std::chrono::steady_clock::now();
    tb += std::chrono::duration<double>(t1 - t0).count(); nb += p.x >= 0;
    int e = extent;
    if (p.x < 0) { p = best_placement(bm, masks[c], extent, e); nf++; ng += e != extent;
    tf += std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count(); }
    if (p.x < 0) { if (dbg) fprintf(stderr, "side %d FAIL box %d %.3f full %d %.3f grow %d\n", side, nb, tb, nf, tf, ng); return false; }
    bm.take(masks[c][p.pose], p.x, p.y);
    at[c] = p;
    if (e != extent) {
      cursors.reset();  // positions past the old extent are open now
      if (step > 0) e = std::min(side, std::max(e, extent + side / step));
    }
    extent = e;
  }
  if (fixed || step > 0) {
    extent = 0;
    for (size_t c = 0; c < masks.size(); ++c)
      extent = std::max({extent, at[c].x + masks[c][at[c].pose].w, at[c].y + masks[c][at[c].pose].h});
  }
  if (dbg) fprintf(stderr, "side %d ok box %d %.3f full %d %.3f grow %d\n", side, nb, tb, nf, tf, ng);
  return true;
}

}  // namespace intrinsic::detail::packing
