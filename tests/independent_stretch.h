// Per-face stretch of an atlas written for the tests (not the library's
// code): Eigen's SVD of each face's Jacobian in a frame built from another
// edge than the library's, at one texel density for the whole atlas.
#pragma once

#include <Eigen/SVD>
#include <algorithm>
#include <numeric>
#include <vector>

#include "intrinsic/atlas.h"

namespace intrinsic::test {

// Per face: 3D area and max(s1, 1/s2) of the map face -> UV, after scaling
// all UVs so that UV area = 3D area (one texel density).
struct Stretch {
  std::vector<double> area, stretch;
};
inline Stretch face_stretch(const MeshData& m, const AtlasResult& r) {
  auto uv = [&](int f, int c) { return Eigen::Vector2d(r.UV.row(r.FUV(f, c)).transpose()); };
  double a3 = 0, a2 = 0;
  for (int f = 0; f < r.F.rows(); ++f) {
    const Eigen::Vector3d a = m.V.row(r.F(f, 0)), b = m.V.row(r.F(f, 1)), c = m.V.row(r.F(f, 2));
    a3 += 0.5 * (b - a).cross(c - a).norm();
    const Eigen::Vector2d p = uv(f, 1) - uv(f, 0), q = uv(f, 2) - uv(f, 0);
    a2 += 0.5 * std::abs(p.x() * q.y() - p.y() * q.x());
  }
  const double k = std::sqrt(a3 / a2);
  Stretch s;
  for (int f = 0; f < r.F.rows(); ++f) {
    const Eigen::Vector3d a = m.V.row(r.F(f, 0)), b = m.V.row(r.F(f, 1)), c = m.V.row(r.F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() == 0) continue;
    const Eigen::Vector3d t = (c - a).normalized(), o = n.normalized().cross(t);
    Eigen::Matrix2d X, U;
    X << (b - a).dot(t), (c - a).dot(t), (b - a).dot(o), (c - a).dot(o);
    U.col(0) = k * (uv(f, 1) - uv(f, 0));
    U.col(1) = k * (uv(f, 2) - uv(f, 0));
    const Eigen::Vector2d sv = Eigen::JacobiSVD<Eigen::Matrix2d>(U * X.inverse()).singularValues();
    s.area.push_back(0.5 * n.norm());
    s.stretch.push_back(std::max(sv(0), 1 / sv(1)));
  }
  return s;
}

inline double quantile(const Stretch& s, double q) {
  std::vector<int> order(s.area.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return s.stretch[a] < s.stretch[b]; });
  const double total = std::accumulate(s.area.begin(), s.area.end(), 0.0);
  double below = 0;
  for (int i : order)
    if ((below += s.area[i]) >= q * total) return s.stretch[i];
  return s.stretch[order.back()];
}

}  // namespace intrinsic::test
