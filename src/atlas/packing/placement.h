// Packing, step 4: one layout at one scale. Charts are placed one at a time,
// largest mask first (a small chart placed early would break up the room a
// large one needs; placed late it fills a gap), each in the pose and at the
// position that keeps the layout's square smallest. Among positions that
// keep it, the first in row order wins: charts settle towards the lower left
// and against each other.
#pragma once

#include <vector>

#include "atlas/packing/bitmap.h"
#include "atlas/packing/texel_mask.h"

namespace intrinsic::detail::packing {

struct Placement {
  int x = -1, y = -1;  // the dilated frame's corner on the bitmap
  int pose = 0;        // index into the chart's masks
};

// The order of placement: most covered texels first (then the larger frame,
// then the chart index, so the order is total and the layout deterministic).
std::vector<int> placement_order(const std::vector<std::vector<Mask>>& masks);

// Places every chart (masks[c]: its poses, of which the first `poses` are
// tried) on a `side`-texel bitmap; false when one does not fit. `extent`:
// the side of the square the layout needs.
bool place_all(const std::vector<std::vector<Mask>>& masks, int side, int poses, std::vector<Placement>& at,
               int& extent);

}  // namespace intrinsic::detail::packing
