// What a person sees of a UV layout (docs/maths.md §9.8): Sander's L2 and
// L-infinity stretch of the whole layout at one texel density, area-weighted
// percentiles of the per-face stretch max(s1, 1/s2), and the mean anisotropy.
// The per-face distortion of §9.3 normalises with the signed UV area and keeps
// collapsed faces apart; here the texel density is the point, so the
// normalisation uses the UV area actually covered (|A_f|: a folded triangle
// still takes texels) against the 3D area of the faces that have some, and
// collapsed faces count as infinitely stretched.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "intrinsic/metrics.h"
#include "util/parallel_for.h"
#include "mesh/degenerate_face.h"

namespace intrinsic {
namespace {

enum class FaceKind : char { Counted, Collapsed, Degenerate };

FaceKind classify(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV, int f) {
  if (detail::degenerate_face(V, F, f)) return FaceKind::Degenerate;
  const Eigen::Vector2d a = UV.row(F(f, 0)), b = UV.row(F(f, 1)), c = UV.row(F(f, 2));
  if (!a.allFinite() || !b.allFinite() || !c.allFinite() || orient2d_sign(a, b, c) == 0) return FaceKind::Collapsed;
  return FaceKind::Counted;
}

// Singular values s1 >= s2 of J from the eigenvalues of J^T J; s2 = |det J| / s1
// keeps full relative precision for thin faces (no cancellation).
std::pair<double, double> singular_values(const Eigen::Matrix2d& J) {
  const double t = J.squaredNorm(), d = std::abs(J.determinant());
  const double s1 = std::sqrt(0.5 * (t + std::sqrt(std::max(0.0, t * t - 4 * d * d))));
  return {s1, s1 > 0 ? d / s1 : 0.0};
}

// Area-weighted percentiles of `values` (sorted with their weights): for each
// fraction p the smallest value whose cumulative weight reaches p of the total
// (to rounding: 1e-12 of the total, so a fraction met exactly is met).
std::vector<double> weighted_percentiles(std::vector<std::pair<double, double>> values,
                                         const std::vector<double>& fractions) {
  std::sort(values.begin(), values.end());
  double total = 0;
  for (const auto& v : values) total += v.second;
  std::vector<double> out(fractions.size(), values.empty() ? 1.0 : values.back().first);
  double cumulative = 0;
  size_t next = 0;
  for (const auto& v : values) {
    cumulative += v.second;
    while (next < fractions.size() && cumulative >= fractions[next] * total - 1e-12 * total) out[next++] = v.first;
    if (next == fractions.size()) break;
  }
  return out;
}

}  // namespace

StretchSummary summarize_stretch(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV) {
  const int m = static_cast<int>(F.rows());
  const FaceFrames frames = face_frames(V, F);
  std::vector<FaceKind> kind(m);
  StretchSummary s;
  double area_3d = 0, area_uv = 0;
  for (int f = 0; f < m; ++f) {
    kind[f] = classify(V, F, UV, f);
    if (kind[f] == FaceKind::Degenerate) {
      ++s.degenerate_faces;
      continue;
    }
    ++s.faces;
    if (kind[f] == FaceKind::Collapsed) {
      ++s.collapsed_faces;
      continue;
    }
    area_3d += frames.area_3d[f];
    const Eigen::Vector2d a = UV.row(F(f, 0)), b = UV.row(F(f, 1)), c = UV.row(F(f, 2));
    area_uv += 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
  }
  if (s.faces == 0) return s;
  const double inf = std::numeric_limits<double>::infinity();
  s.scale_factor = area_uv > 0 ? std::sqrt(area_3d / area_uv) : inf;
  // Per face: stretch max(s1, 1/s2), L2^2, anisotropy s1/s2, 1/s2.
  std::vector<double> stretch(m, inf), l2_squared(m, 0), anisotropy(m, 0), linf(m, inf);
  detail::parallel_for(m, [&](std::int64_t begin, std::int64_t end) {
    for (int f = static_cast<int>(begin); f < end; ++f) {
      if (kind[f] != FaceKind::Counted || !(area_uv > 0)) continue;
      Eigen::Matrix2d Q;
      Q.col(0) = (UV.row(F(f, 1)) - UV.row(F(f, 0))).transpose();
      Q.col(1) = (UV.row(F(f, 2)) - UV.row(F(f, 0))).transpose();
      const Eigen::Map<const Eigen::Matrix<double, 2, 2, Eigen::RowMajor>> P_inverse(frames.P_inverse.row(f).data());
      const auto [s1, s2] = singular_values(s.scale_factor * Q * P_inverse);
      if (!(s2 > 0)) continue;  // too thin to resolve in doubles: collapsed after all
      stretch[f] = std::max(s1, 1 / s2);
      linf[f] = 1 / s2;
      l2_squared[f] = 0.5 * (1 / (s1 * s1) + 1 / (s2 * s2));
      anisotropy[f] = s1 / s2;
    }
  });
  std::vector<std::pair<double, double>> weighted;  // (stretch, 3D area) of the faces counted
  weighted.reserve(s.faces);
  double l2_sum = 0, anisotropy_sum = 0, weight = 0;
  s.sander_linf = s.face_stretch_max = 0;
  for (int f = 0; f < m; ++f) {
    if (kind[f] == FaceKind::Degenerate) continue;
    weighted.emplace_back(stretch[f], frames.area_3d[f]);
    s.face_stretch_max = std::max(s.face_stretch_max, stretch[f]);
    s.sander_linf = std::max(s.sander_linf, linf[f]);
    if (!std::isfinite(stretch[f])) continue;
    l2_sum += frames.area_3d[f] * l2_squared[f];
    anisotropy_sum += frames.area_3d[f] * anisotropy[f];
    weight += frames.area_3d[f];
  }
  s.sander_l2 = weight > 0 ? std::sqrt(l2_sum / weight) : inf;
  s.anisotropy_mean = weight > 0 ? anisotropy_sum / weight : inf;
  const std::vector<double> p = weighted_percentiles(std::move(weighted), {0.5, 0.95, 0.99});
  s.face_stretch_p50 = p[0];
  s.face_stretch_p95 = p[1];
  s.face_stretch_p99 = p[2];
  return s;
}

StretchSummary summarize_stretch(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV, const MatrixX3i& FUV) {
  // A triangle soup: every face its own three corners, so each face reads
  // its own UV whatever the seams.
  const Eigen::Index m = F.rows();
  MatrixX3d P(3 * m, 3);
  MatrixX2d T(3 * m, 2);
  MatrixX3i S(m, 3);
  for (Eigen::Index f = 0; f < m; ++f)
    for (int c = 0; c < 3; ++c) {
      P.row(3 * f + c) = V.row(F(f, c));
      T.row(3 * f + c) = UV.row(FUV(f, c));
      S(f, c) = static_cast<int>(3 * f + c);
    }
  return summarize_stretch(P, S, T);
}

}  // namespace intrinsic
