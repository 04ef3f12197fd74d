// Sampling a texture at one UV point as a glTF renderer would: the
// KHR_texture_transform (uv' = T R S uv), the sampler's wrap modes (glTF
// wrapS/wrapT), then nearest or bilinear filtering between texel centres,
// which sit at ((x + 0.5) / W, (y + 0.5) / H). UVs are glTF image
// coordinates: u right, v down, (0,0) the top-left corner of the image.
#include <cmath>

#include "intrinsic/error.h"
#include "texture/texture_internal.h"

namespace intrinsic {
namespace {

// A texel index wrapped into [0, n) the way OpenGL does for texel
// coordinates (MirroredRepeat mirrors every other period: ... 1 0 | 0 1 ...).
int wrap_index(long long i, int n, TextureWrap mode) {
  switch (mode) {
    case TextureWrap::ClampToEdge:
      return static_cast<int>(i < 0 ? 0 : (i >= n ? n - 1 : i));
    case TextureWrap::MirroredRepeat: {
      long long m = i % (2LL * n);
      if (m < 0) m += 2LL * n;
      return static_cast<int>(m < n ? m : 2LL * n - 1 - m);
    }
    case TextureWrap::Repeat:
    default: {
      long long m = i % n;
      return static_cast<int>(m < 0 ? m + n : m);
    }
  }
}

// A texel coordinate kept to a range whose floor fits the wrap arithmetic
// (a huge or non-finite UV must not overflow the index).
double tame(double x) {
  if (!(x == x)) return 0;
  return x < -1e12 ? -1e12 : (x > 1e12 ? 1e12 : x);
}

}  // namespace

TextureWrap texture_wrap_from_gltf(int code) {
  if (code == 33071) return TextureWrap::ClampToEdge;
  if (code == 33648) return TextureWrap::MirroredRepeat;
  return TextureWrap::Repeat;
}

TextureFilter texture_filter_from_gltf(int mag_filter) {
  return mag_filter == 9728 ? TextureFilter::Nearest : TextureFilter::Linear;
}

namespace detail {

std::array<float, 4> fetch_texel(const Texture& t, int x, int y) {
  const float* p = &t.texels[(static_cast<std::size_t>(y) * t.width + x) * t.channels];
  switch (t.channels) {
    case 1: return {p[0], p[0], p[0], 1.0f};
    case 2: return {p[0], p[0], p[0], p[1]};
    case 3: return {p[0], p[1], p[2], 1.0f};
    default: return {p[0], p[1], p[2], p[3]};
  }
}

}  // namespace detail

namespace {

// The sampler with `fetch(x, y)` giving a texel's 4 values: as stored for
// sample_stored, decoded to linear light for colour in sample_texture.
template <class Fetch>
std::array<float, 4> sample_with(const Texture& t, const TextureSampler& s, double u, double v, Fetch fetch) {
  const TextureTransform& k = s.transform;
  // No trigonometry per texel for the common unrotated case.
  const double c = k.rotation == 0 ? 1 : std::cos(k.rotation), sn = k.rotation == 0 ? 0 : std::sin(k.rotation);
  const double su = k.scale_u * u, sv = k.scale_v * v;
  const double tu = c * su + sn * sv + k.offset_u, tv = -sn * su + c * sv + k.offset_v;
  const double px = tame(tu * t.width), py = tame(tv * t.height);
  if (s.filter == TextureFilter::Nearest) {
    const int x = wrap_index(static_cast<long long>(std::floor(px)), t.width, s.wrap_u);
    const int y = wrap_index(static_cast<long long>(std::floor(py)), t.height, s.wrap_v);
    return fetch(x, y);
  }
  const double fx0 = std::floor(px - 0.5), fy0 = std::floor(py - 0.5);
  const float ax = static_cast<float>(px - 0.5 - fx0), ay = static_cast<float>(py - 0.5 - fy0);
  const long long ix = static_cast<long long>(fx0), iy = static_cast<long long>(fy0);
  const int x0 = wrap_index(ix, t.width, s.wrap_u), x1 = wrap_index(ix + 1, t.width, s.wrap_u);
  const int y0 = wrap_index(iy, t.height, s.wrap_v), y1 = wrap_index(iy + 1, t.height, s.wrap_v);
  const auto a = fetch(x0, y0), b = fetch(x1, y0);
  const auto cc = fetch(x0, y1), d = fetch(x1, y1);
  std::array<float, 4> out;
  for (int i = 0; i < 4; ++i)
    out[i] = (1 - ay) * ((1 - ax) * a[i] + ax * b[i]) + ay * ((1 - ax) * cc[i] + ax * d[i]);
  return out;
}

}  // namespace

namespace detail {

std::array<float, 4> sample_stored(const Texture& t, const TextureSampler& s, double u, double v) {
  return sample_with(t, s, u, v, [&t](int x, int y) { return fetch_texel(t, x, y); });
}

}  // namespace detail

std::array<float, 4> sample_texture(const Texture& t, const TextureSampler& s, double u, double v, TextureRole role) {
  detail::check_texture(t, "sample_texture");
  if (role != TextureRole::Color) return detail::sample_stored(t, s, u, v);
  // Colour is blended in linear light: each tap decoded, the blend encoded
  // back; alpha is linear already.
  std::array<float, 4> out = sample_with(t, s, u, v, [&t](int x, int y) {
    std::array<float, 4> c = detail::fetch_texel(t, x, y);
    for (int i = 0; i < 3; ++i) c[i] = detail::srgb_to_linear(c[i]);
    return c;
  });
  for (int i = 0; i < 3; ++i) out[i] = detail::linear_to_srgb(out[i] > 0 ? (out[i] < 1 ? out[i] : 1) : 0);
  return out;
}

// How the command line, Python and the reports spell these (intrinsic/choice.h).
template <>
ChoiceTable<TextureRole> choice_table<TextureRole>() {
  static const Choice<TextureRole> rows[] = {
      {TextureRole::Color, "color"}, {TextureRole::Data, "data"}, {TextureRole::TangentNormal, "normal"}};
  return make_choice_table(rows);
}

template <>
ChoiceTable<TextureWrap> choice_table<TextureWrap>() {
  static const Choice<TextureWrap> rows[] = {
      {TextureWrap::Repeat, "repeat"}, {TextureWrap::ClampToEdge, "clamp"}, {TextureWrap::MirroredRepeat, "mirror"}};
  return make_choice_table(rows);
}

}  // namespace intrinsic
