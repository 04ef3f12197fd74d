// Image helpers and in-memory PNG encode/decode through libpng. libpng
// reports errors by longjmp, so each libpng call sequence lives in a function
// whose frame holds no objects with destructors between setjmp and the calls;
// the message is carried out in a plain struct and thrown afterwards.
#include "render/image.h"

#include <png.h>

#include <algorithm>
#include <csetjmp>
#include <cstdio>
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

namespace {

struct PngState {
  char message[256] = "";
  // Reader side.
  const unsigned char* data = nullptr;
  std::size_t size = 0, pos = 0;
  // Writer side.
  std::string* out = nullptr;
};

void on_error(png_structp png, png_const_charp msg) {
  auto* st = static_cast<PngState*>(png_get_error_ptr(png));
  std::snprintf(st->message, sizeof st->message, "%s", msg ? msg : "unknown libpng error");
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}  // library code never prints

void on_read(png_structp png, png_bytep dst, png_size_t n) {
  auto* st = static_cast<PngState*>(png_get_io_ptr(png));
  if (n > st->size - st->pos) png_error(png, "truncated PNG data");
  std::memcpy(dst, st->data + st->pos, n);
  st->pos += n;
}

void on_write(png_structp png, png_bytep src, png_size_t n) {
  auto* st = static_cast<PngState*>(png_get_io_ptr(png));
  st->out->append(reinterpret_cast<const char*>(src), n);
}

void on_flush(png_structp) {}

// Returns false with st.message set on failure. `rows` must outlive the call.
bool write_png(PngState& st, int w, int h, png_bytep* rows) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &st, on_error, on_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return false;
  }
  png_set_write_fn(png, &st, on_write, on_flush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(w), static_cast<png_uint_32>(h), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

// Limit on decoded size, so a crafted header cannot make us allocate
// gigabytes for a texture.
constexpr png_uint_32 kMaxSide = 16384;

struct Decoded {
  png_uint_32 width = 0, height = 0;
  std::vector<unsigned char> rgba;
  std::vector<png_bytep> rows;
};

// Decodes to RGBA8. The buffers are only touched through `out`, which lives
// outside this frame, so their state is well-defined if libpng jumps back.
bool read_png(PngState& st, Decoded* out) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &st, on_error, on_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    return false;
  }
  png_set_read_fn(png, &st, on_read);
  png_set_user_limits(png, kMaxSide, kMaxSide);
  png_read_info(png, info);
  const png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
  const int colour = png_get_color_type(png, info);
  if (png_get_bit_depth(png, info) == 16) png_set_strip_16(png);
  if (colour == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colour == PNG_COLOR_TYPE_GRAY || colour == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
  png_set_expand(png);  // low-bit grey and tRNS to 8-bit with alpha
  if (!(colour & PNG_COLOR_MASK_ALPHA)) png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  if (png_get_rowbytes(png, info) != static_cast<png_size_t>(w) * 4) png_error(png, "unsupported PNG pixel layout");
  out->width = w;
  out->height = h;
  out->rgba.resize(static_cast<std::size_t>(w) * h * 4);
  out->rows.resize(h);
  for (png_uint_32 y = 0; y < h; ++y) out->rows[y] = out->rgba.data() + static_cast<std::size_t>(y) * w * 4;
  png_read_image(png, out->rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

}  // namespace

std::string encode_png(const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3)
    throw_usage("encode_png: image is empty or its pixel buffer does not match its size");
  std::string bytes;
  std::vector<png_bytep> rows(image.height);
  for (int y = 0; y < image.height; ++y)
    rows[y] = const_cast<png_bytep>(image.pixel(0, y));  // libpng's API is not const-correct
  PngState st;
  st.out = &bytes;
  if (!write_png(st, image.width, image.height, rows.data()))
    throw_output(std::string("PNG encoding failed: ") + st.message);
  return bytes;
}

Image decode_png(const std::string& bytes) {
  if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8) != 0)
    throw_input("not a PNG file (bad signature)");
  PngState st;
  st.data = reinterpret_cast<const unsigned char*>(bytes.data());
  st.size = bytes.size();
  Decoded d;
  if (!read_png(st, &d)) throw_input(std::string("malformed PNG: ") + st.message);
  Image img(static_cast<int>(d.width), static_cast<int>(d.height));
  const std::size_t n = static_cast<std::size_t>(d.width) * d.height;
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned a = d.rgba[i * 4 + 3];
    for (int c = 0; c < 3; ++c)  // composite on white
      img.rgb[i * 3 + c] = static_cast<std::uint8_t>((d.rgba[i * 4 + c] * a + 255 * (255 - a) + 127) / 255);
  }
  return img;
}

}  // namespace intrinsic
