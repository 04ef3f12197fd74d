// The atlas's layout on shapes whose good layout is known
// (src/generate/generate_cad.cpp): a flat side of a CAD plate is one chart
// whatever its long thin triangles and holes, flat panels and a tube are one
// chart, a fold makes two, a box unfolds without distortion and straight
// edges stay straight and on the axes, and the charts do not depend on the
// order the vertices and faces are listed in. Each quantity is measured here
// from the UVs, not by the library's own metrics; every atlas is also judged
// free of folds and overlaps by `metrics`' code (atlas_test_support.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "atlas_test_support.h"
#include "intrinsic/atlas.h"
#include "intrinsic/generate.h"
#include "intrinsic/mesh.h"
#include "intrinsic/metrics.h"

namespace intrinsic {
namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

// The faces as written: FUV follows their corner order.
const MatrixX3i& written_faces(const MeshData& m, const AtlasResult& r) { return r.F.rows() ? r.F : m.F; }

Vec3 face_normal(const MeshData& m, int f) {
  const Vec3 a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
  return (b - a).cross(c - a).normalized();
}

// The atlas of m, checked valid from the outside: every face in a chart, no
// fold, collapse, mirror or overlap.
AtlasResult checked_atlas(const MeshData& m) {
  const AtlasResult r = atlas(m);
  EXPECT_EQ(r.face_chart.size(), static_cast<size_t>(m.F.rows()));
  for (size_t f = 0; f < r.face_chart.size(); ++f) EXPECT_GE(r.face_chart[f], 0) << "face " << f;
  test::expect_metrics_accept_atlas(m.V, m.F, r);
  return r;
}

// Per chart the larger side of its UV bounding box.
std::map<int, double> chart_extent(const AtlasResult& r) {
  std::map<int, std::pair<Vec2, Vec2>> box;
  for (int f = 0; f < r.FUV.rows(); ++f) {
    const int c = r.face_chart[f];
    if (c < 0) continue;
    auto [it, fresh] = box.try_emplace(c, Vec2::Constant(INFINITY), Vec2::Constant(-INFINITY));
    for (int k = 0; k < 3; ++k) {
      const Vec2 p = r.UV.row(r.FUV(f, k));
      it->second.first = it->second.first.cwiseMin(p);
      it->second.second = it->second.second.cwiseMax(p);
    }
  }
  std::map<int, double> extent;
  for (const auto& [c, b] : box) extent[c] = (b.second - b.first).maxCoeff();
  return extent;
}

// A chart boundary edge: its two UV rows and the two 3D vertices they are corners of.
struct UvEdge {
  int chart, uv0, uv1, v0, v1;
};
// The edges of each chart's UV mesh (FUV) that only one of its faces has.
std::vector<UvEdge> chart_boundary_edges(const MeshData& m, const AtlasResult& r) {
  const MatrixX3i& F = written_faces(m, r);
  std::map<std::pair<int, int>, std::vector<UvEdge>> edges;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const UvEdge e{r.face_chart[f], r.FUV(f, k), r.FUV(f, (k + 1) % 3), F(f, k), F(f, (k + 1) % 3)};
      edges[{std::min(e.uv0, e.uv1), std::max(e.uv0, e.uv1)}].push_back(e);
    }
  std::vector<UvEdge> boundary;
  for (const auto& [key, list] : edges)
    if (list.size() == 1 && list[0].chart >= 0) boundary.push_back(list[0]);
  return boundary;
}

// The faces and vertices of m listed in another order (a fixed shuffle);
// new_face[f] is where the original face f went.
MeshData shuffled(const MeshData& m, std::vector<int>& new_face) {
  std::mt19937 rng(20240611);
  std::vector<int> new_vertex(m.V.rows()), face_order(m.F.rows());
  std::iota(new_vertex.begin(), new_vertex.end(), 0);
  std::iota(face_order.begin(), face_order.end(), 0);
  std::shuffle(new_vertex.begin(), new_vertex.end(), rng);
  std::shuffle(face_order.begin(), face_order.end(), rng);
  MeshData s;
  s.V.resize(m.V.rows(), 3);
  for (int v = 0; v < m.V.rows(); ++v) s.V.row(new_vertex[v]) = m.V.row(v);
  s.F.resize(m.F.rows(), 3);
  new_face.assign(m.F.rows(), -1);
  for (int i = 0; i < m.F.rows(); ++i) {
    const int f = face_order[i];
    for (int k = 0; k < 3; ++k) s.F(i, k) = new_vertex[m.F(f, k)];
    new_face[f] = i;
  }
  s.path = "shuffled";
  return s;
}

