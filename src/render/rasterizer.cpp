// Non-template parts of the rasterizer: buffer setup, the box-filter resolve,
// band parallelism and line drawing.
#include "render/rasterizer.h"

#include <algorithm>
#include "util/parallel_for.h"

namespace intrinsic::render {

SampleBuffer::SampleBuffer(int w, int h, Rgb background)
    : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3),
      depth(static_cast<std::size_t>(w) * h, std::numeric_limits<float>::infinity()) {
  for (std::size_t i = 0; i < rgb.size(); i += 3) rgb[i] = background[0], rgb[i + 1] = background[1], rgb[i + 2] = background[2];
}

Image resolve(const SampleBuffer& buf, int ss) {
  Image img(buf.width / ss, buf.height / ss);
  const unsigned n = static_cast<unsigned>(ss * ss);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      unsigned sum[3] = {0, 0, 0};
      for (int sy = 0; sy < ss; ++sy) {
        const std::uint8_t* p = &buf.rgb[(static_cast<std::size_t>(y * ss + sy) * buf.width + x * ss) * 3];
        for (int sx = 0; sx < ss; ++sx, p += 3) sum[0] += p[0], sum[1] += p[1], sum[2] += p[2];
      }
      std::uint8_t* q = img.pixel(x, y);
      for (int c = 0; c < 3; ++c) q[c] = static_cast<std::uint8_t>((sum[c] + n / 2) / n);
    }
  }
  return img;
}

void for_each_band(int height, const std::function<void(int, int)>& fn) {
  intrinsic::detail::parallel_for(height, [&fn](std::int64_t y0, std::int64_t y1) { fn(static_cast<int>(y0), static_cast<int>(y1)); },
                       32);
}

void draw_line(SampleBuffer& buf, double x0, double y0, double x1, double y1, double width, Rgb colour,
               int band_y0, int band_y1) {
  const double dx = x1 - x0, dy = y1 - y0, len = std::hypot(dx, dy);
  if (!(len > 0)) return;
  // Extend by half the width at both ends so joined segments leave no notch.
  const double h = width / 2, ux = dx / len * h, uy = dy / len * h, nx = -uy, ny = ux;
  const ScreenVertex p0{x0 - ux + nx, y0 - uy + ny, 0}, p1{x1 + ux + nx, y1 + uy + ny, 0};
  const ScreenVertex p2{x1 + ux - nx, y1 + uy - ny, 0}, p3{x0 - ux - nx, y0 - uy - ny, 0};
  auto flat = [&](double, double, double) { return colour; };
  draw_triangle(buf, p0, p1, p2, band_y0, band_y1, false, flat);
  draw_triangle(buf, p0, p2, p3, band_y0, band_y1, false, flat);
}

}  // namespace intrinsic::render
