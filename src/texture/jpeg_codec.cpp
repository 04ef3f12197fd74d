// Texture images as JPEG, decoded by stb_image (Debian's libstb-dev, which
// the project already uses for stb_easy_font): header-only, so the library
// gains no link dependency (the installed CMake package and the pip build
// stay as they are), and it reads baseline and progressive JPEG. Only its
// JPEG decoder is compiled in, with private (static) symbols so it cannot
// clash with another copy of stb_image in a program using the library.
// Grey JPEGs stay one channel, colour ones three; 8 bits, values as encoded.
#include <string>

#include "intrinsic/error.h"
#include "texture/texture_internal.h"

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#define STBI_NO_LINEAR
#define STBI_NO_HDR
#define STBI_MAX_DIMENSIONS 16384
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

namespace intrinsic::detail {

Texture decode_jpeg_texture(const std::string& bytes, const std::string& name) {
  if (bytes.size() > 0x7fffffff) throw_input("texture '" + name + "': JPEG data too large");
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  int w = 0, h = 0, comp = 0;
  // The header first, so an absurd size is refused before any allocation.
  if (!stbi_info_from_memory(data, size, &w, &h, &comp))
    throw_input("texture '" + name + "': malformed JPEG: " + stbi_failure_reason());
  if (w <= 0 || h <= 0 || w > kMaxTextureSide || h > kMaxTextureSide)
    throw_input("texture '" + name + "': JPEG of " + std::to_string(w) + " x " + std::to_string(h) +
                " texels (at most " + std::to_string(kMaxTextureSide) + " per side)");
  const int channels = comp == 1 ? 1 : 3;  // stb converts CMYK/YCCK to RGB
  stbi_uc* pixels = stbi_load_from_memory(data, size, &w, &h, &comp, channels);
  if (!pixels) throw_input("texture '" + name + "': malformed JPEG: " + stbi_failure_reason());
  Texture t;
  t.width = w;
  t.height = h;
  t.channels = channels;
  t.bits = 8;
  const std::size_t n = static_cast<std::size_t>(w) * h * channels;
  t.texels.resize(n);
  for (std::size_t i = 0; i < n; ++i) t.texels[i] = pixels[i] / 255.0f;
  stbi_image_free(pixels);
  return t;
}

}  // namespace intrinsic::detail