TEST(AtlasLayout, GeneratedShapesAreValidSurfaces) {
  // name, Euler characteristic, boundary loops (0: closed)
  const std::vector<std::tuple<const char*, int, int>> shapes{
      {"plate", -30, 0}, {"box", 2, 0},      {"l-panel", 0, 2},
      {"panel-strip", 1, 1}, {"cylinder", 0, 2}, {"rectangle", 1, 1}};
  for (const auto& [name, euler, loops] : shapes) {
    SCOPED_TRACE(name);
    const MeshData m = generate_surface(name, GenerateOptions{});
    ValidateOptions vo;
    vo.allow_closed = true;
    const Mesh mesh = make_mesh(m, vo);  // throws on non-manifold, non-orientable or degenerate input
    EXPECT_EQ(mesh.topology.num_components, 1);
    EXPECT_EQ(mesh.validation.reoriented_faces, 0);
    EXPECT_EQ(mesh.validation.unreferenced_vertices, 0);
    EXPECT_EQ(static_cast<int>(mesh.topology.boundary_loops.size()), loops);
    EXPECT_EQ(m.V.rows() - unique_edges(m.F).rows() + m.F.rows(), euler);
    std::set<std::array<double, 3>> points;
    for (int v = 0; v < m.V.rows(); ++v) points.insert({m.V(v, 0), m.V(v, 1), m.V(v, 2)});
    EXPECT_EQ(static_cast<long>(points.size()), static_cast<long>(m.V.rows())) << "duplicate vertices";
    if (loops == 0) {  // outward: positive signed volume
      double volume = 0;
      for (int f = 0; f < m.F.rows(); ++f)
        volume += Vec3(m.V.row(m.F(f, 0))).dot(Vec3(m.V.row(m.F(f, 1))).cross(Vec3(m.V.row(m.F(f, 2))))) / 6;
      EXPECT_GT(volume, 0);
    }
  }
}

TEST(AtlasLayout, DrilledPlateOneChartPerFlatSide) {
  const MeshData m = generate_drilled_plate(GenerateOptions{});
  const AtlasResult r = checked_atlas(m);
  std::set<int> top, bottom;
  int top_faces = 0, bottom_faces = 0;
  for (int f = 0; f < m.F.rows(); ++f) {
    const double nz = face_normal(m, f).z();
    if (nz > 0.99) top.insert(r.face_chart[f]), ++top_faces;
    if (nz < -0.99) bottom.insert(r.face_chart[f]), ++bottom_faces;
  }
  ASSERT_GT(top_faces, 0);
  ASSERT_EQ(top_faces, bottom_faces);
  EXPECT_EQ(top.size(), 1u) << "the top's faces fall into " << top.size() << " charts";
  EXPECT_EQ(bottom.size(), 1u) << "the bottom's faces fall into " << bottom.size() << " charts";
  if (top.size() == 1 && bottom.size() == 1) {
    EXPECT_NE(*top.begin(), *bottom.begin()) << "the top and the bottom share a chart";
  }
}

TEST(AtlasLayout, FlatRectangleOneChartOnTheAxes) {
  const MeshData m = generate_flat_rectangle(GenerateOptions{});
  const AtlasResult r = checked_atlas(m);
  ASSERT_EQ(r.charts.size(), 1u);
  const double extent = chart_extent(r).begin()->second;
  // The rectangle's own frame: turned back by the 30 degrees it was turned.
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  auto on_side = [&](int v, int side) {
    const double x = c * m.V(v, 0) + s * m.V(v, 1), y = -s * m.V(v, 0) + c * m.V(v, 1);
    const double d[4] = {y, x - 2, y - 1, x};  // bottom, right, top, left
    return std::abs(d[side]) < 1e-9;
  };
  const MatrixX3i& F = written_faces(m, r);
  for (int side = 0; side < 4; ++side) {
    SCOPED_TRACE("side " + std::to_string(side));
    Vec2 lo = Vec2::Constant(INFINITY), hi = Vec2::Constant(-INFINITY);
    std::set<int> corners;
    for (int f = 0; f < F.rows(); ++f)
      for (int k = 0; k < 3; ++k)
        if (on_side(F(f, k), side)) {
          const Vec2 p = r.UV.row(r.FUV(f, k));
          lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
          corners.insert(F(f, k));
        }
    ASSERT_GE(corners.size(), 3u);
    const Vec2 spread = hi - lo;
    EXPECT_LE(spread.minCoeff(), 1e-9 * extent)
        << "the side's UVs spread " << spread.x() << " in u and " << spread.y() << " in v (chart extent " << extent << ")";
  }
}

