// Texture images and the texel transfer: moving an asset's textures from its
// old UV layout into a new one (a re-atlas) without changing how it looks.
// Every texel of the new image maps back through its triangle (barycentric
// coordinates) to the old UVs and samples the old image there; colour is
// filtered in linear light, tangent-space normal maps are re-expressed in the
// new tangent frame, and charts are dilated so mipmaps do not bleed
// background into seams. The maths is in docs/maths.md "Texture transfer".
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "intrinsic/choice.h"
#include "intrinsic/image.h"

namespace intrinsic {

enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };  // glTF sampler wrapS/wrapT 10497/33071/33648
enum class TextureFilter { Linear, Nearest };
template <>
ChoiceTable<TextureWrap> choice_table<TextureWrap>();
// glTF sampler codes: wrap 10497/33071/33648 (anything else, or absent, is
// Repeat, glTF's default); magFilter 9728 = Nearest, else Linear.
TextureWrap texture_wrap_from_gltf(int code);
TextureFilter texture_filter_from_gltf(int mag_filter);

// KHR_texture_transform: uv' = T * R * S * uv (glTF's order: scale, then
// rotation, then offset), R = [cos r, sin r; -sin r, cos r] as glTF defines it.
struct TextureTransform {
  double offset_u = 0, offset_v = 0, rotation = 0, scale_u = 1, scale_v = 1;
};
struct TextureSampler {
  TextureWrap wrap_u = TextureWrap::Repeat, wrap_v = TextureWrap::Repeat;
  TextureFilter filter = TextureFilter::Linear;
  TextureTransform transform;
};

// How texel values are interpolated: Color = sRGB-encoded colour (filtered in
// linear light, written back sRGB-encoded; alpha linear), Data = as is
// (metallic-roughness, occlusion), TangentNormal = tangent-space normal map
// (re-expressed in the new tangent frame, see TransferMesh tangents).
enum class TextureRole { Color, Data, TangentNormal };
template <>
ChoiceTable<TextureRole> choice_table<TextureRole>();

// Triangles of one surface seen through two UV layouts; row 3*f+k is corner k
// of face f. UVs are in glTF image convention: u right, v DOWN, (0,0) =
// top-left texel corner of the image (callers with OpenGL/OBJ v-up convert
// with v -> 1 - v).
struct TransferMesh {
  Eigen::MatrixX2d old_uv, new_uv;  // 3m x 2
  // Only for TangentNormal: per corner, the unit normal and the tangent frame
  // (xyz + handedness w = +-1, glTF TANGENT convention: bitangent =
  // w * cross(normal, tangent)) in the old and the new layout.
  Eigen::MatrixX3d normal;
  Eigen::MatrixX4d old_tangent, new_tangent;
};

struct TransferOptions {
  int width = 2048, height = 2048;  // 1..16384
  TextureRole role = TextureRole::Color;
  // Texels of dilation around every chart (so mipmaps do not bleed
  // background into seams); -1 = fill the whole image.
  int padding = 4;
  int supersample = 1;  // samples per texel along each axis (box filtered), 1..4
};

struct TransferResult {
  // The source's channels and bit depth; texels no chart reaches (beyond the
  // padding) are 0 (alpha 0 too).
  Texture texture;
  std::vector<char> covered;  // per texel (top row first): its centre is inside a new triangle
  long texels_covered = 0, texels_dilated = 0;
  // Texels whose centre is outside every triangle but within half a texel of
  // one (partly covered): they take the colour of the nearest point of it.
  long texels_edge = 0;
};

// Error(Usage) for bad options or inconsistent mesh sizes, Error(Input) for
// non-finite UVs, tangents or normals.
TransferResult transfer_texture(const TransferMesh& mesh, const Texture& source, const TextureSampler& sampler,
                                const TransferOptions& options);

// Sampling one point (the same code transfer uses): bilinear/nearest with the
// wrap modes and the transform applied. Returns 4 values (missing channels:
// grey repeated into RGB, alpha 1). Color: the result is sRGB-encoded but was
// interpolated in linear light; Data and TangentNormal: interpolated as stored.
std::array<float, 4> sample_texture(const Texture& t, const TextureSampler& s, double u, double v, TextureRole role);

// Per-corner tangents for a triangle soup (positions, normals, uvs per
// corner, 3m rows), MikkTSpace-style: corners that share position, normal and
// uv are welded; per-face tangent/bitangent from the uv gradients,
// accumulated angle-weighted, Gram-Schmidt against the normal, handedness
// from the bitangent; faces with opposite handedness or degenerate uv are
// not averaged together. Returns 3m x 4 (xyz unit, w = +-1).
// The tangent points along increasing u and w * cross(n, t) along increasing
// v of the uv given. glTF's TANGENT (and normal maps' green channel) points
// up the image, so for TransferMesh tangents pass v-up uv: (u, 1 - v) of the
// glTF image-convention uv, as MikkTSpace exporters do.
// Error(Usage) for mismatched sizes, Error(Input) for non-finite values.
Eigen::MatrixX4d compute_tangents(const Eigen::MatrixX3d& position, const Eigen::MatrixX3d& normal,
                                  const Eigen::MatrixX2d& uv);

}  // namespace intrinsic
