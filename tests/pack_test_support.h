// What the packer tests share: texel sets from a mask's spans, the padding
// dilation done texel by texel, and small planar charts made from a polygon
// (3D = the polygon in the plane z = 0, so the chart is isometric).
#pragma once

#include <set>
#include <utility>
#include <vector>

#include "atlas/atlas_internal.h"
#include "atlas/packing/texel_mask.h"

namespace intrinsic::detail::packing::test {

using Texels = std::set<std::pair<int, int>>;

// The texels a mask's per-row spans cover, shifted by (x0, y0).
inline Texels texels_of(const std::vector<Spans>& rows, int x0 = 0, int y0 = 0) {
  Texels t;
  for (int y = 0; y < static_cast<int>(rows.size()); ++y)
    for (const auto& s : rows[y])
      for (int x = s.first; x < s.second; ++x) t.insert({x + x0, y + y0});
  return t;
}

// Every texel within Chebyshev distance `pad` of one of `own`, wherever it lies.
inline Texels dilated_by_brute_force(const Texels& own, int pad) {
  Texels d;
  for (const auto& [x, y] : own)
    for (int dy = -pad; dy <= pad; ++dy)
      for (int dx = -pad; dx <= pad; ++dx) d.insert({x + dx, y + dy});
  return d;
}

// The same, kept inside the w x h frame.
inline Texels dilated_by_brute_force(const Texels& own, int pad, int w, int h) {
  Texels d;
  for (const auto& t : dilated_by_brute_force(own, pad))
    if (t.first >= 0 && t.first < w && t.second >= 0 && t.second < h) d.insert(t);
  return d;
}

// A chart whose UVs are the points p, triangulated as a fan from p[0]:
// triangles (0, i, i + 1), and with `closed` also (0, last, 1) (p[0] is then
// a centre, not a corner). Its 3D area is the fan's signed area.
inline FlatChart fan_chart(const std::vector<Eigen::Vector2d>& p, bool closed) {
  const int n = static_cast<int>(p.size());
  FlatChart c;
  c.UV.resize(n, 2);
  c.mesh.data.V.setZero(n, 3);
  for (int i = 0; i < n; ++i) {
    c.UV.row(i) = p[i].transpose();
    c.mesh.data.V.row(i) << p[i].x(), p[i].y(), 0;
  }
  const int triangles = closed ? n - 1 : n - 2;
  c.mesh.data.F.resize(triangles, 3);
  double area = 0;
  for (int k = 0; k < triangles; ++k) {
    const int a = 1 + k, b = closed ? 1 + (k + 1) % (n - 1) : k + 2;
    c.mesh.data.F.row(k) << 0, a, b;
    const Eigen::Vector2d e1 = p[a] - p[0], e2 = p[b] - p[0];
    area += 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
  }
  c.summary.area_3d = area;
  return c;
}

}  // namespace intrinsic::detail::packing::test
