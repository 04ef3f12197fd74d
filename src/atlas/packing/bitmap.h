// Packing, step 3: the layout's occupancy, one bit per texel, and the search
// for the first position in a row band where a mask fits. A fit is tested
// span by span: a dilated span meeting a taken texel tells how far right the
// mask must move at least (past that texel), so a scan jumps over whole
// charts instead of trying every x. Each row also keeps its widest free run:
// a band where some row of the mask is wider than its row's widest run is
// skipped without a scan (most bands, once the layout is dense).
#pragma once

#include <cstdint>
#include <vector>

#include "atlas/packing/texel_mask.h"

namespace intrinsic::detail::packing {

class Bitmap {
 public:
  explicit Bitmap(int side);
  int side() const { return side_; }
  // The last taken texel of row y in [a, b), or -1. Inline, with the
  // masks of the two end words built once: the scans call it for every
  // span of every position they test (half the packer's instructions).
  int last_taken(int y, int a, int b) const {
    if (a >= b) return -1;
    const std::uint64_t* r = row(y);
    const int first = a >> 6;
    int w = (b - 1) >> 6;
    std::uint64_t word = r[w] & (~std::uint64_t{0} >> (63 - ((b - 1) & 63)));  // bits up to b - 1
    if (w == first) word &= ~std::uint64_t{0} << (a & 63);
    while (true) {
      if (word) return (w << 6) + 63 - __builtin_clzll(word);
      if (--w < first) return -1;
      word = w == first ? r[w] & (~std::uint64_t{0} << (a & 63)) : r[w];
    }
  }
  bool taken(int x, int y) const { return (row(y)[x >> 6] >> (x & 63)) & 1; }
  // Takes the mask's own (undilated) texels with its frame's corner at (x, y).
  void take(const Mask& m, int x, int y);
  // True when the mask's dilated texels, frame corner at (x, y), meet no taken texel.
  bool fits(const Mask& m, int x, int y) const;
  // The first x >= x0 with the frame inside [0, limit) where the mask fits
  // in the band of rows starting at y, or -1.
  int first_fit(const Mask& m, int y, int x0, int limit) const;
  // False when some row of the mask's band at y is wider than its row's
  // widest free run (`inside`: the run within the extent, see set_extent):
  // the mask fits nowhere in that band (inside the extent).
  bool may_fit(const Mask& m, int y, bool inside = false) const;
  // The widest run of free texels in row y.
  int widest_free(int y) const { return widest_[y]; }
  // The square [0, e)^2 a search inside the extent looks at: each row's
  // widest free run within [0, e) is kept as well. The runs over the whole
  // row tell almost nothing while the layout is smaller than the bitmap
  // (the free room right of it passes every mask), so the search inside
  // scanned every row with first_fit. Called before the texels past the
  // old extent are taken.
  void set_extent(int e);

 private:
  const std::uint64_t* row(int y) const { return &bits_[static_cast<size_t>(y) * words_]; }
  // The widest free run of row y within [0, n).
  int widest_run(int y, int n) const;
  void update_widest(int y);
  int side_ = 0, words_ = 0, extent_ = 0;
  std::vector<std::uint64_t> bits_;
  std::vector<int> widest_, inside_;
};

}  // namespace intrinsic::detail::packing
