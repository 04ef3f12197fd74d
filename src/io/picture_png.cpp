// The RGB8 pictures' PNG encode/decode (intrinsic/image.h): the texture
// codec (png_codec.cpp) seen through RGB8, so the library has one libpng
// wrapper.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "intrinsic/error.h"
#include "intrinsic/image.h"

namespace intrinsic {
namespace {

// The pictures' PNG codec is the texture codec (src/io/png_codec.cpp)
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

Image picture_from_texture(const Texture& t) {
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
  return picture_from_texture(decode_texture(bytes, "PNG data"));
}

}  // namespace intrinsic
