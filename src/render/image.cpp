// Image helpers, and the pictures' PNG encode/decode as RGB8 views of the
// texture codec (texture.h).
#include "render/image.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "intrinsic/error.h"
#include "intrinsic/texture.h"

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

namespace {

// The pictures' PNG codec is the texture codec (src/texture/png_codec.cpp)
// seen through RGB8: one libpng wrapper for the whole library.
Texture texture_from_picture(const Image& image) {
  Texture t;
  t.width = image.width;
  t.height = image.height;
  t.channels = 3;
  t.bits = 8;
  t.texels.resize(image.rgb.size());
  for (std::size_t i = 0; i < image.rgb.size(); ++i) t.texels[i] = image.rgb[i] / 255.0f;
  return t;
}

}  // namespace

Image render::picture_from_texture(const Texture& t) {
  Image img(t.width, t.height);
  const int c = t.channels;
  const bool alpha = c == 2 || c == 4;
  for (int y = 0; y < t.height; ++y)
    for (int x = 0; x < t.width; ++x) {
      const float* p = &t.texels[(static_cast<std::size_t>(y) * t.width + x) * c];
      const float a = alpha ? p[c - 1] : 1.0f;
      for (int k = 0; k < 3; ++k) {
        const float v = c >= 3 ? p[k] : p[0];
        const float on_white = a * v + (1 - a);
        img.pixel(x, y)[k] = static_cast<std::uint8_t>(std::lround(std::clamp(on_white, 0.0f, 1.0f) * 255));
      }
    }
  return img;
}

std::string encode_png(const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3)
    throw_usage("encode_png: image is empty or its pixel buffer does not match its size");
  return encode_texture_png(texture_from_picture(image));
}

Image decode_png(const std::string& bytes) {
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() < 8 || std::memcmp(bytes.data(), kSignature, 8) != 0)
    throw_input("not a PNG file (bad signature)");
  return render::picture_from_texture(decode_texture(bytes, "PNG data"));
}

}  // namespace intrinsic
