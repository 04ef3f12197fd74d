// Packing, step 2 (texel_mask.h): conservative rasterization of a chart's
// triangles, quarter turns of the texel grid, and the padding dilation.
#include "atlas/packing/texel_mask.h"

#include <algorithm>
#include <cmath>
#include <numeric>

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

Spans spans_of(const char* row, int w, int offset) {
  Spans s;
  for (int x = 0; x < w;) {
    if (!row[x]) {
      ++x;
      continue;
    }
    const int b = x;
    while (x < w && row[x]) ++x;
    s.emplace_back(b + offset, x + offset);
  }
  return s;
}

// The union of sorted-by-begin spans, merged where they touch or overlap.
Spans merged(Spans window) {
  std::sort(window.begin(), window.end());
  Spans out;
  for (const auto& s : window)
    if (!out.empty() && s.first <= out.back().second)
      out.back().second = std::max(out.back().second, s.second);
    else
      out.push_back(s);
  return out;
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

// The widest span per row, the rows by decreasing width, whether the
// dilated texels fill the frame, and the largest box inside them.
void index_rows(Mask& m) {
  m.widest.assign(m.h, 0);
  m.box = true;
  for (int y = 0; y < m.h; ++y) {
    for (const auto& s : m.rows[y]) m.widest[y] = std::max(m.widest[y], s.second - s.first);
    m.box = m.box && m.widest[y] == m.w;
  }
  m.by_width.resize(m.h);
  std::iota(m.by_width.begin(), m.by_width.end(), 0);
  std::stable_sort(m.by_width.begin(), m.by_width.end(), [&](int a, int b) { return m.widest[a] > m.widest[b]; });
  // Large masks are few and their boxes say little: no search for theirs.
  const bool small = static_cast<long>(m.w) * m.h <= kInnerBoxArea;
  m.inner = m.box ? std::array<int, 4>{0, 0, m.w, m.h} : small ? largest_rectangle(m) : std::array<int, 4>{0, 0, 0, 0};
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

Mask mask_of(const std::vector<char>& grid, int w, int h, int pad) {
  Mask m;
  m.w = w + 2 * pad, m.h = h + 2 * pad;
  m.own.resize(m.h);
  for (int y = 0; y < h; ++y) {
    m.own[y + pad] = spans_of(grid.data() + static_cast<long>(y) * w, w, pad);
    for (const auto& s : m.own[y + pad]) m.texels += s.second - s.first;
  }
  // Each dilated row is the union of the own rows within `pad`, every span
  // widened by `pad` on both sides.
  m.rows.resize(m.h);
  Spans window;
  for (int y = 0; y < m.h; ++y) {
    window.clear();
    for (int k = std::max(0, y - pad); k <= std::min(m.h - 1, y + pad); ++k)
      for (const auto& s : m.own[k]) window.emplace_back(std::max(0, s.first - pad), std::min(m.w, s.second + pad));
    m.rows[y] = merged(window);
  }
  index_rows(m);
  return m;
}

void fill_frame(Mask& m) {
  for (Spans& r : m.rows) r.assign(1, {0, m.w});
  index_rows(m);
}

std::vector<Mask> quarter_turn_masks(const MatrixX3i& F, const MatrixX2d& UV, double scale, int pad) {
  const Eigen::Vector2i cells = cells_of(UV, scale);
  int w = cells.x(), h = cells.y();
  std::vector<char> grid = rasterize(F, UV, scale);
  std::vector<Mask> masks(4);
  masks[0] = mask_of(grid, w, h, pad);
  for (int k = 1; k < 4; ++k) {
    grid = quarter_turn(grid, w, h);
    std::swap(w, h);
    masks[k] = mask_of(grid, w, h, pad);
  }
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
