// Tests for texture images: PNG decoding against PNG files assembled by hand
// in the test (chunks, zlib, CRC: an independent writer), the encoder's round
// trip, JPEG decoding of a file written by stb_image_write, refusal of
// malformed data; sampling (wrap modes, filters, KHR_texture_transform, sRGB
// blending) against hand-computed values; tangents on planar and rotated
// surfaces. The transfer itself: test_texture_layouts.cpp.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cerrno>
#include <cmath>
#include <random>
#include <string>

#include "intrinsic/error.h"
#include "intrinsic/texture.h"
#include <Eigen/Geometry>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop
// jpeglib.h uses size_t and FILE without including their headers.
#include <cstddef>
#include <cstdio>
#include <jpeglib.h>

using namespace intrinsic;

namespace {

void put32(std::string& s, unsigned v) {
  for (int k = 3; k >= 0; --k) s.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
}

void chunk(std::string& png, const char* type, const std::string& data) {
  put32(png, static_cast<unsigned>(data.size()));
  const std::string body = std::string(type, 4) + data;
  png += body;
  put32(png, static_cast<unsigned>(crc32(0, reinterpret_cast<const Bytef*>(body.data()), body.size())));
}

// A PNG built by hand from codes (big-endian 16-bit samples, filter 0 rows).
std::string hand_png(int w, int h, int channels, int bits, const std::vector<unsigned>& codes) {
  static const int kType[5] = {0, 0, 4, 2, 6};
  std::string png("\x89PNG\r\n\x1a\n", 8), ihdr;
  put32(ihdr, w), put32(ihdr, h);
  ihdr += static_cast<char>(bits), ihdr += static_cast<char>(kType[channels]);
  ihdr += std::string(3, '\0');
  chunk(png, "IHDR", ihdr);
  std::string raw;
  for (int y = 0; y < h; ++y) {
    raw.push_back('\0');
    for (int i = 0; i < w * channels; ++i) {
      const unsigned c = codes[static_cast<std::size_t>(y) * w * channels + i];
      if (bits == 16) raw.push_back(static_cast<char>(c >> 8));
      raw.push_back(static_cast<char>(c & 0xff));
    }
  }
  uLongf len = compressBound(raw.size());
  std::string z(len, '\0');
  compress(reinterpret_cast<Bytef*>(&z[0]), &len, reinterpret_cast<const Bytef*>(raw.data()), raw.size());
  z.resize(len);
  chunk(png, "IDAT", z);
  chunk(png, "IEND", "");
  return png;
}

void expect_input_error(const std::string& bytes, const std::string& name, const std::string& fragment) {
  try {
    decode_texture(bytes, name);
    ADD_FAILURE() << "accepted: " << fragment;
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(TextureCodec, HandMadePngDecodesExactlyAndRoundTrips) {
  std::mt19937 rng(7);
  for (int bits : {8, 16})
    for (int channels = 1; channels <= 4; ++channels) {
      const int w = 13, h = 7, top = bits == 8 ? 255 : 65535;
      std::vector<unsigned> codes(static_cast<std::size_t>(w) * h * channels);
      for (unsigned& c : codes) c = std::uniform_int_distribution<unsigned>(0, top)(rng);
      codes[0] = 0, codes[1] = top;
      const Texture t = decode_texture(hand_png(w, h, channels, bits, codes), "hand.png");
      ASSERT_EQ(t.width, w);
      ASSERT_EQ(t.height, h);
      ASSERT_EQ(t.channels, channels);
      ASSERT_EQ(t.bits, bits);
      for (std::size_t i = 0; i < codes.size(); ++i)
        ASSERT_EQ(std::lround(t.texels[i] * top), static_cast<long>(codes[i])) << bits << " bits, " << channels;
      const Texture back = decode_texture(encode_texture_png(t), "again.png");
      ASSERT_EQ(back.channels, channels);
      ASSERT_EQ(back.bits, bits);
      EXPECT_EQ(back.texels, t.texels) << bits << " bits, " << channels << " channels";
    }
}

TEST(TextureCodec, JpegWithinJpegTolerance) {
  for (int channels : {1, 3}) {
    const int w = 64, h = 48;
    std::vector<unsigned char> px(static_cast<std::size_t>(w) * h * channels);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < channels; ++c)
          px[(static_cast<std::size_t>(y) * w + x) * channels + c] =
              static_cast<unsigned char>(127.5 + 100 * std::sin(0.1 * x + 0.7 * c) * std::cos(0.13 * y));
    std::string jpg;
    stbi_write_jpg_to_func([](void* ctx, void* data, int size) { static_cast<std::string*>(ctx)->append(
                               static_cast<char*>(data), size); },
                           &jpg, w, h, channels, px.data(), 95);
    const Texture t = decode_texture(jpg, "smooth.jpg");
    ASSERT_EQ(t.width, w);
    ASSERT_EQ(t.height, h);
    // stb_image_write stores grey as YCbCr with flat chroma: 3 channels.
    ASSERT_EQ(t.channels, 3);
    EXPECT_EQ(t.bits, 8);
    double worst = 0, sum = 0;
    for (std::size_t i = 0; i < t.texels.size(); ++i) {
      const std::size_t pixel = i / 3, c = channels == 1 ? 0 : i % 3;
      const double e = std::abs(t.texels[i] - px[pixel * channels + c] / 255.0);
      worst = std::max(worst, e), sum += e;
    }
    // Quality 95 on a smooth image: a few codes at most, about one on average.
    EXPECT_LT(worst, 12 / 255.0);
    EXPECT_LT(sum / t.texels.size(), 2 / 255.0);
  }
}

namespace {

// A one-component (grey) JPEG written with libjpeg's compressor (the
// library's decoder only reads).
std::string grey_jpeg(int w, int h, const std::vector<unsigned char>& px) {
  jpeg_compress_struct c;
  jpeg_error_mgr err;
  c.err = jpeg_std_error(&err);
  jpeg_create_compress(&c);
  unsigned char* buf = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&c, &buf, &size);
  c.image_width = w, c.image_height = h, c.input_components = 1, c.in_color_space = JCS_GRAYSCALE;
  jpeg_set_defaults(&c);
  jpeg_set_quality(&c, 95, TRUE);
  jpeg_start_compress(&c, TRUE);
  while (c.next_scanline < c.image_height) {
    JSAMPROW row = const_cast<unsigned char*>(px.data()) + static_cast<std::size_t>(c.next_scanline) * w;
    jpeg_write_scanlines(&c, &row, 1);
  }
  jpeg_finish_compress(&c);
  jpeg_destroy_compress(&c);
  std::string out(reinterpret_cast<char*>(buf), size);
  free(buf);
  return out;
}

}  // namespace

TEST(TextureCodec, GreyJpegStaysOneChannel) {
  const int w = 40, h = 24;
  std::vector<unsigned char> px(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) px[y * w + x] = static_cast<unsigned char>(127.5 + 100 * std::sin(0.1 * x + 0.05 * y));
  const Texture t = decode_texture(grey_jpeg(w, h, px), "grey.jpg");
  ASSERT_EQ(t.channels, 1);
  ASSERT_EQ(t.texels.size(), px.size());
  for (std::size_t i = 0; i < px.size(); ++i) EXPECT_NEAR(t.texels[i], px[i] / 255.0, 12 / 255.0);
}

TEST(TextureCodec, MalformedDataRefusedWithTheName) {
  expect_input_error("", "empty.png", "neither PNG nor JPEG");
  expect_input_error("GIF89a......", "a.gif", "neither PNG nor JPEG");
  std::vector<unsigned> codes(16 * 16 * 3, 200);
  const std::string png = hand_png(16, 16, 3, 8, codes);
  expect_input_error(png.substr(0, png.size() / 2), "cut.png", "malformed PNG");
  std::string bad_crc = png;
  bad_crc[20] ^= 0x55;  // inside IHDR: its CRC no longer matches
  expect_input_error(bad_crc, "crc.png", "malformed PNG");
  // A header announcing 20000 x 20000 texels: refused before allocating.
  expect_input_error(hand_png(20000, 1, 1, 8, std::vector<unsigned>(20000, 0)), "huge.png", "malformed PNG");
  // A 16000 x 16000 header in front of a few bytes: refused without
  // allocating the 1 GB it announces.
  std::string big = png;  // IHDR: width at byte 16, height at 20, CRC of bytes 12..28 at 29
  std::string dims;
  put32(dims, 16000), put32(dims, 16000);
  big.replace(16, 8, dims);
  std::string crc;
  put32(crc, static_cast<unsigned>(crc32(0, reinterpret_cast<const Bytef*>(big.data() + 12), 17)));
  big.replace(29, 4, crc);
  expect_input_error(big, "short.png", "too small");
  std::string jpg;
  std::vector<unsigned char> px(32 * 32 * 3, 90);
  stbi_write_jpg_to_func([](void* ctx, void* d, int n) { static_cast<std::string*>(ctx)->append(
                             static_cast<char*>(d), n); },
                         &jpg, 32, 32, 3, px.data(), 90);
  expect_input_error(jpg.substr(0, 40), "cut.jpg", "malformed JPEG");
  // The frame header's size (SOF0: FF C0, length, precision, height, width)
  // patched to 30000 x 30000.
  const std::size_t sof = jpg.find("\xff\xc0");
  ASSERT_NE(sof, std::string::npos);
  std::string huge = jpg;
  huge[sof + 5] = huge[sof + 7] = static_cast<char>(30000 >> 8);
  huge[sof + 6] = huge[sof + 8] = static_cast<char>(30000 & 0xff);
  expect_input_error(huge, "huge.jpg", "huge.jpg");
  std::mt19937 rng(3);
  for (int k = 0; k < 200; ++k) {  // corrupted bytes: an error or an image, never a crash
    std::string c = k % 2 ? png : jpg;
    for (int j = 0; j < 4; ++j) c[std::uniform_int_distribution<std::size_t>(0, c.size() - 1)(rng)] = char(rng());
    try {
      decode_texture(c, "fuzzed");
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input);
    }
  }
}

