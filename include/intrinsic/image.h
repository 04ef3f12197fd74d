// Images in memory and their files: Image (RGB8, what the renderer draws and
// the generated textured surfaces carry) and Texture (any channels and bit
// depth, what the texture transfer reads and bakes), with the PNG and JPEG
// codecs (src/io: libpng, libjpeg-turbo).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace intrinsic {

// Row-major, top row first, 3 bytes (R, G, B) per pixel.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;

  Image() = default;
  Image(int w, int h, std::uint8_t grey = 255)
      : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, grey) {}
  const std::uint8_t* pixel(int x, int y) const { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
  std::uint8_t* pixel(int x, int y) { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
};

// A decoded texture image as stored: top row first, `channels` (1 grey,
// 2 grey+alpha, 3 RGB, 4 RGBA) values per texel in [0,1] exactly as encoded
// (no colour-space conversion); `bits` 8 or 16 = what the file had, used when
// encoding back.
struct Texture {
  int width = 0, height = 0, channels = 4, bits = 8;
  std::vector<float> texels;  // width * height * channels, row-major, top row first
};

// PNG or JPEG (told apart by their magic bytes). Malformed or truncated data,
// or more than 16384 texels per side: Error(Input) naming `name`.
Texture decode_texture(const std::string& bytes, const std::string& name);
// Reads and decodes a file: Error(Input) with the errno when it cannot be
// read (a missing file has os_error ENOENT), Error(Input) when malformed.
// (pictures.h's read_picture_texture turns it into the renderer's RGB8.)
Texture read_texture_file(const std::string& path);
// PNG bytes with the texture's channels and bit depth (values rounded to the
// nearest code, clamped to [0,1]). Error(Usage) for an inconsistent Texture.
std::string encode_texture_png(const Texture& t);

// RGB8 PNG bytes of an image. Error(Usage) for an empty or inconsistent one.
std::string encode_png(const Image& image);
// Any PNG colour type/bit depth is converted to RGB8 (alpha is composited on
// white). Throws Error(Input) on malformed data.
Image decode_png(const std::string& bytes);
// RGB8 from any texture: grey replicated, alpha composited on white.
Image picture_from_texture(const Texture& t);

}  // namespace intrinsic
