// Texture files in and out of memory: the format by its magic bytes (PNG or
// JPEG), reading a file whole, and the checks every Texture passes before a
// call uses it.
#include <cstring>
#include <string>

#include "intrinsic/error.h"
#include "io/text_file.h"
#include "io/image_codecs.h"

namespace intrinsic {

namespace detail {

void check_texture(const Texture& t, const char* what) {
  if (t.channels < 1 || t.channels > 4) throw_usage(std::string(what) + ": a texture has 1 to 4 channels");
  if (t.bits != 8 && t.bits != 16) throw_usage(std::string(what) + ": a texture has 8 or 16 bits per channel");
  if (t.width < 1 || t.height < 1 || t.width > kMaxTextureSide || t.height > kMaxTextureSide)
    throw_usage(std::string(what) + ": texture size must be 1.." + std::to_string(kMaxTextureSide) + " per side");
  if (t.texels.size() != static_cast<std::size_t>(t.width) * t.height * t.channels)
    throw_usage(std::string(what) + ": the texel buffer does not match width * height * channels");
}

}  // namespace detail

Texture decode_texture(const std::string& bytes, const std::string& name) {
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), kPng, 8) == 0) return detail::decode_png_texture(bytes, name);
  if (bytes.size() >= 3 && static_cast<unsigned char>(bytes[0]) == 0xff &&
      static_cast<unsigned char>(bytes[1]) == 0xd8 && static_cast<unsigned char>(bytes[2]) == 0xff)
    return detail::decode_jpeg_texture(bytes, name);
  throw_input("texture '" + name + "': neither PNG nor JPEG (unknown signature)");
}

Texture read_texture_file(const std::string& path) {
  return decode_texture(detail::read_text_file(path, "texture"), path);
}

}  // namespace intrinsic
