// Generated shapes whose good atlas layout is known, for the atlas's layout
// tests (tests/test_atlas_layout.cpp): a drilled plate triangulated the way
// CAD exporters write one (long thin triangles between each hole and its
// cell's square border), a box, flat panels (an L with a hole, a panel with a
// strip folded up along one edge, a rotated rectangle) and a long open tube.
// Every vertex is one point shared by all the faces meeting at it (no
// duplicates along seams or the box's edges), the faces are consistently
// oriented and closed solids face outward.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "intrinsic/error.h"
#include "intrinsic/generate.h"
#include "generate/check_rings.h"

namespace intrinsic {
namespace {

// Points and triangles as they are made; mesh() copies them out.
struct Builder {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3i> faces;

  int add(const Eigen::Vector3d& p) {
    points.push_back(p);
    return static_cast<int>(points.size()) - 1;
  }
  MeshData mesh() const {
    MeshData m;
    m.V.resize(static_cast<int>(points.size()), 3);
    for (size_t v = 0; v < points.size(); ++v) m.V.row(static_cast<int>(v)) = points[v].transpose();
    m.F.resize(static_cast<int>(faces.size()), 3);
    for (size_t f = 0; f < faces.size(); ++f) m.F.row(static_cast<int>(f)) = faces[f].transpose();
    m.path = "generated";
    return m;
  }
};

// A sheet over a rows x cols grid of points, id(i, j) = i * cols + j, two
// triangles per kept cell, counter-clockwise in (j, i), the diagonals
// alternating like a chequerboard; only the points of kept cells are
// written, in grid order.
template <class Point, class Keep>
MeshData grid_sheet(int rows, int cols, Point point, Keep keep) {
  std::vector<int> index(static_cast<size_t>(rows) * cols, -1);
  std::vector<std::array<int, 4>> cells;
  for (int i = 0; i + 1 < rows; ++i)
    for (int j = 0; j + 1 < cols; ++j)
      if (keep(i, j)) {
        const std::array<int, 4> c{i * cols + j, i * cols + j + 1, (i + 1) * cols + j, (i + 1) * cols + j + 1};
        for (int q : c) index[q] = 0;
        cells.push_back(c);
      }
  Builder b;
  for (int q = 0; q < rows * cols; ++q)
    if (index[q] == 0) index[q] = b.add(point(q / cols, q % cols));
  for (const std::array<int, 4>& c : cells) {
    const int a = index[c[0]], r = index[c[1]], u = index[c[2]], d = index[c[3]];
    if ((c[0] / cols + c[0] % cols) % 2 == 0) {
      b.faces.emplace_back(a, r, d);
      b.faces.emplace_back(a, d, u);
    } else {
      b.faces.emplace_back(a, r, u);
      b.faces.emplace_back(r, d, u);
    }
  }
  return b.mesh();
}

double cross2(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

// A closed slab from the open top surface in `b`: the top's points again
// `thickness` lower with its faces reversed, and the walls, outer and of the
// holes: one quad down from every boundary edge of the top, run against the
// top's direction.
void extrude_down(Builder& b, double thickness) {
  const int top_points = static_cast<int>(b.points.size()), top_faces = static_cast<int>(b.faces.size());
  for (int v = 0; v < top_points; ++v) b.add(b.points[v] - Eigen::Vector3d(0, 0, thickness));
  for (int f = 0; f < top_faces; ++f) {
    const Eigen::Vector3i t = b.faces[f];
    b.faces.emplace_back(t[0] + top_points, t[2] + top_points, t[1] + top_points);
  }
  std::set<std::pair<int, int>> directed;
  for (int f = 0; f < top_faces; ++f)
    for (int e = 0; e < 3; ++e) directed.emplace(b.faces[f][e], b.faces[f][(e + 1) % 3]);
  for (int f = 0; f < top_faces; ++f)
    for (int e = 0; e < 3; ++e) {
      const int p = b.faces[f][e], q = b.faces[f][(e + 1) % 3];
      if (directed.count({q, p})) continue;
      b.faces.emplace_back(q, p, p + top_points);
      b.faces.emplace_back(q, p + top_points, q + top_points);
    }
}

}  // namespace

MeshData generate_drilled_plate(const GenerateOptions& o) {
  detail::check_rings(o);
  const int nx = 8, ny = 6, k = std::max(1, 2 * o.rings / 5);
  const double side = 0.5, h = side / k, thickness = 0.2, radius = 0.3 * side;
  const double x0 = -0.5 * nx * side, y0 = -0.5 * ny * side;
  Builder b;
  // The top: points of the cell borders on a lattice of spacing h (i or j a
  // multiple of k), each made once and shared by the cells around it.
  std::map<std::pair<int, int>, int> lattice;
  auto lattice_point = [&](int i, int j) {
    auto [it, fresh] = lattice.try_emplace({i, j}, -1);
    if (fresh) it->second = b.add({x0 + i * h, y0 + j * h, thickness / 2});
    return it->second;
  };
  auto tri = [&](int a, int c, int d) {
    if (!(cross2(b.points[a], b.points[c], b.points[d]) > 0))
      throw_numerical("drilled plate: a triangle of the top is not counter-clockwise");
    b.faces.emplace_back(a, c, d);
  };
  for (int cj = 0; cj < ny; ++cj)
    for (int ci = 0; ci < nx; ++ci) {
      // The border, counter-clockwise from the lower-left corner: 4k points.
      std::vector<int> loop;
      const int i0 = ci * k, j0 = cj * k;
      for (int q = 0; q < k; ++q) loop.push_back(lattice_point(i0 + q, j0));
      for (int q = 0; q < k; ++q) loop.push_back(lattice_point(i0 + k, j0 + q));
      for (int q = 0; q < k; ++q) loop.push_back(lattice_point(i0 + k - q, j0 + k));
      for (int q = 0; q < k; ++q) loop.push_back(lattice_point(i0, j0 + k - q));
      const int n = 4 * k;
      const bool drilled = (ci + 2 * cj + static_cast<int>(o.seed % 3)) % 3 == 0;
      if (drilled) {
        // The hole's circle, 4k points from the angle of the lower-left
        // corner (so the corners face their own circle points), joined to
        // the border by a strip of quads, each cut along the diagonal that
        // gives the larger smallest triangle.
        const Eigen::Vector3d centre(x0 + (ci + 0.5) * side, y0 + (cj + 0.5) * side, thickness / 2);
        std::vector<int> circle;
        for (int q = 0; q < n; ++q) {
          const double a = -0.75 * M_PI + 2 * M_PI * q / n;
          circle.push_back(b.add(centre + radius * Eigen::Vector3d(std::cos(a), std::sin(a), 0)));
        }
        for (int q = 0; q < n; ++q) {
          const int p0 = loop[q], p1 = loop[(q + 1) % n], c0 = circle[q], c1 = circle[(q + 1) % n];
          const Eigen::Vector3d &P0 = b.points[p0], &P1 = b.points[p1], &C0 = b.points[c0], &C1 = b.points[c1];
          if (std::min(cross2(P0, P1, C1), cross2(P0, C1, C0)) >= std::min(cross2(P0, P1, C0), cross2(P1, C1, C0))) {
            tri(p0, p1, c1);
            tri(p0, c1, c0);
          } else {
            tri(p0, p1, c0);
            tri(p1, c1, c0);
          }
        }
      } else {
        // Diagonal bands between the two chains from the lower-left to the
        // upper-right corner: A along the bottom and right sides, B along
        // the left and top; 4k - 2 long thin triangles.
        auto A = [&](int i) { return loop[i]; };
        auto B = [&](int i) { return loop[(n - i) % n]; };
        for (int i = 0; i < 2 * k; ++i) {
          if (i < 2 * k - 1) tri(A(i), A(i + 1), B(i + 1));
          if (i > 0) tri(A(i), B(i + 1), B(i));
        }
      }
    }
  extrude_down(b, thickness);
  return b.mesh();
}

MeshData generate_box(const GenerateOptions& o) {
  detail::check_rings(o);
  // Squares of side 0.5 / m: 4m x 2m x m of them along x, y, z.
  const int m = std::max(1, o.rings / 3);
  const std::array<int, 3> cells{4 * m, 2 * m, m};
  const double h = 0.5 / m;
  Builder b;
  std::map<std::array<int, 3>, int> lattice;
  auto point = [&](const std::array<int, 3>& p) {
    auto [it, fresh] = lattice.try_emplace(p, -1);
    if (fresh) it->second = b.add({(p[0] - 0.5 * cells[0]) * h, (p[1] - 0.5 * cells[1]) * h, (p[2] - 0.5 * cells[2]) * h});
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int high = 0; high < 2; ++high) {
      // Counter-clockwise in (u, v) = the next two axes is +axis: outward on the high side.
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = 0; i < cells[u]; ++i)
        for (int j = 0; j < cells[v]; ++j) {
          std::array<int, 3> p{};
          p[axis] = high ? cells[axis] : 0;
          auto corner = [&](int di, int dj) {
            p[u] = i + di, p[v] = j + dj;
            return point(p);
          };
          const int a = corner(0, 0), r = corner(1, 0), s = corner(0, 1), d = corner(1, 1);
          if (high) {
            b.faces.emplace_back(a, r, d);
            b.faces.emplace_back(a, d, s);
          } else {
            b.faces.emplace_back(a, d, r);
            b.faces.emplace_back(a, s, d);
          }
        }
    }
  return b.mesh();
}

MeshData generate_l_panel(const GenerateOptions& o) {
  detail::check_rings(o);
  const int n = 5 * std::max(1, o.rings / 8);  // cells per unit length
  const double h = 1.0 / n;
  auto keep = [n](int i, int j) {
    const bool in_l = i < n || j < n;
    const bool in_hole = i >= 2 * n / 5 && i < 3 * n / 5 && j >= 2 * n / 5 && j < 3 * n / 5;
    return in_l && !in_hole;
  };
  return grid_sheet(3 * n + 1, 3 * n + 1, [h](int i, int j) { return Eigen::Vector3d(j * h, i * h, 0); }, keep);
}

MeshData generate_panel_with_strip(const GenerateOptions& o) {
  detail::check_rings(o);
  const int n = std::max(2, o.rings);  // cells along the panel's side
  const double h = 2.0 / n;
  const int strip_rows = std::max(1, static_cast<int>(std::lround(0.1 / h)));
  // Rows 0..n: the panel (y = i h); rows beyond: the strip folded up at y = 2.
  auto point = [=](int i, int j) {
    const double x = j * h;
    return i <= n ? Eigen::Vector3d(x, i * h, 0) : Eigen::Vector3d(x, 2, 0.1 * (i - n) / strip_rows);
  };
  return grid_sheet(n + strip_rows + 1, n + 1, point, [](int, int) { return true; });
}

MeshData generate_long_cylinder(const GenerateOptions& o) {
  detail::check_rings(o);
  const double radius = 0.2, length = 4;
  const int around = std::max(6, 6 * o.rings / 5);
  // Each ring turned half a step from the last, rings sqrt(3)/2 steps apart:
  // near-equilateral triangles.
  const double step = 2 * M_PI * radius / around;
  const int along = std::max(1, static_cast<int>(std::lround(length / (step * std::sqrt(3.0) / 2))));
  Builder b;
  for (int j = 0; j <= along; ++j)
    for (int i = 0; i < around; ++i) {
      const double a = 2 * M_PI * (i + 0.5 * j) / around;
      b.add({-length / 2 + length * j / along, radius * std::cos(a), radius * std::sin(a)});
    }
  // Counter-clockwise in (angle, x) faces outward.
  auto id = [around](int i, int j) { return j * around + i % around; };
  for (int j = 0; j < along; ++j)
    for (int i = 0; i < around; ++i) {
      b.faces.emplace_back(id(i, j), id(i + 1, j), id(i, j + 1));
      b.faces.emplace_back(id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return b.mesh();
}

MeshData generate_flat_rectangle(const GenerateOptions& o) {
  detail::check_rings(o);
  const int n = std::max(1, o.rings / 2);  // cells along the short side
  const double h = 1.0 / n;
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Eigen::Vector2d> plane((n + 1) * (2 * n + 1));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= 2 * n; ++j) {
      // Interior points move anywhere within 0.3 * jitter of a cell, side
      // points only along their side, the corners not at all.
      Eigen::Vector2d p(j * h, i * h);
      const double dx = 0.3 * o.jitter * h * unit(rng), dy = 0.3 * o.jitter * h * unit(rng);
      if (j > 0 && j < 2 * n) p.x() += dx;
      if (i > 0 && i < n) p.y() += dy;
      plane[i * (2 * n + 1) + j] = p;
    }
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  auto point = [&](int i, int j) {
    const Eigen::Vector2d& p = plane[i * (2 * n + 1) + j];
    return Eigen::Vector3d(c * p.x() - s * p.y(), s * p.x() + c * p.y(), 0);
  };
  return grid_sheet(n + 1, 2 * n + 1, point, [](int, int) { return true; });
}

}  // namespace intrinsic
