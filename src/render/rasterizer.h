// Triangle rasterization into a supersampled colour + depth buffer.
//
// Vertices are snapped to 1/256 of a sample and edge functions are evaluated
// in 64-bit integers, stepped incrementally across each bounding box. Exact
// arithmetic plus a tie-break rule that is antisymmetric in the edge direction
// (the "top-left" rule) means a sample on an edge shared by two triangles is
// drawn by exactly one of them: no cracks and no double coverage.
// The shader is a template parameter so the per-sample call inlines; this is
// what keeps a million-triangle mesh in the seconds range.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

#include "render/image.h"

namespace intrinsic::render {

struct SampleBuffer {
  int width = 0, height = 0;  // in samples
  std::vector<std::uint8_t> rgb;
  std::vector<float> depth;
  SampleBuffer(int w, int h, Rgb background);
};

// Box-filter each ss x ss block of samples into one pixel.
Image resolve(const SampleBuffer& buf, int ss);

// Runs fn(y0, y1) on disjoint horizontal bands of [0, height) in parallel.
// Each band is written by one thread only, so draws need no locking and keep
// their submission order within a band.
void for_each_band(int height, const std::function<void(int, int)>& fn);

// Screen-space vertex, in sample units (x right, y down); z is depth
// (smaller is nearer) and only used when depth testing.
struct ScreenVertex {
  double x, y, z;
};

namespace detail {
constexpr int kSubBits = 8;
constexpr std::int64_t kSub = 1 << kSubBits;
// Beyond this (in samples) products of snapped coordinates could overflow
// int64; framed views never get near it.
constexpr double kGuard = 1 << 20;
}  // namespace detail

// Draws one triangle restricted to sample rows [band_y0, band_y1).
// shade(b0, b1, b2) gets barycentrics in the caller's vertex order and returns
// an Rgb. With depth_test, a sample is written only if nearer than the
// stored depth, which is then updated.
template <class Shader>
void draw_triangle(SampleBuffer& buf, ScreenVertex a, ScreenVertex b, ScreenVertex c, int band_y0, int band_y1,
                   bool depth_test, Shader&& shade) {
  using detail::kSub;
  for (const ScreenVertex* v : {&a, &b, &c})
    if (!(std::abs(v->x) < detail::kGuard && std::abs(v->y) < detail::kGuard)) return;  // also rejects NaN
  std::int64_t X[3] = {std::llround(a.x * kSub), std::llround(b.x * kSub), std::llround(c.x * kSub)};
  std::int64_t Y[3] = {std::llround(a.y * kSub), std::llround(b.y * kSub), std::llround(c.y * kSub)};
  double Z[3] = {a.z, b.z, c.z};
  std::int64_t area2 = (X[1] - X[0]) * (Y[2] - Y[0]) - (Y[1] - Y[0]) * (X[2] - X[0]);
  if (area2 == 0) return;
  // Rasterize in one winding; remember the swap to report barycentrics in
  // the caller's order.
  const bool swapped = area2 < 0;
  if (swapped) {
    std::swap(X[1], X[2]);
    std::swap(Y[1], Y[2]);
    std::swap(Z[1], Z[2]);
    area2 = -area2;
  }
  const std::int64_t half = kSub / 2;  // sample centres are at i + 0.5
  const std::int64_t minX = std::min({X[0], X[1], X[2]}), maxX = std::max({X[0], X[1], X[2]});
  const std::int64_t minY = std::min({Y[0], Y[1], Y[2]}), maxY = std::max({Y[0], Y[1], Y[2]});
  auto first_at_or_after = [&](std::int64_t v) {  // smallest i with i*kSub + half >= v
    const std::int64_t t = v - half;
    return static_cast<std::int64_t>(std::floor(static_cast<double>(t + kSub - 1) / kSub));
  };
  auto last_at_or_before = [&](std::int64_t v) {
    return static_cast<std::int64_t>(std::floor(static_cast<double>(v - half) / kSub));
  };
  const std::int64_t ix0 = std::max<std::int64_t>(first_at_or_after(minX), 0);
  const std::int64_t ix1 = std::min<std::int64_t>(last_at_or_before(maxX), buf.width - 1);
  const std::int64_t iy0 = std::max<std::int64_t>(first_at_or_after(minY), band_y0);
  const std::int64_t iy1 = std::min<std::int64_t>(last_at_or_before(maxY), band_y1 - 1);
  if (ix0 > ix1 || iy0 > iy1) return;

  // Edge k runs from vertex k+1 to k+2 and is zero there; positive inside.
  std::int64_t stepX[3], stepY[3], row[3];
  const std::int64_t px = ix0 * kSub + half, py = iy0 * kSub + half;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const std::int64_t dx = X[j] - X[i], dy = Y[j] - Y[i];
    stepX[k] = -dy * kSub;
    stepY[k] = dx * kSub;
    // Owned samples on the edge: those of edges with dy < 0, or dy == 0 and
    // dx > 0. The neighbour sees the same edge reversed, so exactly one wins.
    const bool owns = dy < 0 || (dy == 0 && dx > 0);
    row[k] = dx * (py - Y[i]) - dy * (px - X[i]) - (owns ? 0 : 1);
  }
  const double inv = 1.0 / static_cast<double>(area2);
  for (std::int64_t y = iy0; y <= iy1; ++y) {
    std::int64_t e0 = row[0], e1 = row[1], e2 = row[2];
    std::size_t idx = static_cast<std::size_t>(y) * buf.width + ix0;
    for (std::int64_t x = ix0; x <= ix1; ++x, ++idx) {
      if ((e0 | e1 | e2) >= 0) {
        const double b0 = e0 * inv, b1 = e1 * inv, b2 = 1.0 - b0 - b1;
        bool pass = true;
        if (depth_test) {
          const float z = static_cast<float>(b0 * Z[0] + b1 * Z[1] + b2 * Z[2]);
          pass = z < buf.depth[idx];
          if (pass) buf.depth[idx] = z;
        }
        if (pass) {
          const Rgb col = swapped ? shade(b0, b2, b1) : shade(b0, b1, b2);
          std::uint8_t* p = &buf.rgb[idx * 3];
          p[0] = col[0], p[1] = col[1], p[2] = col[2];
        }
      }
      e0 += stepX[0], e1 += stepX[1], e2 += stepX[2];
    }
    row[0] += stepY[0], row[1] += stepY[1], row[2] += stepY[2];
  }
}

// A segment drawn as a quad of the given width (in samples), flat colour.
void draw_line(SampleBuffer& buf, double x0, double y0, double x1, double y1, double width, Rgb colour,
               int band_y0, int band_y1);

}  // namespace intrinsic::render
