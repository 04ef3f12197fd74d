// Distortion measures (docs/maths.md §9): per-triangle Jacobian singular values,
// area-weighted summaries, and the paper's section 5.1 energies.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "intrinsic/metrics.h"
#include "util/parallel_for.h"
#include "util/vertex_adjacency.h"

namespace intrinsic {
namespace {

// Face f's edges in its own 2D frame (columns) and its 3D area.
Eigen::Matrix2d edge_frame(const MatrixX3d& V, const MatrixX3i& F, int f, double& area3d) {
  const Eigen::Vector3d x0 = V.row(F(f, 0)), x1 = V.row(F(f, 1)), x2 = V.row(F(f, 2));
  const Eigen::Vector3d e1 = x1 - x0, e2 = x2 - x0;
  const double l1 = e1.norm();
  const Eigen::Vector3d n = e1.cross(e2);
  area3d = 0.5 * n.norm();
  Eigen::Matrix2d P;
  P << l1, e1.dot(e2) / l1, 0, n.norm() / l1;
  return P;
}

// Jacobian of the map from face f's own 2D frame to the plane.
Eigen::Matrix2d jacobian(const FaceFrames& frames, const MatrixX3i& F, const MatrixX2d& UV, int f) {
  Eigen::Matrix2d Q;
  Q.col(0) = (UV.row(F(f, 1)) - UV.row(F(f, 0))).transpose();
  Q.col(1) = (UV.row(F(f, 2)) - UV.row(F(f, 0))).transpose();
  return Q * Eigen::Map<const Eigen::Matrix<double, 2, 2, Eigen::RowMajor>>(frames.P_inverse.row(f).data());
}

// Singular values of a 2x2 matrix, s1 >= s2 >= 0, in closed form.
void singular_values(const Eigen::Matrix2d& J, double& s1, double& s2) {
  const double a = J(0, 0), b = J(0, 1), c = J(1, 0), d = J(1, 1);
  const double e = 0.5 * (a + d), f = 0.5 * (a - d), g = 0.5 * (c + b), h = 0.5 * (c - b);
  const double q = std::hypot(e, h), r = std::hypot(f, g);
  s1 = q + r;
  s2 = std::abs(q - r);
}

Stat weighted_stat(const Eigen::VectorXd& x, const Eigen::VectorXd& w) {
  Stat s;
  s.min = std::numeric_limits<double>::infinity();
  s.max = -std::numeric_limits<double>::infinity();
  double sum = 0, wsum = 0;
  for (int i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i])) continue;
    s.min = std::min(s.min, x[i]);
    s.max = std::max(s.max, x[i]);
    sum += w[i] * x[i];
    wsum += w[i];
  }
  if (wsum > 0) s.mean = sum / wsum;
  if (!std::isfinite(s.min)) s.min = s.max = s.mean = 0;
  return s;
}

// The sum in index order, as one serial loop adds: the terms may be computed
// on all cores, the result stays the same to the last bit.
double ordered_sum(const Eigen::VectorXd& x) {
  double sum = 0;
  for (Eigen::Index i = 0; i < x.size(); ++i) sum += x[i];
  return sum;
}

// term(i) for i in [0, n), on all cores.
template <class Term>
Eigen::VectorXd terms(std::int64_t n, Term&& term) {
  Eigen::VectorXd x(n);
  detail::parallel_for(n, [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i) x[i] = term(i);
  });
  return x;
}

// sqrt(3D area / |signed UV area|): the signed areas on all cores, summed
// in face order as one serial loop adds them (the same bits).
double normalisation(const FaceFrames& frames, const MatrixX3i& F, const MatrixX2d& UV) {
  double a2 = ordered_sum(terms(F.rows(), [&](std::int64_t f) {
    const Eigen::Vector2d u0 = UV.row(F(f, 0)), u1 = UV.row(F(f, 1)), u2 = UV.row(F(f, 2));
    return 0.5 * ((u1.x() - u0.x()) * (u2.y() - u0.y()) - (u1.y() - u0.y()) * (u2.x() - u0.x()));
  }));
  a2 = std::abs(a2);
  return a2 > 0 ? std::sqrt(frames.total_area_3d / a2) : 1.0;
}

