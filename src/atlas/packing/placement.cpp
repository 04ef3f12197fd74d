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

// The best placement of one chart: the smallest square side max(extent,
// x + w, y + h) over its poses and positions, the first found on ties
// (poses in order, rows bottom up, first fit in each row). No position can
// give less than `floor`, so the search stops once one reaches it.
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
      // Only positions that would beat the best so far: x + w < best_extent.
      const int x = bm.first_fit(m, y, 0, static_cast<int>(std::min<long>(side, static_cast<long>(best_extent) - 1)));
      if (x < 0) continue;
      const int e = std::max({extent, x + m.w, y + m.h});
      if (e < best_extent) best_extent = e, best = {x, y, static_cast<int>(p)};
    }
  }
  return best;
}

}  // namespace

bool place_all(const std::vector<std::vector<Mask>>& masks, int side, std::vector<Placement>& at, int& extent) {
  Bitmap bm(side);
  at.assign(masks.size(), {});
  extent = 0;
  for (int c : placement_order(masks)) {
    int e = 0;
    const Placement p = best_placement(bm, masks[c], extent, e);
    if (p.x < 0) return false;
    bm.take(masks[c][p.pose], p.x, p.y);
    at[c] = p;
    extent = e;
  }
  return true;
}

}  // namespace intrinsic::detail::packing
