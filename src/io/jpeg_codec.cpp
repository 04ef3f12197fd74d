// Texture images as JPEG, decoded by libjpeg-turbo (Debian's
// libjpeg62-turbo-dev): fuzzed upstream and hardened against hostile files.
// (stb_image 2.27, Debian's, was tried first: its Huffman table builder
// writes out of bounds on corrupted tables, which UBSan showed in
// tests/test_texture.cpp.) Grey JPEGs stay one channel, colour ones three;
// 8 bits, values as encoded. libjpeg reports errors by longjmp, so the
// decoding frame holds no objects with destructors; a file that ends early
// (libjpeg would pad it with grey and warn) is refused as truncated.
// jpeglib.h uses size_t and FILE without including their headers.
#include <cstddef>
#include <cstdio>
#include <jpeglib.h>
#include <jerror.h>  // after jpeglib.h: the message codes (JWRN_JPEG_EOF)

#include <csetjmp>
#include <cstring>
#include <string>
#include <vector>

#include "intrinsic/error.h"
#include "io/image_codecs.h"

namespace intrinsic {
namespace {

struct JpegError {
  jpeg_error_mgr pub;  // first member: libjpeg passes a pointer to it
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX + 64] = "";
};

[[noreturn]] void on_error(j_common_ptr c) {
  auto* e = reinterpret_cast<JpegError*>(c->err);
  char text[JMSG_LENGTH_MAX] = "";
  (*c->err->format_message)(c, text);
  std::snprintf(e->message, sizeof e->message, "%s", text);
  std::longjmp(e->jump, 1);
}

// Warnings are not printed (library code never prints); the end of the data
// before the image is complete is an error, other corrupt-data warnings
// leave a decoded (if damaged) image, as viewers show it.
void on_message(j_common_ptr c, int level) {
  if (level < 0 && c->err->msg_code == JWRN_JPEG_EOF) on_error(c);
}

struct JpegPixels {
  int width = 0, height = 0, channels = 0;
  std::vector<unsigned char> bytes;
};

// Decodes into `out` (outside this frame, so well-defined after a longjmp).
bool read_jpeg(JpegError& err, const std::string& data, JpegPixels* out) {
  jpeg_decompress_struct info;
  info.err = jpeg_std_error(&err.pub);
  err.pub.error_exit = on_error;
  err.pub.emit_message = on_message;
  if (setjmp(err.jump)) {
    jpeg_destroy_decompress(&info);
    return false;
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, reinterpret_cast<const unsigned char*>(data.data()), static_cast<unsigned long>(data.size()));
  jpeg_read_header(&info, TRUE);
  if (info.image_width > static_cast<unsigned>(detail::kMaxTextureSide) ||
      info.image_height > static_cast<unsigned>(detail::kMaxTextureSide)) {
    std::snprintf(err.message, sizeof err.message, "%u x %u texels (at most %d per side)", info.image_width,
                  info.image_height, detail::kMaxTextureSide);
    jpeg_destroy_decompress(&info);
    return false;
  }
  if (info.jpeg_color_space == JCS_CMYK || info.jpeg_color_space == JCS_YCCK) {
    std::snprintf(err.message, sizeof err.message, "CMYK JPEG is not supported");
    jpeg_destroy_decompress(&info);
    return false;
  }
  info.out_color_space = info.num_components == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_start_decompress(&info);
  out->width = static_cast<int>(info.output_width);
  out->height = static_cast<int>(info.output_height);
  out->channels = info.output_components;
  const std::size_t row = static_cast<std::size_t>(out->width) * out->channels;
  // Grown row by row, so a header announcing more than the data holds
  // costs no more memory than the rows actually decoded.
  while (info.output_scanline < info.output_height) {
    out->bytes.resize(row * (info.output_scanline + 1));
    JSAMPROW dst = out->bytes.data() + row * info.output_scanline;
    jpeg_read_scanlines(&info, &dst, 1);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return true;
}

}  // namespace

namespace detail {

Texture decode_jpeg_texture(const std::string& bytes, const std::string& name) {
  JpegError err;
  JpegPixels p;
  if (!read_jpeg(err, bytes, &p)) throw_input("texture '" + name + "': malformed JPEG: " + err.message);
  if (p.channels != 1 && p.channels != 3) throw_input("texture '" + name + "': unsupported JPEG colour layout");
  Texture t;
  t.width = p.width, t.height = p.height, t.channels = p.channels, t.bits = 8;
  t.texels.resize(p.bytes.size());
  for (std::size_t i = 0; i < p.bytes.size(); ++i) t.texels[i] = p.bytes[i] / 255.0f;
  return t;
}

}  // namespace detail
}  // namespace intrinsic
