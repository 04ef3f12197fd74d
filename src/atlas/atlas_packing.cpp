// Packing: every chart already has UV area = 3D area
// (one texel density for all); each is turned to its smallest bounding box
// (whose side lies on a convex hull edge). The charts are then packed by
// rasterization, as xatlas does: each chart's texel mask (every texel its
// triangles touch) is placed, largest first, at the position of a
// `resolution`-wide bitmap that keeps the layout's square smallest (in any
// of its four quarter turns: an L or C shape can then wrap another), where
// its mask dilated by `padding` texels meets no texel already taken. The scale (texels per unit of surface) is the largest
// for which every chart fits, found by bisection; the layout is then fitted
// into [0,1]^2 by one similarity. Boxes alone (a skyline of rectangles) left
// a third of the square empty on the assets; masks let small charts sit in
// the concave parts of large ones.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "atlas/atlas_internal.h"
#include "util/parallel_for.h"

namespace intrinsic::detail {
namespace {

// Andrew's monotone chain; counter-clockwise, no repeated point.
std::vector<Eigen::Vector2d> convex_hull(const MatrixX2d& UV) {
  std::vector<Eigen::Vector2d> p(UV.rows());
  for (int i = 0; i < UV.rows(); ++i) p[i] = UV.row(i).transpose();
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (p.size() < 3) return p;
  std::vector<Eigen::Vector2d> h(2 * p.size());
  size_t k = 0;
  auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

// The angle that turns UV to its smallest axis-aligned box; `area` gets that box's area.
double smallest_box_angle(const MatrixX2d& UV, double& best_area) {
  const std::vector<Eigen::Vector2d> hull = convex_hull(UV);
  best_area = INFINITY;
  double best_angle = 0;
  for (size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d e = hull[(i + 1) % hull.size()] - hull[i];
    if (e.norm() == 0) continue;
    const double a = -std::atan2(e.y(), e.x());
    const Eigen::Rotation2Dd R(a);
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(INFINITY), hi = -lo;
    for (const Eigen::Vector2d& q : hull) lo = lo.cwiseMin(R * q), hi = hi.cwiseMax(R * q);
    const double area = (hi - lo).prod();
    if (area < best_area * (1 - 1e-12)) best_area = area, best_angle = a;
  }
  return best_angle;
}

// Rotates the chart to its smallest box (then wider than tall) and moves its corner to the origin.
void orient_chart(FlatChart& chart) {
  double best_area = 0;
  const double best_angle = smallest_box_angle(chart.UV, best_area);
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(best_angle).toRotationMatrix();
  chart.UV = chart.UV * R.transpose();
  if (!chart.UV.allFinite()) chart.UV.setZero();
  chart.UV.rowwise() -= chart.UV.colwise().minCoeff();
}

// The chart's size in whole texels at `scale` (its corner at the origin).
Eigen::Vector2i cells_of(const MatrixX2d& UV, double scale) {
  const Eigen::Vector2d size = UV.colwise().maxCoeff().transpose() * scale;
  return {std::max(1, static_cast<int>(std::ceil(size.x()))), std::max(1, static_cast<int>(std::ceil(size.y())))};
}

// The chart (turned to its box, corner at the origin) in texels at `scale`
// after `turns` quarter turns counter-clockwise (orientation kept), each turn
// (x, y) -> (h - y, x) with h the texel height of the grid before it: the
// texel grid turns onto itself, so the masks of the turned poses are the
// first pose's mask turned (rasterized once).
MatrixX2d texel_pose(const MatrixX2d& UV, double scale, int turns) {
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

// Texel spans of one row: [begin, end) pairs, sorted, disjoint.
using Spans = std::vector<std::pair<int, int>>;

// A chart rasterized at one scale: the texels its triangles touch, and the
// same dilated by the padding (in the same frame, which starts `pad` texels
// left of and below the chart's own texels).
struct Mask {
  int w = 0, h = 0;            // size of the dilated frame
  std::vector<Spans> rows;     // dilated, per row of the frame
  std::vector<Spans> own;      // undilated, per row of the frame
  long texels = 0;             // undilated
};

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

Spans spans_of(const std::vector<char>& row) {
  Spans s;
  for (int x = 0; x < static_cast<int>(row.size());) {
    if (!row[x]) {
      ++x;
      continue;
    }
    const int b = x;
    while (x < static_cast<int>(row.size()) && row[x]) ++x;
    s.emplace_back(b, x);
  }
  return s;
}

// The mask of an own-texel grid (w x h, row-major) with the frame and the
// dilation by `pad`.
Mask mask_of(const std::vector<char>& own, int w, int h, int pad) {
  Mask m;
  m.w = w + 2 * pad, m.h = h + 2 * pad;
  m.own.resize(m.h);
  std::vector<char> row(m.w, 0);
  for (int y = 0; y < h; ++y) {
    std::copy(own.begin() + static_cast<long>(y) * w, own.begin() + static_cast<long>(y + 1) * w, row.begin() + pad);
    m.own[y + pad] = spans_of(row);
    for (const auto& s : m.own[y + pad]) m.texels += s.second - s.first;
  }
  // Chebyshev dilation by `pad`: each row is the union of the rows within
  // `pad`, every span widened by `pad` on both sides.
  m.rows.resize(m.h);
  Spans window;
  for (int y = 0; y < m.h; ++y) {
    window.clear();
    for (int k = std::max(0, y - pad); k <= std::min(m.h - 1, y + pad); ++k)
      for (const auto& s : m.own[k]) window.emplace_back(std::max(0, s.first - pad), std::min(m.w, s.second + pad));
    std::sort(window.begin(), window.end());
    for (const auto& s : window)
      if (!m.rows[y].empty() && s.first <= m.rows[y].back().second)
        m.rows[y].back().second = std::max(m.rows[y].back().second, s.second);
      else
        m.rows[y].push_back(s);
  }
  return m;
}

// Rasterizes UV (corner at the origin) at `scale` texels per unit, in its
// four quarter turns (texel_pose).
std::array<Mask, 4> rasterize(const FlatChart& chart, const MatrixX2d& UV, double scale, int pad) {
  const Eigen::Vector2i cells = cells_of(UV, scale);
  int cw = cells.x(), ch = cells.y();
  std::vector<char> grid(static_cast<size_t>(cw) * ch, 0);
  const MatrixX3i& F = chart.mesh.data.F;
  for (int f = 0; f < F.rows(); ++f) {
    Eigen::Vector2d p[3];
    for (int c = 0; c < 3; ++c) p[c] = UV.row(F(f, c)).transpose() * scale;
    const double ylo = std::min({p[0].y(), p[1].y(), p[2].y()}), yhi = std::max({p[0].y(), p[1].y(), p[2].y()});
    const int y0 = std::clamp(static_cast<int>(std::floor(ylo)), 0, ch - 1), y1 = std::clamp(static_cast<int>(std::floor(yhi)), 0, ch - 1);
    for (int y = y0; y <= y1; ++y) {
      double lo = 0, hi = 0;
      if (!band_range(p, y, y + 1, lo, hi)) continue;
      // Every texel of the row the range touches (closed: a shared side counts).
      const int x0 = std::clamp(static_cast<int>(std::floor(lo)), 0, cw - 1), x1 = std::clamp(static_cast<int>(std::floor(hi)), 0, cw - 1);
      std::fill(grid.begin() + static_cast<long>(y) * cw + x0, grid.begin() + static_cast<long>(y) * cw + x1 + 1, 1);
    }
  }
  std::array<Mask, 4> masks;
  masks[0] = mask_of(grid, cw, ch, pad);
  for (int k = 1; k < 4; ++k) {
    // A quarter turn of the closed texels: texel (x, y) -> (ch - 1 - y, x).
    std::vector<char> turned(grid.size());
    for (int y = 0; y < ch; ++y)
      for (int x = 0; x < cw; ++x) turned[static_cast<size_t>(x) * ch + (ch - 1 - y)] = grid[static_cast<size_t>(y) * cw + x];
    grid.swap(turned);
    std::swap(cw, ch);
    masks[k] = mask_of(grid, cw, ch, pad);
  }
  return masks;
}

// The occupied texels of the layout, one bit each, rows of 64-bit words.
struct Bitmap {
  int side = 0, words = 0;
  std::vector<std::uint64_t> bits;
  explicit Bitmap(int s) : side(s), words((s + 63) / 64), bits(static_cast<size_t>(words) * s, 0) {}
  // The last taken texel of row y in [a, b), or -1.
  int last_taken(int y, int a, int b) const {
    const std::uint64_t* r = &bits[static_cast<size_t>(y) * words];
    for (int x = b - 1; x >= a;) {
      const int w = x >> 6;
      std::uint64_t word = r[w];
      const int hi = x & 63;
      if (hi < 63) word &= (std::uint64_t{2} << hi) - 1;
      const int lo_bit = std::max(a, w << 6) - (w << 6);
      word &= ~((std::uint64_t{1} << lo_bit) - 1);
      if (word) return (w << 6) + 63 - __builtin_clzll(word);
      x = (w << 6) - 1;
    }
    return -1;
  }
  void take(int y, int a, int b) {
    std::uint64_t* r = &bits[static_cast<size_t>(y) * words];
    for (int x = a; x < b; ++x) r[x >> 6] |= std::uint64_t{1} << (x & 63);
  }
};

// The first x >= x0 in row band y where the mask's dilated texels meet no
// taken texel (the mask's frame inside [0, limit)), or -1.
int first_fit(const Bitmap& bm, const Mask& m, int y, int x0, int limit) {
  int hot = 0;  // the row that last met a taken texel: tried first, it usually does again
  for (int x = x0; x + m.w <= limit;) {
    int next = -1;
    for (int i = 0; i < m.h && next < 0; ++i) {
      const int r = (hot + i) % m.h;
      for (const auto& s : m.rows[r]) {
        const int t = bm.last_taken(y + r, x + s.first, x + s.second);
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

struct Placement {
  int x = -1, y = -1;
  int turns = 0;  // quarter turns counter-clockwise
};

// Places each chart (largest mask first) where the square the layout needs
// grows least; false when one does not fit in the bitmap.
bool place_all(const std::vector<std::array<Mask, 4>>& masks, const std::vector<int>& order, int side,
               std::vector<Placement>& at, int& extent) {
  Bitmap bm(side);
  at.assign(masks.size(), {});
  extent = 0;
  for (int c : order) {
    Placement best;
    int best_extent = INT32_MAX;
    // No placement needs a smaller square than this: stop when one reaches it.
    const int floor = std::max({extent, masks[c][0].w, masks[c][0].h});
    for (int turn = 0; turn < 4 && best_extent > floor; ++turn) {
      const Mask& m = masks[c][turn];
      for (int y = 0; y + m.h <= side && std::max(extent, y + m.h) < best_extent && best_extent > floor; ++y) {
        // Only positions that would beat the best so far: x + w < best_extent.
        const int x = first_fit(bm, m, y, 0, std::min<long>(side, static_cast<long>(best_extent) - 1));
        if (x < 0) continue;
        const int e = std::max({extent, x + m.w, y + m.h});
        if (e < best_extent) best_extent = e, best = {x, y, turn};
      }
    }
    if (best.x < 0) return false;
    const Mask& m = masks[c][best.turns];
    for (int r = 0; r < m.h; ++r)
      for (const auto& s : m.own[r]) bm.take(best.y + r, best.x + s.first, best.x + s.second);
    at[c] = best;
    extent = best_extent;
  }
  return true;
}

}  // namespace

namespace {

// The smallest box of the points UV and the fraction `area` fills of it.
ChartBox box_of(const MatrixX2d& UV, double area) {
  double box = 0;
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(smallest_box_angle(UV, box)).toRotationMatrix();
  const MatrixX2d turned = UV * R.transpose();
  const Eigen::Vector2d size = turned.colwise().maxCoeff() - turned.colwise().minCoeff();
  ChartBox b;
  b.longer = size.maxCoeff(), b.shorter = size.minCoeff();
  b.fill = b.longer * b.shorter > 0 ? area / (b.longer * b.shorter) : 1;
  return b;
}

}  // namespace

ChartBox chart_box(const FlatChart& chart) { return box_of(chart.UV, chart.summary.area_3d); }

ChartBox planar_chart_box(const ChartMesh& chart) {
  const MatrixX3d& V = chart.data.V;
  const MatrixX3i& F = chart.data.F;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double area = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d n = (V.row(F(f, 1)) - V.row(F(f, 0))).cross(V.row(F(f, 2)) - V.row(F(f, 0)));
    normal += n, area += n.norm() / 2;
  }
  if (!(normal.norm() > 0)) return {};
  normal.normalize();
  const Eigen::Vector3d u = normal.unitOrthogonal(), v = normal.cross(u);
  MatrixX2d P(V.rows(), 2);
  P.col(0) = V * u;
  P.col(1) = V * v;
  return box_of(P, area);
}

bool packs_well(const ChartBox& box, double surface_area) {
  const double square_fill = box.fill * box.shorter / box.longer;  // of the square on the longer side
  return box.fill >= 0.15 && (square_fill >= 0.15 || box.fill >= 0.5) &&
         box.longer * box.longer <= 4 * surface_area;
}

namespace {

// Every chart's mask at `scale` in its four quarter turns, rasterized in parallel.
std::vector<std::array<Mask, 4>> rasterize_all(const std::vector<FlatChart>& charts, double scale, int pad) {
  std::vector<std::array<Mask, 4>> masks(charts.size());
  parallel_for(static_cast<std::int64_t>(charts.size()), [&](std::int64_t b, std::int64_t e) {
    for (std::int64_t c = b; c < e; ++c) {
      masks[c] = rasterize(charts[c], charts[c].UV, scale, pad);
    }
  }, 8);
  return masks;
}

struct Layout {
  double scale = 0;
  int extent = 0;
  std::vector<Placement> at;
};

// Packs at `scale` into a `side`-texel square; false when a chart does not fit.
bool try_scale(const std::vector<FlatChart>& charts, double scale, int side,
               int pad, Layout& out) {
  const std::vector<std::array<Mask, 4>> masks = rasterize_all(charts, scale, pad);
  std::vector<int> order(charts.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const long ha = std::max(masks[a][0].w, masks[a][0].h), hb = std::max(masks[b][0].w, masks[b][0].h);
    return masks[a][0].texels != masks[b][0].texels ? masks[a][0].texels > masks[b][0].texels : ha > hb;
  });
  Layout l;
  l.scale = scale;
  if (!place_all(masks, order, side, l.at, l.extent)) return false;
  out = std::move(l);
  return true;
}

// The largest scale (texels per unit of surface) at which every chart fits:
// shrink until one fits, then bisect between the fitting and the failing scale.
Layout best_layout(const std::vector<FlatChart>& charts, double area,
                   int& side, int pad) {
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
    side *= 2;  // more charts than the bitmap holds with their padding: a larger bitmap
  }
}

// The bisection on a bitmap of half the size first (a quarter of the
// texels to place), then the full bitmap from just above that scale down in
// small steps: a few full-size packings instead of a dozen.
Layout search_layout(const std::vector<FlatChart>& charts, double area,
                     int& side, int pad) {
  if (side < 256) return best_layout(charts, area, side, pad);
  int half = side / 2;
  const Layout coarse = best_layout(charts, area, half, (pad + 1) / 2);
  if (half == side / 2) {  // the half bitmap held them: its scale, doubled, is close
    double s = coarse.scale * 2 * 1.03;
    for (int i = 0; i < 6; ++i, s *= 0.985) {
      Layout l;
      if (try_scale(charts, s, side, pad, l)) return l;
    }
  }
  return best_layout(charts, area, side, pad);
}

}  // namespace

double pack_charts(std::vector<FlatChart>& charts, const AtlasOptions& options, int& overlapping) {
  overlapping = 0;
  if (charts.empty()) return 0;
  double area = 0;
  for (size_t c = 0; c < charts.size(); ++c) {
    orient_chart(charts[c]);
    area += charts[c].summary.area_3d;
  }
  // The bitmap is at most 1024 texels wide: larger textures pack on a coarser
  // grid (padding rounded up to whole cells of it).
  int side = std::min(options.resolution, 1024);
  const int pad = static_cast<int>(std::ceil(options.padding * side / options.resolution - 1e-9));
  // Half the padding (rounded up) around the border, as a neighbour's half
  // would complete it: the bitmap reaches `edge` texels past the square on
  // every side, where nothing is ever taken but dilated masks may lie.
  const int edge = pad - (pad + 1) / 2;
  int bitmap = side + 2 * edge;
  const Layout l = search_layout(charts, std::max(area, 1e-300), bitmap, pad);
  const double square = l.extent - 2 * edge;  // texels; the layout is [edge, extent - edge] of the bitmap
  for (size_t c = 0; c < charts.size(); ++c) {
    const Placement& p = l.at[c];
    charts[c].UV = texel_pose(charts[c].UV, l.scale, p.turns);
    charts[c].summary.rotated = p.turns != 0;
    charts[c].UV.col(0).array() += p.x + pad - edge;
    charts[c].UV.col(1).array() += p.y + pad - edge;
    charts[c].UV /= square;
    charts[c].UV = charts[c].UV.cwiseMax(0.0).cwiseMin(1.0);  // rounding only
  }
  const double used = l.scale / square;
  return area * used * used;
}

}  // namespace intrinsic::detail
