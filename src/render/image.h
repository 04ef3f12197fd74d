// Small pixel-level helpers shared by the renderer's drawing code; the Image
// type itself is public (intrinsic/image.h).
#pragma once

#include <array>
#include <cstdint>

#include "intrinsic/render.h"

namespace intrinsic::render {

using Rgb = std::array<std::uint8_t, 3>;

// Integer rectangle, half-open: [x0, x1) x [y0, y1).
struct Rect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};

// Both clip to the image, so callers can draw partly outside it.
void fill_rect(Image& img, Rect r, Rgb colour);
void blit(Image& dst, const Image& src, int x, int y);

inline Rgb get_pixel(const Image& img, int x, int y) {
  const std::uint8_t* p = img.pixel(x, y);
  return {p[0], p[1], p[2]};
}

}  // namespace intrinsic::render