TEST(AtlasLayout, BoxUnfoldsIsometrically) {
  const MeshData m = generate_box(GenerateOptions{});
  const AtlasResult r = checked_atlas(m);
  const MatrixX3i& F = written_faces(m, r);
  // One scale for every edge of every face: UV length over 3D length.
  double uv_total = 0, xyz_total = 0;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      uv_total += (r.UV.row(r.FUV(f, k)) - r.UV.row(r.FUV(f, (k + 1) % 3))).norm();
      xyz_total += (m.V.row(F(f, k)) - m.V.row(F(f, (k + 1) % 3))).norm();
    }
  const double scale = uv_total / xyz_total;
  double worst = 0;
  int worst_face = -1;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const double uv = (r.UV.row(r.FUV(f, k)) - r.UV.row(r.FUV(f, (k + 1) % 3))).norm();
      const double xyz = (m.V.row(F(f, k)) - m.V.row(F(f, (k + 1) % 3))).norm();
      const double error = std::abs(uv / (scale * xyz) - 1);
      if (error > worst) worst = error, worst_face = f;
    }
  EXPECT_LE(worst, 1e-6) << "face " << worst_face << " is not congruent to its 3D triangle";
  // Chart boundary edges along the box's edges (both ends on the same two
  // faces of the box) are parallel to the u or the v axis.
  const Vec3 half(1, 0.5, 0.25);
  auto along_box_edge = [&](int a, int b) {
    int shared = 0;
    for (int axis = 0; axis < 3; ++axis)
      for (double sign : {-1.0, 1.0})
        shared += std::abs(m.V(a, axis) - sign * half[axis]) < 1e-12 && std::abs(m.V(b, axis) - sign * half[axis]) < 1e-12;
    return shared >= 2;
  };
  const std::map<int, double> extent = chart_extent(r);
  int checked = 0, slanted = 0;
  for (const UvEdge& e : chart_boundary_edges(m, r)) {
    if (!along_box_edge(e.v0, e.v1)) continue;
    ++checked;
    const Vec2 d = (r.UV.row(e.uv1) - r.UV.row(e.uv0)).cwiseAbs();
    if (d.minCoeff() > 1e-9 * extent.at(e.chart)) {
      if (slanted++ == 0)
        ADD_FAILURE() << "chart " << e.chart << ": the UV edge of vertices " << e.v0 << ", " << e.v1 << " runs " << d.x()
                      << " in u and " << d.y() << " in v";
    }
  }
  EXPECT_GT(checked, 0);
  EXPECT_EQ(slanted, 0) << "of " << checked << " chart boundary edges along the box's edges";
}

TEST(AtlasLayout, LPanelWithHoleOneChart) {
  const AtlasResult r = checked_atlas(generate_l_panel(GenerateOptions{}));
  EXPECT_EQ(r.charts.size(), 1u);
}

TEST(AtlasLayout, PanelWithStripTwoCompactCharts) {
  const MeshData m = generate_panel_with_strip(GenerateOptions{});
  const AtlasResult r = checked_atlas(m);
  EXPECT_EQ(r.charts.size(), 2u);
  std::set<int> panel, strip;
  for (int f = 0; f < m.F.rows(); ++f) {
    const bool flat = m.V(m.F(f, 0), 2) == 0 && m.V(m.F(f, 1), 2) == 0 && m.V(m.F(f, 2), 2) == 0;
    (flat ? panel : strip).insert(r.face_chart[f]);
  }
  EXPECT_EQ(panel.size(), 1u) << "the panel's faces fall into " << panel.size() << " charts";
  EXPECT_EQ(strip.size(), 1u) << "the strip's faces fall into " << strip.size() << " charts";
  if (panel.size() == 1 && strip.size() == 1) {
    EXPECT_NE(*panel.begin(), *strip.begin()) << "the panel and the strip share a chart";
  }
}

// A long tube is one strip: cut lengthwise once, never across (the chart
// runs its whole length).
TEST(AtlasLayout, LongCylinderOneStrip) {
  const MeshData m = generate_long_cylinder(GenerateOptions{});
  const AtlasResult r = checked_atlas(m);
  EXPECT_EQ(r.charts.size(), 1u);
  const double lo = m.V.col(0).minCoeff(), hi = m.V.col(0).maxCoeff();
  std::map<int, std::pair<double, double>> span;
  for (int f = 0; f < m.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const double x = m.V(m.F(f, c), 0);
      auto it = span.try_emplace(r.face_chart[f], x, x).first;
      it->second.first = std::min(it->second.first, x), it->second.second = std::max(it->second.second, x);
    }
  for (const auto& [chart, s] : span) {
    EXPECT_NEAR(s.first, lo, 1e-9 * (hi - lo)) << "chart " << chart;
    EXPECT_NEAR(s.second, hi, 1e-9 * (hi - lo)) << "chart " << chart;
  }
}

TEST(AtlasLayout, ShuffledOrderSameCharts) {
  for (const char* name : {"torus", "plate"}) {
    SCOPED_TRACE(name);
    const MeshData m = generate_surface(name, GenerateOptions{});
    std::vector<int> new_face;
    const MeshData s = shuffled(m, new_face);
    const AtlasResult a = checked_atlas(m), b = checked_atlas(s);
    EXPECT_EQ(a.charts.size(), b.charts.size());
    // The same partition of the original faces: chart ids correspond one to one.
    std::map<int, int> a_to_b, b_to_a;
    int differing = 0;
    for (int f = 0; f < m.F.rows(); ++f) {
      const int ca = a.face_chart[f], cb = b.face_chart[new_face[f]];
      const int mapped_b = a_to_b.try_emplace(ca, cb).first->second;
      const int mapped_a = b_to_a.try_emplace(cb, ca).first->second;
      differing += mapped_b != cb || mapped_a != ca;
    }
    EXPECT_EQ(differing, 0) << "faces whose chart differs between the two orders (" << a.charts.size() << " and "
                            << b.charts.size() << " charts)";
  }
}

}  // namespace
}  // namespace intrinsic
