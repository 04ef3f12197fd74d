// Packing, step 2 (texel_mask.h): conservative rasterization of a chart's
// triangles, quarter turns of the texel grid, and the padding dilation.
#include "atlas/packing/texel_mask.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "atlas/thresholds.h"

namespace intrinsic::detail::packing {

Eigen::Vector2i cells_of(const MatrixX2d& UV, double scale) {
  if (UV.rows() == 0) return {1, 1};
  const Eigen::Vector2d size = UV.colwise().maxCoeff().transpose() * scale;
  return {std::max(1, static_cast<int>(std::ceil(size.x()))), std::max(1, static_cast<int>(std::ceil(size.y())))};
}

namespace {

// The x range of the triangle within the horizontal band [y0, y1]: the
// extremes over its vertices inside the band and its edges' crossings of the
// band's two lines (the part of a convex shape in a band is convex). False
// when the triangle misses the band.
bool band_range(const Eigen::Vector2d p[3], double y0, double y1, double& lo, double& hi) {
  lo = INFINITY, hi = -INFINITY;
  for (int e = 0; e < 3; ++e) {
    const Eigen::Vector2d a = p[e], b = p[(e + 1) % 3];
    if (a.y() >= y0 && a.y() <= y1) lo = std::min(lo, a.x()), hi = std::max(hi, a.x());
    for (double y : {y0, y1})
      if ((a.y() - y) * (b.y() - y) < 0) {
        const double x = a.x() + (b.x() - a.x()) * (y - a.y()) / (b.y() - a.y());
        lo = std::min(lo, x), hi = std::max(hi, x);
      }
  }
  return lo <= hi;
}

// The runs of 1s of a row of 0s and 1s, found with memchr (vectorized in
// libc): rows are mostly one or two long runs.
void runs_of(const char* row, int w, Spans& s, int offset = 0) {
  s.clear();
  const char* end = row + w;
  for (const char* p = row; p < end;) {
    const char* b = static_cast<const char*>(std::memchr(p, 1, end - p));
    if (!b) break;
    const char* e = static_cast<const char*>(std::memchr(b, 0, end - b));
    if (!e) e = end;
    s.emplace_back(static_cast<int>(b - row) + offset, static_cast<int>(e - row) + offset);
    p = e;
  }
}
Spans spans_of(const char* row, int w, int offset) {
  Spans s;
  runs_of(row, w, s, offset);
  return s;
}

// The largest rectangle of dilated texels: per row, the column heights of
// dilated texels ending there, and the largest rectangle under that
// histogram (a stack of rising heights).
std::array<int, 4> largest_rectangle(const Mask& m) {
  std::array<int, 4> best{0, 0, 0, 0};
  std::vector<int> height(m.w + 1, 0), stack;
  std::vector<char> row(m.w);
  for (int y = 0; y < m.h; ++y) {
    std::fill(row.begin(), row.end(), 0);
    for (const auto& s : m.rows[y]) std::fill(row.begin() + s.first, row.begin() + s.second, 1);
    for (int x = 0; x < m.w; ++x) height[x] = row[x] ? height[x] + 1 : 0;
    stack.clear();
    for (int x = 0; x <= m.w; ++x) {
      while (!stack.empty() && height[stack.back()] >= height[x]) {
        const int hgt = height[stack.back()];
        stack.pop_back();
        const int left = stack.empty() ? 0 : stack.back() + 1;
        if (static_cast<long>(hgt) * (x - left) > static_cast<long>(best[2]) * best[3])
          best = {left, y - hgt + 1, x - left, hgt};
      }
      stack.push_back(x);
    }
  }
  return best;
}

// The largest box of dilated texels, searched for in small masks only:
// large masks are few and their boxes say little.
std::array<int, 4> inner_box(const Mask& m) {
  if (m.box) return {0, 0, m.w, m.h};
  const bool small = static_cast<long>(m.w) * m.h <= kInnerBoxArea;
  return small ? largest_rectangle(m) : std::array<int, 4>{0, 0, 0, 0};
}

// The widest span per row, the rows by decreasing width, whether the
// dilated texels fill the frame, and (`inner`) the largest box inside them.
void index_rows(Mask& m, bool inner = true) {
  m.widest.assign(m.h, 0);
  m.box = true;
  for (int y = 0; y < m.h; ++y) {
    for (const auto& s : m.rows[y]) m.widest[y] = std::max(m.widest[y], s.second - s.first);
    m.box = m.box && m.widest[y] == m.w;
  }
  // A counting sort (widths are at most w): equal widths keep row order.
  std::vector<int> start(m.w + 2, 0);
  for (int y = 0; y < m.h; ++y) ++start[m.w - m.widest[y] + 1];
  for (int k = 1; k <= m.w + 1; ++k) start[k] += start[k - 1];
  m.by_width.resize(m.h);
  for (int y = 0; y < m.h; ++y) m.by_width[start[m.w - m.widest[y]]++] = y;
  m.inner = inner ? inner_box(m) : std::array<int, 4>{0, 0, 0, 0};
}

}  // namespace

std::vector<char> rasterize(const MatrixX3i& F, const MatrixX2d& UV, double scale) {
  const Eigen::Vector2i cells = cells_of(UV, scale);
  const int cw = cells.x(), ch = cells.y();
  std::vector<char> grid(static_cast<size_t>(cw) * ch, 0);
  for (int f = 0; f < F.rows(); ++f) {
    Eigen::Vector2d p[3];
    for (int c = 0; c < 3; ++c) p[c] = UV.row(F(f, c)).transpose() * scale;
    const double ylo = std::min({p[0].y(), p[1].y(), p[2].y()}), yhi = std::max({p[0].y(), p[1].y(), p[2].y()});
    const int y0 = std::clamp(static_cast<int>(std::floor(ylo)), 0, ch - 1);
    const int y1 = std::clamp(static_cast<int>(std::floor(yhi)), 0, ch - 1);
    for (int y = y0; y <= y1; ++y) {
      double lo = 0, hi = 0;
      if (!band_range(p, y, y + 1, lo, hi)) continue;
      // Every texel of the row the range touches (closed: a shared side counts).
      const int x0 = std::clamp(static_cast<int>(std::floor(lo)), 0, cw - 1);
      const int x1 = std::clamp(static_cast<int>(std::floor(hi)), 0, cw - 1);
      std::fill(grid.begin() + static_cast<long>(y) * cw + x0, grid.begin() + static_cast<long>(y) * cw + x1 + 1, 1);
    }
  }
  return grid;
}

std::vector<char> quarter_turn(const std::vector<char>& grid, int w, int h) {
  std::vector<char> turned(grid.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) turned[static_cast<size_t>(x) * h + (h - 1 - y)] = grid[static_cast<size_t>(y) * w + x];
  return turned;
}

// The dilation is separable (a square neighbourhood): each frame row is
// first the OR of the grid rows within `pad` (one pass of byte ORs, which
// the compiler vectorizes), then its spans are widened by `pad` on both
// sides and merged where they touch, left to right (no sort).
Mask mask_of(const std::vector<char>& grid, int w, int h, int pad, bool inner) {
  Mask m;
  m.w = w + 2 * pad, m.h = h + 2 * pad;
  m.own.resize(m.h);
  for (int y = 0; y < h; ++y) {
    m.own[y + pad] = spans_of(grid.data() + static_cast<long>(y) * w, w, pad);
    for (const auto& s : m.own[y + pad]) m.texels += s.second - s.first;
  }
  // Frame row y holds the grid rows y - 2 pad .. y (grid row g is frame row g + pad).
  std::vector<char> band(static_cast<size_t>(w) * m.h, 0);
  for (int g = 0; g < h; ++g) {
    if (m.own[g + pad].empty()) continue;
    const char* src = grid.data() + static_cast<long>(g) * w;
    for (int y = g; y <= g + 2 * pad; ++y) {
      char* dst = band.data() + static_cast<long>(y) * w;
      for (int x = 0; x < w; ++x) dst[x] |= src[x];
    }
  }
  m.rows.resize(m.h);
  Spans runs;  // one row's runs, reused: no allocation per row
  for (int y = 0; y < m.h; ++y) {
    Spans& out = m.rows[y];
    runs_of(band.data() + static_cast<long>(y) * w, w, runs);
    for (const auto& s : runs) {
      const int b = s.first, e = s.second + 2 * pad;  // the texels [b, e) of the grid widened, in frame columns
      if (!out.empty() && b <= out.back().second)
        out.back().second = std::max(out.back().second, e);
      else
        out.emplace_back(b, e);
    }
  }
  index_rows(m, inner);
  return m;
}

namespace {

// A span list mirrored in a row of width w: [a, b) -> [w - b, w - a), in order.
Spans mirrored(const Spans& row, int w) {
  Spans out(row.size());
  for (size_t i = 0; i < row.size(); ++i) out[row.size() - 1 - i] = {w - row[i].second, w - row[i].first};
  return out;
}

// The mask turned by half a turn: texel (x, y) of the frame goes to
// (w - 1 - x, h - 1 - y), two of quarter_turn's turns (the padding is the
// same on every side, so the frame turns onto itself). The spans are
// mirrored instead of the grid turned and rasterized again; its largest
// box is the turned box (a largest box of the turned texels).
Mask half_turned(const Mask& m) {
  Mask t;
  t.w = m.w, t.h = m.h, t.texels = m.texels, t.box = m.box;
  t.rows.resize(m.h), t.own.resize(m.h), t.widest.resize(m.h), t.by_width.resize(m.h);
  for (int y = 0; y < m.h; ++y) {
    t.rows[m.h - 1 - y] = mirrored(m.rows[y], m.w);
    t.own[m.h - 1 - y] = mirrored(m.own[y], m.w);
    t.widest[m.h - 1 - y] = m.widest[y];
  }
  // Rows by decreasing width as before (only the order of the tests in
  // Bitmap::may_fit, never its answer, depends on the order among equals).
  for (int i = 0; i < m.h; ++i) t.by_width[i] = m.h - 1 - m.by_width[i];
  const auto& b = m.inner;
  t.inner = {m.w - b[0] - b[2], m.h - b[1] - b[3], b[2], b[3]};
  if (b[2] == 0 || b[3] == 0) t.inner = b;
  return t;
}

}  // namespace

void fill_frame(Mask& m) {
  for (Spans& r : m.rows) r.assign(1, {0, m.w});
  index_rows(m);
}

// One rasterization and one quarter turn of the grid: turns 2 and 3 are
// turns 0 and 1 turned by half a turn (half_turned). A mask placed as its
// frame is filled before its largest box is searched for (the search, a
// pass over the frame's texels, found the whole frame then); the half turn
// of a filled mask is filled again, so its rows are listed as fill_frame
// lists them.
std::vector<Mask> quarter_turn_masks(const MatrixX3i& F, const MatrixX2d& UV, double scale, int pad,
                                     bool (*as_box)(const Mask&, int)) {
  const Eigen::Vector2i cells = cells_of(UV, scale);
  const int w = cells.x(), h = cells.y();
  const std::vector<char> grid = rasterize(F, UV, scale);
  std::vector<Mask> masks(4);
  masks[0] = mask_of(grid, w, h, pad, !as_box);
  masks[1] = mask_of(quarter_turn(grid, w, h), h, w, pad, !as_box);
  bool filled[2] = {false, false};
  for (int k = 0; k < 2 && as_box; ++k) {
    filled[k] = as_box(masks[k], pad);
    if (filled[k]) fill_frame(masks[k]);
    else masks[k].inner = inner_box(masks[k]);
  }
  masks[2] = half_turned(masks[0]);
  masks[3] = half_turned(masks[1]);
  for (int k = 0; k < 2; ++k)
    if (filled[k]) fill_frame(masks[k + 2]);
  return masks;
}

MatrixX2d texel_coordinates(const MatrixX2d& UV, double scale, int turns) {
  MatrixX2d T = UV * scale;
  Eigen::Vector2i cells = cells_of(UV, scale);
  for (int k = 0; k < turns; ++k) {
    const Eigen::VectorXd x = T.col(0);
    T.col(0) = cells.y() - T.col(1).array();
    T.col(1) = x;
    cells = Eigen::Vector2i(cells.y(), cells.x());
  }
  return T;
}

}  // namespace intrinsic::detail::packing