TEST(TextureCodec, MissingFileNamesPathAndErrno) {
  try {
    read_texture_file("/nonexistent/dir/albedo.png");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_EQ(e.os_error(), ENOENT);
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/albedo.png"), std::string::npos);
  }
}

TEST(TextureCodec, EncoderRefusesInconsistentTexture) {
  Texture t;
  t.width = 2, t.height = 2, t.channels = 3;
  t.texels.assign(5, 0.5f);
  EXPECT_THROW(encode_texture_png(t), Error);
}

namespace {

Texture grey_texture(int w, int h, const std::vector<float>& values) {
  Texture t;
  t.width = w, t.height = h, t.channels = 1, t.bits = 16;
  t.texels = values;
  return t;
}

float sample1(const Texture& t, TextureWrap wrap, TextureFilter filter, double u, double v) {
  TextureSampler s;
  s.wrap_u = s.wrap_v = wrap;
  s.filter = filter;
  return sample_texture(t, s, u, v, TextureRole::Data)[0];
}

}  // namespace

TEST(TextureSampling, WrapModesAtKnownPoints) {
  // One row of 4 texels (a second row equal, so v does not matter).
  const std::vector<float> row{0.1f, 0.3f, 0.6f, 0.8f};
  std::vector<float> values = row;
  values.insert(values.end(), row.begin(), row.end());
  const Texture t = grey_texture(4, 2, values);
  const double v = 0.25;
  for (int x = 0; x < 4; ++x)  // texel centres: the texel itself, any filter
    for (TextureFilter f : {TextureFilter::Nearest, TextureFilter::Linear})
      EXPECT_NEAR(sample1(t, TextureWrap::Repeat, f, (x + 0.5) / 4, v), row[x], 1e-6);
  // u = 0: halfway between texel 0 and the texel left of it.
  EXPECT_NEAR(sample1(t, TextureWrap::Repeat, TextureFilter::Linear, 0, v), (0.8 + 0.1) / 2, 1e-6);
  EXPECT_NEAR(sample1(t, TextureWrap::ClampToEdge, TextureFilter::Linear, 0, v), 0.1, 1e-6);
  EXPECT_NEAR(sample1(t, TextureWrap::MirroredRepeat, TextureFilter::Linear, 0, v), 0.1, 1e-6);
  // u = -0.25: texel indices -2 and -1, halfway.
  EXPECT_NEAR(sample1(t, TextureWrap::Repeat, TextureFilter::Linear, -0.25, v), (0.6 + 0.8) / 2, 1e-6);
  EXPECT_NEAR(sample1(t, TextureWrap::MirroredRepeat, TextureFilter::Linear, -0.25, v), (0.3 + 0.1) / 2, 1e-6);
  EXPECT_NEAR(sample1(t, TextureWrap::ClampToEdge, TextureFilter::Linear, -0.25, v), 0.1, 1e-6);
  // u = 1.6: texel coordinate 6.4, indices 5 and 6 with weights 0.1 and 0.9.
  EXPECT_NEAR(sample1(t, TextureWrap::Repeat, TextureFilter::Linear, 1.6, v), 0.1 * 0.3 + 0.9 * 0.6, 1e-6);
  EXPECT_NEAR(sample1(t, TextureWrap::MirroredRepeat, TextureFilter::Linear, 1.6, v), 0.1 * 0.6 + 0.9 * 0.3, 1e-6);
  EXPECT_NEAR(sample1(t, TextureWrap::ClampToEdge, TextureFilter::Linear, 1.6, v), 0.8, 1e-6);
  // Nearest at u = 1.6: texel 6 -> 2 (repeat), 1 (mirrored), 3 (clamped).
  EXPECT_NEAR(sample1(t, TextureWrap::Repeat, TextureFilter::Nearest, 1.6, v), 0.6, 1e-6);
  EXPECT_NEAR(sample1(t, TextureWrap::MirroredRepeat, TextureFilter::Nearest, 1.6, v), 0.3, 1e-6);
  EXPECT_NEAR(sample1(t, TextureWrap::ClampToEdge, TextureFilter::Nearest, 1.6, v), 0.8, 1e-6);
  // Huge and non-finite coordinates: some texel value, no crash.
  const float far = sample1(t, TextureWrap::Repeat, TextureFilter::Linear, 1e300, NAN);
  EXPECT_TRUE(far >= 0.1f && far <= 0.8f);
  EXPECT_EQ(texture_wrap_from_gltf(33071), TextureWrap::ClampToEdge);
  EXPECT_EQ(texture_wrap_from_gltf(33648), TextureWrap::MirroredRepeat);
  EXPECT_EQ(texture_wrap_from_gltf(10497), TextureWrap::Repeat);
  EXPECT_EQ(texture_filter_from_gltf(9728), TextureFilter::Nearest);
}

