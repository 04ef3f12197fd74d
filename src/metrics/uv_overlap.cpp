// Overlapping UV triangles (a test independent of the packer, so that it
// checks it; docs/maths.md §9 for the other atlas measures). Two triangles
// overlap when their interiors meet; touching along an edge or at a corner
// is not an overlap. For convex polygons with disjoint interiors some edge's
// supporting line separates them (the separating axis theorem), so the test
// is six exact orientation signs. A uniform grid over the UV box keeps the
// candidate pairs near linear in the number of faces.
#include <algorithm>
#include <array>
#include <cmath>

#include "intrinsic/metrics.h"

namespace intrinsic {
namespace {

// Error-free transformations (Shewchuk 1997, "Adaptive precision
// floating-point arithmetic and fast robust geometric predicates").
void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double bv = x - a, av = x - bv;
  y = (a - av) + (b - bv);
}

// The exact determinant as a sum of six products expanded into twelve
// doubles, added into a non-overlapping expansion; its sign is that of its
// largest component.
int orient2d_exact(double ax, double ay, double bx, double by, double cx, double cy) {
  const std::array<std::pair<double, double>, 6> products = {{{ax, by}, {-ax, cy}, {-cx, by},
                                                              {-ay, bx}, {ay, cx}, {cy, bx}}};
  std::array<double, 13> e{};
  int n = 0;
  auto grow = [&](double b) {
    double q = b;
    for (int i = 0; i < n; ++i) {
      double x, y;
      two_sum(q, e[i], x, y);
      e[i] = y;
      q = x;
    }
    e[n++] = q;
  };
  for (const auto& [p, q] : products) {
    const double x = p * q;
    grow(std::fma(p, q, -x));
    grow(x);
  }
  for (int i = n - 1; i >= 0; --i)
    if (e[i] != 0) return e[i] > 0 ? 1 : -1;
  return 0;
}

struct Box {
  double x0, y0, x1, y1;
};

// Interiors of two counter-clockwise triangles meet: no edge line of either
// has the other triangle wholly on its closed outer side.
bool interiors_meet(const std::array<Eigen::Vector2d, 3>& s, const std::array<Eigen::Vector2d, 3>& t) {
  auto separates = [](const std::array<Eigen::Vector2d, 3>& a, const std::array<Eigen::Vector2d, 3>& b) {
    for (int i = 0; i < 3; ++i) {
      bool inside = false;
      for (int j = 0; j < 3 && !inside; ++j) inside = orient2d_sign(a[i], a[(i + 1) % 3], b[j]) > 0;
      if (!inside) return true;
    }
    return false;
  };
  return !separates(s, t) && !separates(t, s);
}

}  // namespace

int orient2d_sign(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double l = (a.x() - c.x()) * (b.y() - c.y()), r = (a.y() - c.y()) * (b.x() - c.x());
  const double det = l - r;
  // Shewchuk's ccwerrboundA: beyond it the rounded sign is the exact sign.
  const double bound = 3.3306690738754716e-16 * (std::abs(l) + std::abs(r));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return orient2d_exact(a.x(), a.y(), b.x(), b.y(), c.x(), c.y());
}

std::vector<char> overlapping_uv_triangles(const MatrixX3i& FT, const MatrixX2d& UV, int* pairs_within,
                                           int* pairs_between, const std::vector<int>* face_chart) {
  const int m = static_cast<int>(FT.rows());
  std::vector<char> hit(m, 0);
  std::vector<std::array<Eigen::Vector2d, 3>> tri(m);
  std::vector<Box> box(m);
  std::vector<int> live;
  Box all{INFINITY, INFINITY, -INFINITY, -INFINITY};
  for (int f = 0; f < m; ++f) {
    for (int c = 0; c < 3; ++c) tri[f][c] = UV.row(FT(f, c)).transpose();
    if (!(tri[f][0].allFinite() && tri[f][1].allFinite() && tri[f][2].allFinite())) continue;
    const int o = orient2d_sign(tri[f][0], tri[f][1], tri[f][2]);
    if (o == 0) continue;  // no interior
    if (o < 0) std::swap(tri[f][1], tri[f][2]);
    Box& b = box[f];
    b = {std::min({tri[f][0].x(), tri[f][1].x(), tri[f][2].x()}), std::min({tri[f][0].y(), tri[f][1].y(), tri[f][2].y()}),
         std::max({tri[f][0].x(), tri[f][1].x(), tri[f][2].x()}), std::max({tri[f][0].y(), tri[f][1].y(), tri[f][2].y()})};
    all = {std::min(all.x0, b.x0), std::min(all.y0, b.y0), std::max(all.x1, b.x1), std::max(all.y1, b.y1)};
    live.push_back(f);
  }
  int within = 0, between = 0;
  if (live.size() >= 2) {
    // About one face per cell; cells square-ish in UV.
    const double w = std::max(all.x1 - all.x0, 1e-300), h = std::max(all.y1 - all.y0, 1e-300);
    const double n = static_cast<double>(live.size());
    const int gx = static_cast<int>(std::clamp(std::sqrt(n * w / h), 1.0, 4096.0));
    const int gy = static_cast<int>(std::clamp(std::sqrt(n * h / w), 1.0, 4096.0));
    auto cx = [&](double x) { return std::clamp(static_cast<int>((x - all.x0) / w * gx), 0, gx - 1); };
    auto cy = [&](double y) { return std::clamp(static_cast<int>((y - all.y0) / h * gy), 0, gy - 1); };
    // Counting sort of (cell, face) entries.
    std::vector<int> start(static_cast<size_t>(gx) * gy + 1, 0);
    auto each_cell = [&](int f, auto&& fn) {
      for (int j = cy(box[f].y0); j <= cy(box[f].y1); ++j)
        for (int i = cx(box[f].x0); i <= cx(box[f].x1); ++i) fn(static_cast<size_t>(j) * gx + i);
    };
    for (int f : live) each_cell(f, [&](size_t k) { ++start[k + 1]; });
    for (size_t k = 0; k + 1 < start.size(); ++k) start[k + 1] += start[k];
    std::vector<int> entry(start.back()), fill(start.begin(), start.end() - 1);
    for (int f : live) each_cell(f, [&](size_t k) { entry[fill[k]++] = f; });
    for (size_t k = 0; k + 1 < start.size(); ++k)
      for (int p = start[k]; p < start[k + 1]; ++p)
        for (int q = p + 1; q < start[k + 1]; ++q) {
          const int f = entry[p], g = entry[q];
          const Box &a = box[f], &b = box[g];
          if (a.x1 <= b.x0 || b.x1 <= a.x0 || a.y1 <= b.y0 || b.y1 <= a.y0) continue;
          // Each pair once: in the cell holding the corner of the boxes' intersection.
          if (static_cast<size_t>(cy(std::max(a.y0, b.y0))) * gx + cx(std::max(a.x0, b.x0)) != k) continue;
          if (!interiors_meet(tri[f], tri[g])) continue;
          hit[f] = hit[g] = 1;
          if (face_chart && (*face_chart)[f] != (*face_chart)[g]) ++between;
          else ++within;
        }
  }
  if (pairs_within) *pairs_within = within;
  if (pairs_between) *pairs_between = between;
  return hit;
}

}  // namespace intrinsic