// Flipped or collapsed: the one definition face_distortion and count_flipped share.
bool is_flipped(const Eigen::Matrix2d& J) { return !(J.determinant() > 0); }

FaceDistortion face_distortion_scaled(const FaceFrames& frames, const MatrixX3i& F, const MatrixX2d& UV, double k);

}  // namespace

FaceFrames face_frames(const MatrixX3d& V, const MatrixX3i& F) {
  const int m = static_cast<int>(F.rows());
  FaceFrames frames;
  frames.P_inverse.resize(m, 4);
  frames.area_3d.resize(m);
  detail::parallel_for(m, [&](std::int64_t begin, std::int64_t end) {
    for (int f = static_cast<int>(begin); f < end; ++f) {
      const Eigen::Matrix2d Pi = edge_frame(V, F, f, frames.area_3d[f]).inverse();
      frames.P_inverse.row(f) << Pi(0, 0), Pi(0, 1), Pi(1, 0), Pi(1, 1);
    }
  });
  frames.total_area_3d = ordered_sum(frames.area_3d);
  return frames;
}

FaceDistortion face_distortion(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV) {
  return face_distortion(face_frames(V, F), F, UV);
}

FaceDistortion face_distortion(const FaceFrames& frames, const MatrixX3i& F, const MatrixX2d& UV) {
  return face_distortion_scaled(frames, F, UV, normalisation(frames, F, UV));
}

namespace {

// face_distortion with the normalisation k already known.
FaceDistortion face_distortion_scaled(const FaceFrames& frames, const MatrixX3i& F, const MatrixX2d& UV, double k) {
  const int m = static_cast<int>(F.rows());
  const double inf = std::numeric_limits<double>::infinity();
  FaceDistortion d;
  d.angle.resize(m);
  d.area.resize(m);
  d.stretch_l2.resize(m);
  d.stretch_linf.resize(m);
  d.area_3d.resize(m);
  // vector<bool> packs bits: threads write a byte array, copied after.
  std::vector<char> flipped(m, 0);
  detail::parallel_for(m, [&](std::int64_t begin, std::int64_t end) {
    for (int f = static_cast<int>(begin); f < end; ++f) {
      const Eigen::Matrix2d J = k * jacobian(frames, F, UV, f);
      d.area_3d[f] = frames.area_3d[f];
      double s1 = 0, s2 = 0;
      singular_values(J, s1, s2);
      flipped[f] = is_flipped(J);
      // Symmetric in growth and shrinkage: the area-weighted mean of s1*s2
      // itself is 1 by construction once total areas are normalised.
      const double ratio = s1 * s2;
      d.area[f] = ratio > 0 ? std::max(ratio, 1 / ratio) : inf;
      d.stretch_l2[f] = s2 > 0 ? std::sqrt(0.5 * (1 / (s1 * s1) + 1 / (s2 * s2))) : inf;
      d.stretch_linf[f] = s2 > 0 ? 1 / s2 : inf;
      d.angle[f] = s2 > 0 ? s1 / s2 : inf;
    }
  });
  d.flipped.assign(flipped.begin(), flipped.end());
  return d;
}

}  // namespace

int count_flipped(const FaceFrames& frames, const MatrixX3i& F, const MatrixX2d& UV) {
  const double k = normalisation(frames, F, UV);
  int n = 0;
  for (int f = 0; f < static_cast<int>(F.rows()); ++f) n += is_flipped(k * jacobian(frames, F, UV, f)) ? 1 : 0;
  return n;
}

