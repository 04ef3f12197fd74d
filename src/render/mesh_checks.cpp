// Validation and mesh queries for the renderer.
#include "render/mesh_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "intrinsic/error.h"

namespace intrinsic::render {

namespace {
constexpr int kMaxSide = 16384;
// Colour + depth cost 7 bytes per sample; this caps the buffer near 470 MB.
constexpr long long kMaxSamples = 1LL << 26;
}  // namespace

void check_options(const RenderOptions& o) {
  if (o.width < 1 || o.height < 1 || o.width > kMaxSide || o.height > kMaxSide)
    throw_usage("render: image size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                " is outside 1.." + std::to_string(kMaxSide));
  if (o.supersample < 1 || o.supersample > 8)
    throw_usage("render: supersample must be in 1..8, got " + std::to_string(o.supersample));
  if (static_cast<long long>(o.width) * o.height * o.supersample * o.supersample > kMaxSamples)
    throw_usage("render: " + std::to_string(o.width) + "x" + std::to_string(o.height) + " with supersample " +
                std::to_string(o.supersample) + " needs too much memory; lower one of them");
  if (o.checker_squares < 1 || o.checker_squares > 1000000)
    throw_usage("render: checker squares must be in 1..1000000, got " + std::to_string(o.checker_squares));
  if (!o.auto_view && !(std::isfinite(o.azimuth_deg) && std::isfinite(o.elevation_deg)))
    throw_usage("render: azimuth and elevation must be finite");
  if (o.texture && (o.texture->width < 1 || o.texture->height < 1 ||
                    o.texture->rgb.size() != static_cast<std::size_t>(o.texture->width) * o.texture->height * 3))
    throw_input("render: texture image is empty or malformed");
}

void check_faces(const MatrixX3i& F, Eigen::Index n, const char* what) {
  if (F.rows() == 0) throw_input(std::string(what) + ": the mesh has no faces");
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (F(f, k) < 0 || F(f, k) >= n)
        throw_input(std::string(what) + ": face " + std::to_string(f) + " refers to vertex " +
                    std::to_string(F(f, k)) + " but there are " + std::to_string(n));
}

template <class Matrix>
void check_some_finite(const MatrixX3i& F, const Matrix& P, const char* what) {
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    bool ok = true;
    for (int k = 0; k < 3 && ok; ++k) ok = P.row(F(f, k)).allFinite();
    if (ok) return;
  }
  throw_input(std::string(what) + ": no face has finite coordinates (all NaN or infinite)");
}
template void check_some_finite(const MatrixX3i&, const MatrixX2d&, const char*);
template void check_some_finite(const MatrixX3i&, const MatrixX3d&, const char*);

void collect_edges(const MatrixX3i& F, std::vector<std::array<int, 2>>& interior,
                   std::vector<std::array<int, 2>>& boundary) {
  // Sorting packed 64-bit keys is much faster than a hash map for millions
  // of edges.
  std::vector<std::uint64_t> keys;
  keys.reserve(static_cast<std::size_t>(F.rows()) * 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = static_cast<std::uint32_t>(F(f, k)), b = static_cast<std::uint32_t>(F(f, (k + 1) % 3));
      if (a == b) continue;
      keys.push_back((static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b));
    }
  std::sort(keys.begin(), keys.end());
  interior.clear();
  boundary.clear();
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i + 1;
    while (j < keys.size() && keys[j] == keys[i]) ++j;
    const std::array<int, 2> e = {static_cast<int>(keys[i] >> 32), static_cast<int>(keys[i] & 0xffffffffu)};
    (j - i == 1 ? boundary : interior).push_back(e);
    i = j;
  }
}

UvFrame frame_uv(const MatrixX3i& F, const MatrixX2d& UV, int width, int height, double margin) {
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 2; ++d) {
        const double c = UV(F(f, k), d);
        if (std::isfinite(c)) lo[d] = std::min(lo[d], c), hi[d] = std::max(hi[d], c);
      }
  UvFrame fr;
  // Halve before subtracting so extreme coordinates cannot overflow.
  const double cu = lo[0] / 2 + hi[0] / 2, cv = lo[1] / 2 + hi[1] / 2;
  const double hu = hi[0] / 2 - lo[0] / 2, hv = hi[1] / 2 - lo[1] / 2;
  const double avail_w = width * (1 - 2 * margin), avail_h = height * (1 - 2 * margin);
  double scale = std::min(hu > 0 ? avail_w / (2 * hu) : INFINITY, hv > 0 ? avail_h / (2 * hv) : INFINITY);
  if (!std::isfinite(scale) || !(scale > 0)) scale = 1;  // a single point: nothing to fit
  fr.scale = scale;
  fr.u0 = cu;
  fr.v0 = cv;
  fr.x0 = 0.5 * width;
  fr.y0 = 0.5 * height;
  return fr;
}

}  // namespace intrinsic::render
