// The texel transfer (texture.h transfer_texture): every texel of the new
// image is mapped back through the new-layout triangle it lies in
// (barycentric coordinates) to the old UVs, where the source is sampled;
// colour is filtered in linear light, normal maps are re-expressed in the new
// tangent frame, and the charts are dilated. Rows are cut into bands, each
// rasterized and shaded on its own (parallel, same result on any number of
// cores). Maths: docs/maths.md "Texture transfer".
#include <algorithm>
#include <cmath>

#include "intrinsic/error.h"
#include "texture/texture_internal.h"
#include "util/parallel_for.h"

namespace intrinsic {
namespace {

constexpr int kBandRows = 16;

void check_rows(const Eigen::MatrixXd& m, Eigen::Index rows, int cols, const char* what) {
  if (m.rows() != rows || m.cols() != cols)
    throw_usage(std::string("transfer_texture: ") + what + " must have " + std::to_string(rows) + " rows (3 per face)");
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    if (!m.row(i).allFinite())
      throw_input(std::string("transfer_texture: ") + what + " of face " + std::to_string(i / 3) + ", corner " +
                  std::to_string(i % 3) + " is not finite");
}

void check_request(const TransferMesh& mesh, const Texture& source, const TransferOptions& o) {
  detail::check_texture(source, "transfer_texture (source)");
  if (o.width < 1 || o.height < 1 || o.width > detail::kMaxTextureSide || o.height > detail::kMaxTextureSide)
    throw_usage("transfer_texture: width and height must be 1.." + std::to_string(detail::kMaxTextureSide));
  if (o.supersample < 1 || o.supersample > 4) throw_usage("transfer_texture: supersample must be 1..4");
  if (o.padding < -1) throw_usage("transfer_texture: padding must be -1 (fill the image) or at least 0");
  if (mesh.old_uv.rows() % 3 != 0) throw_usage("transfer_texture: old_uv must have 3 rows per face");
  const Eigen::Index n = mesh.old_uv.rows();
  check_rows(mesh.old_uv, n, 2, "old_uv");
  check_rows(mesh.new_uv, n, 2, "new_uv");
  if (o.role != TextureRole::TangentNormal) return;
  if (source.channels < 3) throw_usage("transfer_texture: a tangent-space normal map needs RGB or RGBA texels");
  check_rows(mesh.normal, n, 3, "normal");
  check_rows(mesh.old_tangent, n, 4, "old_tangent");
  check_rows(mesh.new_tangent, n, 4, "new_tangent");
}

// Faces per band of kBandRows rows whose texel-space box (grown by the
// raster's largest margin) reaches the band; in increasing face order.
std::vector<std::vector<int>> bin_faces(const Eigen::MatrixX2d& uv, int height, int bands) {
  std::vector<std::vector<int>> out(bands);
  for (Eigen::Index f = 0; f < uv.rows() / 3; ++f) {
    const double lo = std::min({uv(3 * f, 1), uv(3 * f + 1, 1), uv(3 * f + 2, 1)}) * height - 1.5;
    const double hi = std::max({uv(3 * f, 1), uv(3 * f + 1, 1), uv(3 * f + 2, 1)}) * height + 1.5;
    if (hi < 0 || lo > height) continue;
    // Clamped before the conversion: a far-away UV must not overflow an int.
    const int b0 = static_cast<int>(std::max(lo, 0.0)) / kBandRows;
    const int b1 = std::min(bands - 1, static_cast<int>(std::min(hi, static_cast<double>(height))) / kBandRows);
    for (int b = b0; b <= b1; ++b) out[b].push_back(static_cast<int>(f));
  }
  return out;
}

struct Shader {
  const TransferMesh& mesh;
  const Texture& source;  // linear for Color
  const TextureSampler& sampler;
  TextureRole role;