TEST(TextureSampling, TextureTransformMatchesTheExtension) {
  // The extension's own example: offset (0, 1), rotation 90 degrees, scale
  // 0.5 shows only the lower-left quadrant of the image.
  const Texture quad = grey_texture(2, 2, {0.1f, 0.2f, 0.3f, 0.4f});
  TextureSampler s;
  s.filter = TextureFilter::Nearest;
  s.transform.offset_u = 0, s.transform.offset_v = 1, s.transform.rotation = M_PI / 2;
  s.transform.scale_u = s.transform.scale_v = 0.5;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.01, 0.99);
  for (int k = 0; k < 50; ++k)
    EXPECT_FLOAT_EQ(sample_texture(quad, s, unit(rng), unit(rng), TextureRole::Data)[0], 0.3f);
  // Any transform: the same as sampling at uv' = T R S uv without one.
  std::vector<float> values(16 * 16);
  for (float& x : values) x = static_cast<float>(unit(rng));
  const Texture t = grey_texture(16, 16, values);
  for (int k = 0; k < 50; ++k) {
    TextureSampler a;
    a.transform = {unit(rng) * 3 - 1, unit(rng) * 3 - 1, unit(rng) * 7, unit(rng) * 4 - 2, unit(rng) * 4 - 2};
    const double u = unit(rng) * 2, v = unit(rng) * 2;
    const TextureTransform& x = a.transform;
    Eigen::Matrix3d T, R, S;
    T << 1, 0, x.offset_u, 0, 1, x.offset_v, 0, 0, 1;
    R << std::cos(x.rotation), std::sin(x.rotation), 0, -std::sin(x.rotation), std::cos(x.rotation), 0, 0, 0, 1;
    S << x.scale_u, 0, 0, 0, x.scale_v, 0, 0, 0, 1;
    const Eigen::Vector3d p = T * R * S * Eigen::Vector3d(u, v, 1);
    EXPECT_NEAR(sample_texture(t, a, u, v, TextureRole::Data)[0],
                sample_texture(t, TextureSampler{}, p.x(), p.y(), TextureRole::Data)[0], 1e-5);
  }
}

