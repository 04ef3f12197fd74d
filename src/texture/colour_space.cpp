// sRGB encoding of colour textures (glTF baseColor and emissive are
// sRGB-encoded): the transfer filters colour in linear light, because
// averaging encoded values darkens edges and blends (docs/maths.md "Texture
// transfer"). Alpha is linear in glTF and is never converted.
#include <cmath>
#include <vector>

#include "texture/texture_internal.h"
#include "util/parallel_for.h"

namespace intrinsic::detail {

float srgb_to_linear(float c) {
  if (c <= 0.04045f) return c / 12.92f;
  return static_cast<float>(std::pow((c + 0.055) / 1.055, 2.4));
}

float linear_to_srgb(float c) {
  if (c <= 0.0031308f) return c * 12.92f;
  return static_cast<float>(1.055 * std::pow(static_cast<double>(c), 1 / 2.4) - 0.055);
}

namespace {

// Channels that carry colour: all but the alpha of grey+alpha and RGBA.
int colour_channels(const Texture& t) { return t.channels == 2 || t.channels == 4 ? t.channels - 1 : t.channels; }

}  // namespace

Texture linearized(const Texture& t) {
  Texture out = t;
  const int codes = t.bits == 16 ? 65536 : 256;
  std::vector<float> table(codes);
  for (int i = 0; i < codes; ++i) table[i] = srgb_to_linear(static_cast<float>(i) / (codes - 1));
  const int cc = colour_channels(t);
  const std::int64_t n = static_cast<std::int64_t>(t.width) * t.height;
  parallel_for(n, [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i)
      for (int c = 0; c < cc; ++c) {
        float& v = out.texels[i * t.channels + c];
        // Decoded values are exact codes; others (a caller's floats) are
        // rounded to the nearest code, well within the quantization they had.
        const float x = v > 0 ? (v < 1 ? v : 1) : 0;
        v = table[static_cast<int>(x * (codes - 1) + 0.5f)];
      }
  });
  return out;
}

void encode_srgb_in_place(Texture& t) {
  const int cc = colour_channels(t);
  const std::int64_t n = static_cast<std::int64_t>(t.width) * t.height;
  parallel_for(n, [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i)
      for (int c = 0; c < cc; ++c) {
        float& v = t.texels[i * t.channels + c];
        v = linear_to_srgb(v > 0 ? (v < 1 ? v : 1) : 0);
      }
  });
}

}  // namespace intrinsic::detail
