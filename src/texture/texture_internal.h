// What the texture files share inside the library: the size limit, texel
// access, the sRGB transfer functions, the sampler core and the stages of the
// transfer (raster, dilation, normal-map frames). Nothing here is public; the
// API is include/intrinsic/texture.h, the maths docs/maths.md "Texture transfer".
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "intrinsic/texture.h"
#include "io/image_codecs.h"

namespace intrinsic::detail {


// The UV area of a triangle soup given per corner (3m x 2, row 3f+k corner
// k of face f): with the 3D area, a layout's texel density, which
// `--texture-size 0` keeps from the source layout.
double corner_uv_area(const Eigen::MatrixX2d& uv);


// sRGB electro-optical transfer function and its inverse (IEC 61966-2-1),
// on values in [0,1].
float srgb_to_linear(float c);
float linear_to_srgb(float c);
// The texture with its colour channels (all but alpha: 1 of grey+alpha, 3 of
// RGBA) decoded to linear light, alpha untouched; through a table per code,
// so a 2048^2 texture costs no pow() per texel.
Texture linearized(const Texture& t);
// The inverse, in place: colour channels encoded back to sRGB.
void encode_srgb_in_place(Texture& t);

// Texel (x, y) (already wrapped into the image) as 4 values: grey repeated
// into RGB, alpha 1 when the texture has none.
std::array<float, 4> fetch_texel(const Texture& t, int x, int y);
// The sampler on values as stored (no colour-space conversion): the
// transform, then the wrap modes, then nearest or bilinear.
std::array<float, 4> sample_stored(const Texture& t, const TextureSampler& s, double u, double v);

// One sample point of the new layout resolved to a triangle: face index (-1:
// none) and barycentric coordinates of the point, or of the nearest point
// of the triangle when the point lies outside it.
struct RasterSample {
  int face = -1;
  double b[3] = {0, 0, 0};
};
// The raster of the new layout for rows [row0, row1) of a width x height
// image, `ss` x `ss` samples per texel: centre[(y - row0) * width + x] for
// texel centres (a face only within half a texel of a triangle), and, when
// ss > 1, sub[(sy) * width * ss + sx] for the sub-samples of those rows (a
// face only inside a triangle).
// `faces` lists the faces that may touch these rows.
struct RasterBand {
  std::vector<RasterSample> centre, sub;
  std::vector<char> inside;  // per centre: inside a triangle (not only near)
};
RasterBand rasterize_band(const Eigen::MatrixX2d& new_uv, const std::vector<int>& faces, int width, int height,
                          int row0, int row1, int ss);

// Dilates `value` (width x height x channels, `filled` per texel) ring by
// ring: each empty texel 8-adjacent to the filled area takes the mean of its
// filled 4-neighbours (or, without any, of its filled diagonal neighbours).
// `rings` < 0: until the image is full. Returns the number of texels filled.
long dilate(std::vector<float>& value, std::vector<char>& filled, int width, int height, int channels, int rings);

// A tangent frame at one point: unit tangent, bitangent, normal.
struct Frame {
  Eigen::Vector3d t, b, n;
};
// The frame at barycentric point `b` of face f from per-corner normals and
// tangents (xyz, w): interpolated, Gram-Schmidt against the normal,
// bitangent = w * cross(n, t) with w the sign of the interpolated w.
Frame corner_frame(const Eigen::MatrixX3d& normal, const Eigen::MatrixX4d& tangent, int f, const double b[3]);
// An encoded tangent-space normal (rgb in [0,1]) in frame `from` re-expressed
// in frame `to`, renormalized and encoded again.
std::array<float, 3> reexpress_normal(const std::array<float, 3>& rgb, const Frame& from, const Frame& to);

}  // namespace intrinsic::detail