TEST(TextureSampling, ColourBlendsInLinearLightAlphaAsIs) {
  auto to_linear = [](double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); };
  auto to_srgb = [](double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055; };
  Texture t;
  t.width = 2, t.height = 1, t.channels = 4, t.bits = 8;
  t.texels = {0.2f, 0.2f, 0.2f, 0.2f, 0.9f, 0.9f, 0.9f, 0.8f};
  TextureSampler s;
  s.wrap_u = s.wrap_v = TextureWrap::ClampToEdge;
  const auto c = sample_texture(t, s, 0.5, 0.5, TextureRole::Color);
  EXPECT_NEAR(c[0], to_srgb((to_linear(0.2) + to_linear(0.9)) / 2), 1e-5);
  EXPECT_NEAR(c[3], 0.5, 1e-6);
  const auto d = sample_texture(t, s, 0.5, 0.5, TextureRole::Data);
  EXPECT_NEAR(d[0], 0.55, 1e-6);
}

namespace {

// An n x n grid of the plane z = 0 over [0,1]^2 as a triangle soup (two
// counter-clockwise triangles per cell), normals +z, uv = (x, y).
struct Soup {
  Eigen::MatrixX3d p, n;
  Eigen::MatrixX2d uv;
};

Soup planar_grid(int cells) {
  Soup s;
  const int m = 2 * cells * cells;
  s.p.resize(3 * m, 3), s.n.resize(3 * m, 3), s.uv.resize(3 * m, 2);
  int r = 0;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const double c[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      static const int kTris[2][3] = {{0, 1, 2}, {0, 2, 3}};
      for (const auto& tri : kTris)
        for (int k = 0; k < 3; ++k, ++r) {
          const double x = (i + c[tri[k]][0]) / cells, y = (j + c[tri[k]][1]) / cells;
          s.p.row(r) << x, y, 0;
          s.n.row(r) << 0, 0, 1;
          s.uv.row(r) << x, y;
        }
    }
  return s;
}

}  // namespace

