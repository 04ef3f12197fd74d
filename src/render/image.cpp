// Pixel helpers of the renderer's drawing code.
#include "render/image.h"

#include <algorithm>
#include <cstring>

#include "intrinsic/error.h"

namespace intrinsic {
namespace render {

void fill_rect(Image& img, Rect r, Rgb colour) {
  const int x0 = std::max(r.x0, 0), x1 = std::min(r.x1, img.width);
  const int y0 = std::max(r.y0, 0), y1 = std::min(r.y1, img.height);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      std::uint8_t* p = img.pixel(x, y);
      p[0] = colour[0], p[1] = colour[1], p[2] = colour[2];
    }
}

void blit(Image& dst, const Image& src, int x, int y) {
  const int sx0 = std::max(0, -x), sx1 = std::min(src.width, dst.width - x);
  if (sx1 <= sx0) return;
  for (int sy = std::max(0, -y); sy < std::min(src.height, dst.height - y); ++sy)
    std::memcpy(dst.pixel(x + sx0, y + sy), src.pixel(sx0, sy), static_cast<std::size_t>(sx1 - sx0) * 3);
}

}  // namespace render

}  // namespace intrinsic
