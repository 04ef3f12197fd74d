// Packing, step 4 (placement.h): greedy placement on the bitmap.
#include "atlas/packing/placement.h"

#include <algorithm>
#include <climits>
#include <numeric>

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
    if (!bm.may_fit(m, y, true)) continue;
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
Placement best_placement(const Bitmap& bm, const std::vector<Mask>& poses, size_t n, int extent, int& best_extent) {
  Placement best;
  best_extent = INT_MAX;
  int smallest = INT_MAX;
  for (size_t p = 0; p < n; ++p) smallest = std::min(smallest, std::max(poses[p].w, poses[p].h));
  const int floor = std::max(extent, smallest);
  const int side = bm.side();
  for (size_t p = 0; p < n && best_extent > floor; ++p) {
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
Placement first_inside_all(const Bitmap& bm, const std::vector<Mask>& poses, size_t n, int extent, BoxCursors& cursors) {
  for (size_t p = 0; p < n; ++p) {
    const long from = cursors.start(bm, poses[p], extent);
    if (from < 0) continue;
    const long pos = first_inside(bm, poses[p], from, extent);
    if (pos >= 0) return {static_cast<int>(pos % bm.side()), static_cast<int>(pos / bm.side()), static_cast<int>(p)};
  }
  return {};
}

}  // namespace

bool place_all(const std::vector<std::vector<Mask>>& masks, int side, int poses, std::vector<Placement>& at,
               int& extent) {
  // More covered texels than the bitmap has: no need to try.
  long texels = 0;
  for (const std::vector<Mask>& m : masks) texels += m[0].texels;
  if (texels > static_cast<long>(side) * side) return false;
  Bitmap bm(side);
  at.assign(masks.size(), {});
  extent = 0;
  BoxCursors cursors;
  for (int c : placement_order(masks)) {
    const size_t n = std::min<size_t>(poses, masks[c].size());
    Placement p = first_inside_all(bm, masks[c], n, extent, cursors);
    int e = extent;
    if (p.x < 0) p = best_placement(bm, masks[c], n, extent, e);
    if (p.x < 0) return false;
    if (e != extent) {
      cursors.reset();  // positions past the old extent are open now
      bm.set_extent(e);  // before the take: it relies on nothing taken past the old extent
    }
    bm.take(masks[c][p.pose], p.x, p.y);
    at[c] = p;
    extent = e;
  }
  return true;
}

int place_on_pages(const std::vector<std::vector<Mask>>& masks, int side, int poses, std::vector<Placement>& at,
                   std::vector<int>& page, int max_pages) {
  struct Page {
    Bitmap bm;
    BoxCursors cursors;
    explicit Page(int side) : bm(side) { bm.set_extent(side); }
  };
  std::vector<Page> pages;
  at.assign(masks.size(), {});
  page.assign(masks.size(), -1);
  for (int c : placement_order(masks)) {
    const size_t n = std::min<size_t>(poses, masks[c].size());
    for (size_t k = 0; page[c] < 0; ++k) {
      const bool fresh = k == pages.size();
      if (fresh) {
        if (max_pages > 0 && static_cast<int>(pages.size()) == max_pages) return -1;
        pages.emplace_back(side);
      }
      const Placement p = first_inside_all(pages[k].bm, masks[c], n, side, pages[k].cursors);
      if (p.x < 0 && fresh) return -1;  // fits no empty page: the caller's promise broken
      if (p.x < 0) continue;
      pages[k].bm.take(masks[c][p.pose], p.x, p.y);
      at[c] = p;
      page[c] = static_cast<int>(k);
    }
  }
  return static_cast<int>(pages.size());
}

}  // namespace intrinsic::detail::packing