TEST(TextureTangents, PlanarGridMirroredAndRotated) {
  Soup s = planar_grid(4);
  Eigen::MatrixX4d t = compute_tangents(s.p, s.n, s.uv);
  for (Eigen::Index i = 0; i < t.rows(); ++i) {
    EXPECT_NEAR((t.row(i).head<3>() - Eigen::RowVector3d(1, 0, 0)).norm(), 0, 1e-12);
    EXPECT_EQ(t(i, 3), 1);
  }
  // u mirrored: the tangent (direction of increasing u) is -x, and the
  // bitangent +y is now -cross(n, t): w = -1.
  Soup m = s;
  m.uv.col(0) *= -1;
  t = compute_tangents(m.p, m.n, m.uv);
  for (Eigen::Index i = 0; i < t.rows(); ++i) {
    EXPECT_NEAR((t.row(i).head<3>() - Eigen::RowVector3d(-1, 0, 0)).norm(), 0, 1e-12);
    EXPECT_EQ(t(i, 3), -1);
  }
  // Left half mirrored about x = 0.5 (u = 1 - x there): the seam corners are
  // welded (same position, normal, uv) but the two handednesses are not
  // averaged: each side keeps its own frame.
  Soup h = s;
  for (Eigen::Index i = 0; i < h.uv.rows(); ++i) {
    const double cx = (h.p(3 * (i / 3), 0) + h.p(3 * (i / 3) + 1, 0) + h.p(3 * (i / 3) + 2, 0)) / 3;
    if (cx < 0.5) h.uv(i, 0) = 1 - h.p(i, 0);
  }
  t = compute_tangents(h.p, h.n, h.uv);
  for (Eigen::Index i = 0; i < t.rows(); ++i) {
    const double cx = (h.p(3 * (i / 3), 0) + h.p(3 * (i / 3) + 1, 0) + h.p(3 * (i / 3) + 2, 0)) / 3;
    const double sign = cx < 0.5 ? -1 : 1;
    EXPECT_NEAR((t.row(i).head<3>() - Eigen::RowVector3d(sign, 0, 0)).norm(), 0, 1e-12) << i;
    EXPECT_EQ(t(i, 3), sign);
  }
  // A rigid rotation of positions and normals rotates the tangents (on a
  // curved version of the grid, so the frames vary).
  Soup c = s;
  for (Eigen::Index i = 0; i < c.p.rows(); ++i) {
    const double x = c.p(i, 0), y = c.p(i, 1);
    c.p(i, 2) = 0.2 * std::sin(3 * x) * std::cos(2 * y);
    c.n.row(i) = Eigen::RowVector3d(-0.6 * std::cos(3 * x) * std::cos(2 * y), 0.4 * std::sin(3 * x) * std::sin(2 * y),
                                    1).normalized();
  }
  const Eigen::MatrixX4d t0 = compute_tangents(c.p, c.n, c.uv);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Soup r = c;
  r.p = (c.p * R.transpose()).eval() + Eigen::RowVector3d(4, -2, 1).replicate(c.p.rows(), 1);
  r.n = c.n * R.transpose();
  const Eigen::MatrixX4d t1 = compute_tangents(r.p, r.n, r.uv);
  for (Eigen::Index i = 0; i < t0.rows(); ++i) {
    EXPECT_NEAR((R * t0.row(i).head<3>().transpose() - t1.row(i).head<3>().transpose()).norm(), 0, 1e-9);
    EXPECT_EQ(t0(i, 3), t1(i, 3));
    EXPECT_NEAR(t0.row(i).head<3>().dot(c.n.row(i)), 0, 1e-12);  // orthogonal to the normal
    EXPECT_NEAR(t0.row(i).head<3>().norm(), 1, 1e-12);
  }
}
