// Packing, step 5 (scale_search.h): the search for the scale.
#include "atlas/packing/scale_search.h"

#include <cmath>
#include <cstdint>

#include "util/parallel_for.h"

namespace intrinsic::detail::packing {

std::vector<std::vector<Mask>> all_masks(const std::vector<PackChart>& charts, double scale, int pad) {
  std::vector<std::vector<Mask>> masks(charts.size());
  parallel_for(static_cast<std::int64_t>(charts.size()), [&](std::int64_t b, std::int64_t e) {
    for (std::int64_t c = b; c < e; ++c)
      for (const MatrixX2d& UV : charts[c].poses) {
        std::vector<Mask> turns = quarter_turn_masks(*charts[c].F, UV, scale, pad);
        for (Mask& m : turns) masks[c].push_back(std::move(m));
      }
  }, 8);
  return masks;
}

bool try_scale(const std::vector<PackChart>& charts, double scale, int side, int pad, Layout& out) {
  Layout l;
  l.scale = scale;
  if (!place_all(all_masks(charts, scale, pad), side, l.at, l.extent)) return false;
  out = std::move(l);
  return true;
}

namespace {

// The largest scale at which every chart fits: shrink until one fits, then
// bisect between the fitting and the failing scale.
Layout bisect_scale(const std::vector<PackChart>& charts, double area, int& side, int pad) {
  Layout fit;
  while (true) {
    double hi = side / std::sqrt(area), lo = 0;
    for (double s = hi * 0.85; s > hi * 1e-4; s *= 0.8) {
      if (try_scale(charts, s, side, pad, fit)) {
        lo = s;
        break;
      }
      hi = s;
    }
    if (lo > 0) {
      for (int i = 0; i < 7 && hi > lo * 1.01; ++i) {
        const double mid = std::sqrt(lo * hi);
        Layout l;
        if (try_scale(charts, mid, side, pad, l))
          lo = mid, fit = std::move(l);
        else
          hi = mid;
      }
      return fit;
    }
    side *= 2;
  }
}

}  // namespace

// The bisection on a bitmap of half the size first (a quarter of the
// texels to place), then the full bitmap from just above that scale down in
// small steps: a few full-size packings instead of a dozen.
Layout search_layout(const std::vector<PackChart>& charts, double area, int& side, int pad) {
  if (side < 256) return bisect_scale(charts, area, side, pad);
  int half = side / 2;
  const Layout coarse = bisect_scale(charts, area, half, (pad + 1) / 2);
  if (half == side / 2) {  // the half bitmap held them: its scale, doubled, is close
    double s = coarse.scale * 2 * 1.03;
    for (int i = 0; i < 6; ++i, s *= 0.985) {
      Layout l;
      if (try_scale(charts, s, side, pad, l)) return l;
    }
  }
  return bisect_scale(charts, area, side, pad);
}

}  // namespace intrinsic::detail::packing