  // The value of one raster sample, in working space (linear for colour).
  std::array<float, 4> operator()(const detail::RasterSample& r) const {
    const int f = r.face;
    double u = 0, v = 0;
    for (int k = 0; k < 3; ++k) u += r.b[k] * mesh.old_uv(3 * f + k, 0), v += r.b[k] * mesh.old_uv(3 * f + k, 1);
    std::array<float, 4> c = detail::sample_stored(source, sampler, u, v);
    if (role == TextureRole::TangentNormal) {
      const detail::Frame from = detail::corner_frame(mesh.normal, mesh.old_tangent, f, r.b);
      const detail::Frame to = detail::corner_frame(mesh.normal, mesh.new_tangent, f, r.b);
      const auto n = detail::reexpress_normal({c[0], c[1], c[2]}, from, to);
      c[0] = n[0], c[1] = n[1], c[2] = n[2];
    }
    return c;
  }
};

// The stored channels of a 4-value sample: grey is R, its alpha A.
void store(const std::array<float, 4>& c, int channels, float* dst) {
  if (channels == 1) dst[0] = c[0];
  else if (channels == 2) dst[0] = c[0], dst[1] = c[3];
  else
    for (int i = 0; i < channels; ++i) dst[i] = c[i];
}

struct BandCounts {
  long inside = 0, edge = 0;
};

// Rasterizes and shades rows [row0, row1) into `value` / `filled` / `covered`.
BandCounts shade_band(const Shader& shade, const std::vector<int>& faces, const TransferOptions& o, int row0,
                      int row1, std::vector<float>& value, std::vector<char>& filled, std::vector<char>& covered) {
  const int W = o.width, ss = o.supersample, C = shade.source.channels;
  const detail::RasterBand band = detail::rasterize_band(shade.mesh.new_uv, faces, W, o.height, row0, row1, ss);
  BandCounts counts;
  for (int y = row0; y < row1; ++y)
    for (int x = 0; x < W; ++x) {
      const std::size_t local = static_cast<std::size_t>(y - row0) * W + x;
      const detail::RasterSample& centre = band.centre[local];
      if (centre.face < 0) continue;
      std::array<float, 4> sum{0, 0, 0, 0};
      for (int sy = 0; sy < ss; ++sy)
        for (int sx = 0; sx < ss; ++sx) {
          const detail::RasterSample* s = &centre;
          if (ss > 1) {
            const std::size_t k = static_cast<std::size_t>((y - row0) * ss + sy) * W * ss + x * ss + sx;
            if (band.sub[k].face >= 0) s = &band.sub[k];
          }
          const auto c = shade(*s);
          for (int i = 0; i < 4; ++i) sum[i] += c[i];
        }
      for (float& v : sum) v /= static_cast<float>(ss * ss);
      const std::size_t t = static_cast<std::size_t>(y) * W + x;
      store(sum, C, &value[t * C]);
      filled[t] = 1;
      covered[t] = band.inside[local];
      ++(band.inside[local] ? counts.inside : counts.edge);
    }
  return counts;
}

// Averaged (supersampled, dilated) normals are shorter than 1: renormalized.
void renormalize_normals(Texture& t, const std::vector<char>& filled) {
  for (std::size_t i = 0; i < filled.size(); ++i) {
    if (!filled[i]) continue;
    float* p = &t.texels[i * t.channels];
    Eigen::Vector3d n(2.0 * p[0] - 1, 2.0 * p[1] - 1, 2.0 * p[2] - 1);
    if (n.norm() < 1e-12) continue;
    n.normalize();
    for (int c = 0; c < 3; ++c) p[c] = static_cast<float>(0.5 * n[c] + 0.5);
  }
}

}  // namespace

TransferResult transfer_texture(const TransferMesh& mesh, const Texture& source, const TextureSampler& sampler,
                                const TransferOptions& options) {
  check_request(mesh, source, options);
  const Texture linear = options.role == TextureRole::Color ? detail::linearized(source) : Texture{};
  const Shader shade{mesh, options.role == TextureRole::Color ? linear : source, sampler, options.role};
  TransferResult result;
  Texture& out = result.texture;
  out.width = options.width, out.height = options.height, out.channels = source.channels, out.bits = source.bits;
  const std::size_t texels = static_cast<std::size_t>(out.width) * out.height;
  out.texels.assign(texels * out.channels, 0.0f);
  result.covered.assign(texels, 0);
  std::vector<char> filled(texels, 0);
  const int bands = (out.height + kBandRows - 1) / kBandRows;
  const auto binned = bin_faces(mesh.new_uv, out.height, bands);
  std::vector<BandCounts> counts(bands);
  detail::parallel_for(
      bands,
      [&](std::int64_t b0, std::int64_t b1) {
        for (std::int64_t b = b0; b < b1; ++b) {
          const int row0 = static_cast<int>(b) * kBandRows, row1 = std::min(out.height, row0 + kBandRows);
          counts[b] = shade_band(shade, binned[b], options, row0, row1, out.texels, filled, result.covered);
        }
      },
      1);
  for (const BandCounts& c : counts) result.texels_covered += c.inside, result.texels_edge += c.edge;
  if (options.padding != 0)
    result.texels_dilated = detail::dilate(out.texels, filled, out.width, out.height, out.channels, options.padding);
  if (options.role == TextureRole::TangentNormal) renormalize_normals(out, filled);
  if (options.role == TextureRole::Color) detail::encode_srgb_in_place(out);
  return result;
}

namespace detail {

double corner_uv_area(const Eigen::MatrixX2d& uv) {
  double a = 0;
  for (Eigen::Index f = 0; f + 2 < uv.rows(); f += 3) {
    const Eigen::Vector2d e1 = uv.row(f + 1) - uv.row(f), e2 = uv.row(f + 2) - uv.row(f);
    a += 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
  }
  return a;
}

}  // namespace detail

}  // namespace intrinsic
