// The raster of the new layout for the texel transfer: which triangle each
// texel centre (and each sub-sample) belongs to, with its barycentric
// coordinates. Work is in texel space (u * W, v * H), where texel centres
// sit at half-integers. A point inside several triangles (only on shared
// edges of a valid layout) keeps the one it is deepest in, ties to the lower
// face index; a point outside every triangle but within `margin` texels of
// one takes the nearest point of the nearest triangle, so texels partly
// covered by a chart get the chart's colour rather than background
// (docs/maths.md "Texture transfer").
#include <algorithm>
#include <cmath>
#include <limits>

#include "texture/texture_internal.h"

namespace intrinsic::detail {
namespace {

// A texel centre is filled when within half a texel of a triangle (it is
// then at least partly covered). A sub-sample counts only inside a triangle:
// outside, the texel's centre sample stands in for it (transfer.cpp), so a
// sub-sample never reaches across a gap into a neighbouring chart.
constexpr double kCentreMargin = 0.5;
constexpr double kSubMargin = 0;

struct Tri {
  Eigen::Vector2d p[3];
  double area2;       // twice the signed area
  double inv_len[3];  // 1 / length of the edge opposite corner k
};

// Barycentric coordinates of the point of triangle `t` nearest to q
// (Ericson, Real-Time Collision Detection 5.1.5, in 2D).
void nearest_barycentric(const Tri& t, const Eigen::Vector2d& q, double b[3]) {
  const Eigen::Vector2d &a = t.p[0], &bb = t.p[1], &c = t.p[2];
  const Eigen::Vector2d ab = bb - a, ac = c - a, ap = q - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  auto set = [b](double x, double y, double z) { b[0] = x, b[1] = y, b[2] = z; };
  if (d1 <= 0 && d2 <= 0) return set(1, 0, 0);
  const Eigen::Vector2d bp = q - bb;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return set(0, 1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return set(1 - v, v, 0);
  }
  const Eigen::Vector2d cp = q - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return set(0, 0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return set(1 - w, 0, w);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return set(0, 1 - w, w);
  }
  const double denom = 1 / (va + vb + vc);
  set(va * denom, vb * denom, vc * denom);
}

// Rasterizes one triangle into a grid of samples at ((x + 0.5) / scale,
// (y + 0.5) / scale) for grid rows [gy0, gy1): each sample keeps the face
// with the lowest score (how far outside, in texels; negative inside).
void raster_tri(const Tri& t, int face, int scale, int grid_w, int gy0, int gy1, double margin,
                std::vector<RasterSample>& out, std::vector<float>& score) {
  const double lo_x = std::min({t.p[0].x(), t.p[1].x(), t.p[2].x()}) - margin;
  const double hi_x = std::max({t.p[0].x(), t.p[1].x(), t.p[2].x()}) + margin;
  const double lo_y = std::min({t.p[0].y(), t.p[1].y(), t.p[2].y()}) - margin;
  const double hi_y = std::max({t.p[0].y(), t.p[1].y(), t.p[2].y()}) + margin;
  // Grid index i has position (i + 0.5) / scale.
  const int x0 = std::max(0, static_cast<int>(std::ceil(lo_x * scale - 0.5)));
  const int x1 = std::min(grid_w - 1, static_cast<int>(std::floor(hi_x * scale - 0.5)));
  const int y0 = std::max(gy0, static_cast<int>(std::ceil(lo_y * scale - 0.5)));
  const int y1 = std::min(gy1 - 1, static_cast<int>(std::floor(hi_y * scale - 0.5)));
  const double sign = t.area2 > 0 ? 1 : -1;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const Eigen::Vector2d q((x + 0.5) / scale, (y + 0.5) / scale);
      double bary[3], s = -std::numeric_limits<double>::infinity();
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d& a = t.p[(k + 1) % 3];
        const Eigen::Vector2d e = t.p[(k + 2) % 3] - a, d = q - a;
        const double cr = e.x() * d.y() - e.y() * d.x();  // area2 * b_k
        bary[k] = cr / t.area2;
        s = std::max(s, -sign * cr * t.inv_len[k]);  // distance outside edge k
      }
      if (s > margin) continue;
      const std::size_t i = static_cast<std::size_t>(y - gy0) * grid_w + x;
      if (!(s < score[i])) continue;
      score[i] = static_cast<float>(s);
      RasterSample& r = out[i];
      r.face = face;
      if (s <= 0) {
        std::copy(bary, bary + 3, r.b);
      } else {
        nearest_barycentric(t, q, r.b);
      }
    }
}

}  // namespace

RasterBand rasterize_band(const Eigen::MatrixX2d& new_uv, const std::vector<int>& faces, int width, int height,
                          int row0, int row1, int ss) {
  RasterBand band;
  const std::size_t n_centre = static_cast<std::size_t>(row1 - row0) * width;
  band.centre.assign(n_centre, RasterSample{});
  std::vector<float> centre_score(n_centre, std::numeric_limits<float>::infinity());
  std::vector<float> sub_score;
  if (ss > 1) {
    band.sub.assign(n_centre * ss * ss, RasterSample{});
    sub_score.assign(band.sub.size(), std::numeric_limits<float>::infinity());
  }
  for (int f : faces) {
    Tri t;
    for (int k = 0; k < 3; ++k) t.p[k] = Eigen::Vector2d(new_uv(3 * f + k, 0) * width, new_uv(3 * f + k, 1) * height);
    t.area2 = (t.p[1] - t.p[0]).x() * (t.p[2] - t.p[0]).y() - (t.p[1] - t.p[0]).y() * (t.p[2] - t.p[0]).x();
    if (!(std::abs(t.area2) > 1e-12)) continue;  // covers no texel
    for (int k = 0; k < 3; ++k) t.inv_len[k] = 1 / (t.p[(k + 2) % 3] - t.p[(k + 1) % 3]).norm();
    raster_tri(t, f, 1, width, row0, row1, kCentreMargin, band.centre, centre_score);
    if (ss > 1) raster_tri(t, f, ss, width * ss, row0 * ss, row1 * ss, kSubMargin, band.sub, sub_score);
  }
  band.inside.resize(n_centre);
  for (std::size_t i = 0; i < n_centre; ++i) band.inside[i] = centre_score[i] <= 0;
  return band;
}

}  // namespace intrinsic::detail
