// The image codecs' shared limits and entry points inside the library
// (src/io/png_codec.cpp, jpeg_codec.cpp); the API is intrinsic/image.h.
#pragma once

#include <string>

#include "intrinsic/image.h"

namespace intrinsic::detail {

// Largest accepted side of a decoded or requested texture, so a crafted
// header cannot make us allocate gigabytes.
constexpr int kMaxTextureSide = 16384;

// Error(Usage) unless 1..4 channels, 8 or 16 bits, a size within limits and
// a texel buffer of exactly width * height * channels values.
void check_texture(const Texture& t, const char* what);

Texture decode_png_texture(const std::string& bytes, const std::string& name);
Texture decode_jpeg_texture(const std::string& bytes, const std::string& name);

}  // namespace intrinsic::detail
