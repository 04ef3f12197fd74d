// Texture images as PNG through libpng (the only libpng code: the pictures
// of render.h are RGB8 views of it), at full fidelity: grey, grey+alpha,
// RGB and RGBA at 8 or 16 bits are kept as they are (palette and low-bit grey
// expand to 8 bits, a tRNS chunk becomes an alpha channel); no gamma or
// colour-space conversion. libpng reports errors
// by longjmp, so each libpng call sequence lives in a function whose frame
// holds no objects with destructors between setjmp and the calls.
#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <vector>

#include "intrinsic/error.h"
#include "io/image_codecs.h"

namespace intrinsic {
namespace {

struct PngIo {
  char message[256] = "";
  const unsigned char* data = nullptr;
  std::size_t size = 0, pos = 0;
  std::string* out = nullptr;
};

void on_error(png_structp png, png_const_charp msg) {
  auto* io = static_cast<PngIo*>(png_get_error_ptr(png));
  std::snprintf(io->message, sizeof io->message, "%s", msg ? msg : "unknown libpng error");
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}  // library code never prints

void on_read(png_structp png, png_bytep dst, png_size_t n) {
  auto* io = static_cast<PngIo*>(png_get_io_ptr(png));
  if (n > io->size - io->pos) png_error(png, "truncated PNG data");
  std::memcpy(dst, io->data + io->pos, n);
  io->pos += n;
}

void on_write(png_structp png, png_bytep src, png_size_t n) {
  static_cast<PngIo*>(png_get_io_ptr(png))->out->append(reinterpret_cast<const char*>(src), n);
}

void on_flush(png_structp) {}

struct PngPixels {
  png_uint_32 width = 0, height = 0;
  int channels = 0, bits = 0;
  std::vector<unsigned char> bytes;
  std::vector<png_bytep> rows;
};

// Decodes into `out` (which lives outside this frame, so its state is
// well-defined if libpng jumps back). Returns false with io.message set.
bool read_png(PngIo& io, PngPixels* out) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &io, on_error, on_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    return false;
  }
  png_set_read_fn(png, &io, on_read);
  png_set_user_limits(png, detail::kMaxTextureSide, detail::kMaxTextureSide);
  png_read_info(png, info);
  png_set_expand(png);  // palette to RGB, low-bit grey to 8 bits, tRNS to alpha
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  out->width = png_get_image_width(png, info);
  out->height = png_get_image_height(png, info);
  out->channels = png_get_channels(png, info);
  out->bits = png_get_bit_depth(png, info);
  if ((out->bits != 8 && out->bits != 16) || out->channels < 1 || out->channels > 4 ||
      png_get_rowbytes(png, info) != static_cast<png_size_t>(out->width) * out->channels * (out->bits / 8))
    png_error(png, "unsupported PNG pixel layout");
  const std::size_t row = png_get_rowbytes(png, info);
  // Deflate expands at most 1032:1, so a file too small to hold its rows is
  // truncated: refused before allocating what its header announces.
  if (static_cast<double>(row + 1) * out->height > 1032.0 * static_cast<double>(io.size) + 4096)
    png_error(png, "the file is too small for the image its header announces (truncated)");
  out->bytes.resize(row * out->height);
  out->rows.resize(out->height);
  for (png_uint_32 y = 0; y < out->height; ++y) out->rows[y] = out->bytes.data() + row * y;
  png_read_image(png, out->rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

bool write_png(PngIo& io, const Texture& t, png_bytep* rows) {
  static const int kColour[5] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                 PNG_COLOR_TYPE_RGBA};
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &io, on_error, on_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return false;
  }
  png_set_write_fn(png, &io, on_write, on_flush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(t.width), static_cast<png_uint_32>(t.height), t.bits,
               kColour[t.channels], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

namespace detail {

Texture decode_png_texture(const std::string& bytes, const std::string& name) {
  PngIo io;
  io.data = reinterpret_cast<const unsigned char*>(bytes.data());
  io.size = bytes.size();
  PngPixels p;
  if (!read_png(io, &p)) throw_input("texture '" + name + "': malformed PNG: " + io.message);
  Texture t;
  t.width = static_cast<int>(p.width);
  t.height = static_cast<int>(p.height);
  t.channels = p.channels;
  t.bits = p.bits;
  const std::size_t n = static_cast<std::size_t>(t.width) * t.height * t.channels;
  t.texels.resize(n);
  if (p.bits == 8) {
    for (std::size_t i = 0; i < n; ++i) t.texels[i] = p.bytes[i] / 255.0f;
  } else {  // PNG stores 16-bit samples big-endian
    for (std::size_t i = 0; i < n; ++i) t.texels[i] = (p.bytes[2 * i] * 256 + p.bytes[2 * i + 1]) / 65535.0f;
  }
  return t;
}

}  // namespace detail

std::string encode_texture_png(const Texture& t) {
  detail::check_texture(t, "encode_texture_png");
  const int bytes_per = t.bits / 8;
  const std::size_t row = static_cast<std::size_t>(t.width) * t.channels * bytes_per;
  std::vector<unsigned char> data(row * t.height);
  const float top = t.bits == 8 ? 255.0f : 65535.0f;
  for (std::size_t i = 0; i < t.texels.size(); ++i) {
    const float v = t.texels[i] > 0 ? (t.texels[i] < 1 ? t.texels[i] : 1) : 0;  // NaN -> 0
    const unsigned code = static_cast<unsigned>(v * top + 0.5f);
    if (bytes_per == 1) {
      data[i] = static_cast<unsigned char>(code);
    } else {
      data[2 * i] = static_cast<unsigned char>(code >> 8);
      data[2 * i + 1] = static_cast<unsigned char>(code & 0xff);
    }
  }
  std::vector<png_bytep> rows(t.height);
  for (int y = 0; y < t.height; ++y) rows[y] = data.data() + row * y;
  std::string out;
  PngIo io;
  io.out = &out;
  if (!write_png(io, t, rows.data())) throw_output(std::string("PNG encoding failed: ") + io.message);
  return out;
}

}  // namespace intrinsic