// Sorted by (smaller, larger) vertex: each edge once, at its smaller end,
// from the counting sort of util/vertex_adjacency.h (a tiny sort per vertex
// instead of sorting all 3m edge keys at once: 0.4 s at 1M vertices), then
// written out row by row on all cores.
Eigen::MatrixX2i unique_edges(const MatrixX3i& F) {
  const std::int64_t m = F.rows();
  const int parts = detail::parallel_parts(m);
  std::vector<int> part_max(parts, 0);
  detail::parallel_for_parts(m, parts, [&](int p, std::int64_t f0, std::int64_t f1) {
    int x = 0;
    for (int c = 0; c < 3; ++c)
      for (std::int64_t f = f0; f < f1; ++f) x = std::max(x, F(f, c) + 1);
    part_max[p] = x;
  });
  const int n = *std::max_element(part_max.begin(), part_max.end());
  const detail::SparseMatrix larger = detail::vertex_adjacency_pattern(F, n, {}, detail::AdjacencyNeighbours::LargerOnly);
  const int* at = larger.outerIndexPtr();
  const int* other = larger.innerIndexPtr();
  Eigen::MatrixX2i E(at[n], 2);
  detail::parallel_for(n, [&](std::int64_t first, std::int64_t end) {
    for (std::int64_t v = first; v < end; ++v)
      for (int k = at[v]; k < at[v + 1]; ++k) {
        E(k, 0) = static_cast<int>(v);
        E(k, 1) = other[k];
      }
  });
  return E;
}

namespace {

double edge_length_energy(const MatrixX3d& V, const Eigen::MatrixX2i& E, const MatrixX2d& UV) {
  return ordered_sum(terms(E.rows(), [&](std::int64_t k) {
    const int i = E(k, 0), j = E(k, 1);
    const double r = (UV.row(i) - UV.row(j)).squaredNorm() / (V.row(i) - V.row(j)).squaredNorm() - 1;
    return r * r;
  }));
}

}  // namespace

double edge_length_energy(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV) {
  return edge_length_energy(V, unique_edges(F), UV);
}

double area_energy(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV) {
  return ordered_sum(terms(F.rows(), [&](std::int64_t f) {
    const Eigen::Vector3d x0 = V.row(F(f, 0)), x1 = V.row(F(f, 1)), x2 = V.row(F(f, 2));
    const Eigen::Vector2d u0 = UV.row(F(f, 0)), u1 = UV.row(F(f, 1)), u2 = UV.row(F(f, 2));
    const double a3 = 0.5 * (x1 - x0).cross(x2 - x0).norm();
    const double a2 = 0.5 * ((u1.x() - u0.x()) * (u2.y() - u0.y()) - (u1.y() - u0.y()) * (u2.x() - u0.x()));
    return (a2 / a3 - 1) * (a2 / a3 - 1);
  }));
}

DistortionSummary summarize_distortion(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV) {
  const FaceFrames frames = face_frames(V, F);
  DistortionSummary s;
  s.scale_factor = normalisation(frames, F, UV);
  const FaceDistortion d = face_distortion_scaled(frames, F, UV, s.scale_factor);
  for (int f = 0; f < F.rows(); ++f) {
    s.flipped_triangles += d.flipped[f];
    s.collapsed_triangles += std::isfinite(d.angle[f]) ? 0 : 1;
  }
  s.angle_distortion = weighted_stat(d.angle, d.area_3d);
  s.area_distortion = weighted_stat(d.area, d.area_3d);
  s.stretch_l2 = weighted_stat(d.stretch_l2, d.area_3d);
  s.stretch_linf = weighted_stat(d.stretch_linf, d.area_3d);
  const MatrixX2d UVn = s.scale_factor * UV;
  const Eigen::MatrixX2i E = unique_edges(F);
  const Eigen::VectorXd r = terms(E.rows(), [&](std::int64_t k) {
    return (UVn.row(E(k, 0)) - UVn.row(E(k, 1))).squaredNorm() / (V.row(E(k, 0)) - V.row(E(k, 1))).squaredNorm();
  });
  s.edge_length_distortion = weighted_stat(r, Eigen::VectorXd::Ones(r.size()));
  s.edge_length_energy = edge_length_energy(V, E, UVn);
  s.area_energy = area_energy(V, F, UVn);
  return s;
}

}  // namespace intrinsic
