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

// Fixed-size pages filled in turn (a lightmap at one texel density): each
// chart, in placement order, goes to the first page where one of its first
// `poses` masks fits, at its first position there; a new page is opened
// when none has room. Every mask must fit an empty `side` page. page[c]:
// chart c's page. Returns the number of pages, or -1 when more than
// `max_pages` (> 0) would be needed.
int place_on_pages(const std::vector<std::vector<Mask>>& masks, int side, int poses, std::vector<Placement>& at,
                   std::vector<int>& page, int max_pages);

}  // namespace intrinsic::detail::packing
