// Packing, step 5 (scale_search.h): the search for the scale.
#include "atlas/packing/scale_search.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "atlas/batch_workers.h"
#include "atlas/thresholds.h"
#include "util/parallel_for.h"

namespace intrinsic::detail::packing {
namespace {

// Masks placed as their whole frame (thresholds.h: kBoxFill, kBoxSide).
bool as_box(const Mask& m, int pad) {
  if (m.box) return false;
  long dilated = 0;
  for (const Spans& r : m.rows)
    for (const auto& s : r) dilated += s.second - s.first;
  const double fill = static_cast<double>(dilated) / (static_cast<double>(m.w) * m.h);
  return fill >= kBoxFill || std::max(m.w, m.h) <= 2 * pad + kBoxSide;
}

}  // namespace

void add_masks(const std::vector<PackChart>& charts, double scale, int pad, size_t first, size_t last,
               std::vector<std::vector<Mask>>& masks, bool serial) {
  masks.resize(charts.size());
  const std::int64_t n = static_cast<std::int64_t>(charts.size());
  parallel_for(n, [&](std::int64_t b, std::int64_t e) {
    for (std::int64_t c = b; c < e; ++c)
      for (size_t a = first; a < std::min(last, charts[c].poses.size()); ++a) {
        for (Mask& m : quarter_turn_masks(*charts[c].F, charts[c].poses[a], scale, pad, as_box))
          masks[c].push_back(std::move(m));
      }
  }, serial ? n + 1 : 8);
}

bool try_scale(const std::vector<PackChart>& charts, double scale, int side, int pad, bool angles, Layout& out,
               bool serial) {
  size_t n = 1;
  for (const PackChart& c : charts) n = std::max(n, angles ? c.poses.size() : 1);
  std::vector<std::vector<Mask>> masks;
  add_masks(charts, scale, pad, 0, n, masks, serial);
  Layout l;
  l.scale = scale;
  l.pad = pad;
  if (!place_all(masks, side, static_cast<int>(4 * n), l.at, l.extent)) return false;
  out = std::move(l);
  return true;
}

namespace {

// One packing's outcome, kept apart until the search decides that it counts.
struct Try {
  double scale = 0;
  bool ok = false;
  Layout l;
};

Try attempt(const std::vector<PackChart>& charts, double scale, int side, int pad, bool angles, bool serial) {
  Try t;
  t.scale = scale;
  t.ok = try_scale(charts, scale, side, pad, angles, t.l, serial);
  return t;
}

// Two packings at once, each on its own core with its masks built on its
// own thread; only when there are two cores (one core tries one scale at a
// time, and never a scale the sequential search would not try). On a
// worker kept for the whole search (batch_workers.h): a thread started per
// pair had to be scheduled and joined each time, and on a loaded machine
// the calling thread waited for it; now it makes the second packing itself
// when the worker has not begun it.
bool two_cores() { return parallel_parts(2, 1) >= 2; }
std::pair<Try, Try> attempt_two(BatchWorkers& workers, const std::vector<PackChart>& charts, double a, int side_a,
                                double b, int side_b, int pad, bool angles) {
  Try t[2];
  workers.run(2, [&](std::int64_t i) {
    t[i] = i == 0 ? attempt(charts, a, side_a, pad, angles, true) : attempt(charts, b, side_b, pad, angles, true);
  });
  return {std::move(t[0]), std::move(t[1])};
}

// The layouts tried so far: the one with the largest scale / extent (the
// utilization is the charts' area times its square), the largest scale that
// fitted and the smallest that did not. With two cores the next packing the
// sequential search would make is made beside the current one whenever it
// is known or likely (speculation), and its outcome counts only once the
// sequential search would have made it: the same packings decide in the same
// order, so the layout never depends on the cores.
struct Search {
  BatchWorkers& workers;
  const std::vector<PackChart>& charts;
  int side, pad;
  bool angles;  // try_scale with every pose angle
  Layout best;
  double lo = 0, hi = INFINITY;
  int packings = 0;
  bool two = two_cores();
  bool record(Try&& t) {
    ++packings;
    if (!t.ok) {
      hi = std::min(hi, t.scale);
      return false;
    }
    lo = std::max(lo, t.scale);
    if (best.extent == 0 || t.l.scale / t.l.extent > best.scale / best.extent) best = std::move(t.l);
    return true;
  }
  bool fits(double scale) { return record(attempt(charts, scale, side, pad, angles, false)); }
  // From `start` down by `step` until a scale fits, at most `tries` scales;
  // two at a time (the start is above what packs: the second is needed).
  bool bracket(double start, double step, int tries) {
    double s = start;
    for (int i = 0; i < tries;) {
      if (two && i + 1 < tries) {
        auto [a, b] = attempt_two(workers, charts, s, side, s * step, side, pad, angles);
        if (record(std::move(a)) || record(std::move(b))) return true;
        s *= step, s *= step, i += 2;
      } else {
        if (fits(s)) return true;
        s *= step, ++i;
      }
    }
    return false;
  }
  // Bisects [lo, hi] (geometric mean) until hi / lo is within `ratio`. With
  // two cores the midpoint is packed beside the next midpoint should it fit
  // (the first midpoint fitted on 12 of the 17 shared assets).
  void bisect(double ratio, int steps) {
    for (int i = 0; i < steps && hi > lo * ratio; ++i) {
      const double mid = std::sqrt(lo * hi);
      if (!two || i + 1 >= steps || !(hi > mid * ratio)) {
        fits(mid);
        continue;
      }
      auto [a, b] = attempt_two(workers, charts, mid, side, std::sqrt(mid * hi), side, pad, angles);
      if (record(std::move(a))) record(std::move(b)), ++i;
    }
  }
  // Above the largest scale the smallest-box poses reached, with every pose
  // angle: two steps of a bisection up to 8% higher (the angles are tried
  // only here, each costing a rasterization per angle: a layout the greedy
  // placement finds with more poses can also be worse, so they never
  // replace a better one).
  void with_angles() {
    bool more = false;
    for (const PackChart& c : charts) more = more || c.poses.size() > 1;
    if (!more || lo == 0) return;
    angles = true;
    double a = lo, b = lo * kAnglesRange;
    for (int i = 0; i < 2; ++i) {
      const double mid = std::sqrt(a * b);
      (fits(mid) ? a : b) = mid;
    }
  }
};

// Brackets from the largest scale the area allows, then bisects to
// `ratio`; the side doubles when even tiny scales fail (more charts than
// the bitmap holds with their padding).
Layout bisect_scale(BatchWorkers& workers, const std::vector<PackChart>& charts, double area, int& side, int pad,
                    double ratio, bool angles, double* largest = nullptr) {
  while (true) {
    Search s{workers, charts, side, pad, false, {}};
    if (s.bracket(kStartFill * side / std::sqrt(area), kBracketStep, kBracketTries)) {
      if (s.hi == INFINITY) s.hi = kStartFill * side / std::sqrt(area) / kBracketStep;
      s.bisect(ratio, kBisectSteps);
      if (angles) s.with_angles();
      if (largest) *largest = s.lo;
      return std::move(s.best);
    }
    side *= 2;
  }
}

}  // namespace

// The bisection on a bitmap of half the size first (a quarter of the texels
// to place, twice the tolerance). Its best layout, each cell taken as 2 x 2
// texels, is a valid layout of the full bitmap (padding rounded up to whole
// cells); the full bitmap is then tried only where it could beat it: down
// from 3% above twice the coarse scale in steps of 1.5% (the first of
// which is skipped, thresholds.h: kGuessTries), each packing on a bitmap
// just small enough that a layout fitting it has a larger scale / extent (a
// worse one fails early, once the placed charts pass that side); the first
// that fits, in order, is taken, the two tried at once on two cores.
// The searches packed the full bitmap 3-6 times before, each failure as
// costly as a success.
Layout search_layout(const std::vector<PackChart>& charts, double area, int& side, int pad) {
  BatchWorkers workers(two_cores() ? 2 : 1);
  if (side < kHalfBitmapMinSide) return bisect_scale(workers, charts, area, side, pad, kFineRatio, true);
  int half = side / 2;
  double coarse = 0;  // the largest scale that fitted (the best layout may be at a smaller one)
  Layout best = bisect_scale(workers, charts, area, half, (pad + 1) / 2, kCoarseRatio, false, &coarse);
  if (half != side / 2) return bisect_scale(workers, charts, area, side, pad, kFineRatio, true);
  // The half bitmap held them: its layout at twice the scale.
  best.scale *= 2, best.extent *= 2, best.zoom *= 2;
  const double guess = 2 * coarse;
  // The first step, kGuessAbove itself, fitted on none of the shared assets
  // (thresholds.h): the tries start one step below it.
  std::vector<double> scales(kGuessTries);
  double s = guess * kGuessAbove;
  for (double& t : scales) s /= kGuessStep, t = s;
  // Better than `best`: extent < s * best.extent / best.scale.
  auto limit = [&](double t) {
    return std::min(side, static_cast<int>(std::ceil(t * best.extent / best.scale)) - 1);
  };
  for (size_t i = 0; i < scales.size();) {
    if (two_cores() && i + 1 < scales.size()) {  // the first that fits, in order
      auto [a, b] =
          attempt_two(workers, charts, scales[i], limit(scales[i]), scales[i + 1], limit(scales[i + 1]), pad, false);
      if (a.ok) return std::move(a.l);
      if (b.ok) return std::move(b.l);
      i += 2;
    } else {
      Try t = attempt(charts, scales[i], limit(scales[i]), pad, false, false);
      if (t.ok) return std::move(t.l);
      ++i;
    }
  }
  return best;
}

}  // namespace intrinsic::detail::packing
