// Packing, step 3 (bitmap.h): occupancy bits and the first-fit scan.
#include "atlas/packing/bitmap.h"

#include <algorithm>

namespace intrinsic::detail::packing {

Bitmap::Bitmap(int side)
    : side_(side), words_((side + 63) / 64), bits_(static_cast<size_t>(words_) * side, 0), widest_(side, side), inside_(side, 0) {}

namespace {

// The longest run of set bits in x.
int longest_ones(std::uint64_t x) {
  int k = 0;
  for (; x; ++k) x &= x << 1;
  return k;
}

}  // namespace

// Word by word: a free run grows across zero words, ends at a word's lowest
// taken bit and restarts after its highest; runs inside a word are counted too.
int Bitmap::widest_run(int y, int n) const {
  const std::uint64_t* r = row(y);
  int best = 0, run = 0;
  for (int w = 0; w < (n + 63) / 64; ++w) {
    std::uint64_t word = r[w];
    const int valid = std::min(64, n - 64 * w);
    if (valid < 64) word |= ~std::uint64_t{0} << valid;  // past n: taken
    if (word == 0) {
      run += 64;
      continue;
    }
    best = std::max(best, run + __builtin_ctzll(word));
    // A run inside the word is at most its free bits: counted only when
    // that could beat the best (the count loops once per bit of the run).
    if (__builtin_popcountll(~word) > best) best = std::max(best, longest_ones(~word));
    run = __builtin_clzll(word);
  }
  return std::max(best, run);
}

void Bitmap::update_widest(int y) {
  widest_[y] = widest_run(y, side_);
  if (y < extent_) inside_[y] = widest_run(y, extent_);
}

// Nothing is taken outside the old extent's square: a row's run within the
// new extent is its old one or its free run ending at the old extent,
// lengthened by the columns added (rows above the old extent are all free).
void Bitmap::set_extent(int e) {
  e = std::min(e, side_);
  if (e < extent_) {
    extent_ = e;
    for (int y = 0; y < extent_; ++y) inside_[y] = widest_run(y, extent_);
    return;
  }
  for (int y = 0; y < extent_; ++y)
    inside_[y] = std::max(inside_[y], extent_ - 1 - last_taken(y, 0, extent_) + (e - extent_));
  for (int y = extent_; y < e; ++y) inside_[y] = e;
  extent_ = e;
}

namespace {

// Sets the bits [a, b) of a row, a word at a time (a span of a large chart
// covers hundreds of texels; bit by bit, taking was a fifth of the placement).
void set_bits(std::uint64_t* bits, int a, int b) {
  if (a >= b) return;
  const int first = a >> 6, last = (b - 1) >> 6;
  const std::uint64_t lo = ~std::uint64_t{0} << (a & 63), hi = ~std::uint64_t{0} >> (63 - ((b - 1) & 63));
  if (first == last) {
    bits[first] |= lo & hi;
    return;
  }
  bits[first] |= lo;
  for (int w = first + 1; w < last; ++w) bits[w] = ~std::uint64_t{0};
  bits[last] |= hi;
}

}  // namespace

void Bitmap::take(const Mask& m, int x, int y) {
  for (int r = 0; r < m.h; ++r) {
    std::uint64_t* bits = &bits_[static_cast<size_t>(y + r) * words_];
    for (const auto& s : m.own[r]) set_bits(bits, x + s.first, x + s.second);
    if (!m.own[r].empty()) update_widest(y + r);
  }
}

bool Bitmap::fits(const Mask& m, int x, int y) const {
  for (int r = 0; r < m.h; ++r)
    for (const auto& s : m.rows[r])
      if (last_taken(y + r, x + s.first, x + s.second) >= 0) return false;
  return true;
}

bool Bitmap::may_fit(const Mask& m, int y, bool inside) const {
  const int* widest = inside ? inside_.data() : widest_.data();
  for (int r : m.by_width)  // widest first: the likeliest to fail
    if (m.widest[r] > widest[y + r]) return false;
  return true;
}

int Bitmap::first_fit(const Mask& m, int y, int x0, int limit) const {
  // The row that last met a taken texel, tried first (it usually does
  // again); at first the widest row, the likeliest to meet one.
  int hot = m.by_width.empty() ? 0 : m.by_width[0];
  for (int x = x0; x + m.w <= limit;) {
    int next = -1;
    for (int i = 0; i < m.h && next < 0; ++i) {
      const int r = hot + i < m.h ? hot + i : hot + i - m.h;
      for (const auto& s : m.rows[r]) {
        const int t = last_taken(y + r, x + s.first, x + s.second);
        if (t >= 0) {
          next = t - s.first + 1, hot = r;
          break;
        }
      }
    }
    if (next < 0) return x;
    x = next;
  }
  return -1;
}

}  // namespace intrinsic::detail::packing
