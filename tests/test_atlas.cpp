// intrinsic atlas, checked from the outside: every face gets
// finite per-corner UVs in [0,1]^2, no triangle is flipped, no two triangles
// overlap (an overlap test of its own: a uniform grid over UV space and a
// separating-axis triangle test with a small tolerance, independent of the
// packer and of the library's own checks), each chart is a disk on its corner
// mesh (V - E + F = 1, one boundary loop), on the generated closed surfaces,
// hand-made messy meshes, every patch of shared/meshes and every asset.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "intrinsic/atlas.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/generate.h"
#include "intrinsic/io.h"
#include "intrinsic/mesh.h"
#include "intrinsic/metrics.h"
#include "atlas_test_support.h"
#include "independent_stretch.h"
#include "test_support.h"

namespace intrinsic {
namespace {

using Vec2 = Eigen::Vector2d;

double twice_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

bool degenerate_3d(const MeshData& m, int f) {
  const int a = m.F(f, 0), b = m.F(f, 1), c = m.F(f, 2);
  if (a == b || b == c || a == c) return true;
  const Eigen::Vector3d x0 = m.V.row(a), x1 = m.V.row(b), x2 = m.V.row(c);
  const double longest = std::max({(x1 - x0).squaredNorm(), (x2 - x1).squaredNorm(), (x0 - x2).squaredNorm()});
  return !((x1 - x0).cross(x2 - x0).norm() > 1e-12 * longest);
}

// Separating axis test for two triangles: true when their interiors overlap
// by more than `tol` along every edge normal of both.
bool triangles_overlap(const std::array<Vec2, 3>& p, const std::array<Vec2, 3>& q, double tol) {
  for (const std::array<Vec2, 3>* t : {&p, &q})
    for (int e = 0; e < 3; ++e) {
      const Vec2 d = (*t)[(e + 1) % 3] - (*t)[e];
      if (d.norm() == 0) continue;
      const Vec2 n = Vec2(-d.y(), d.x()).normalized();
      double p0 = INFINITY, p1 = -INFINITY, q0 = INFINITY, q1 = -INFINITY;
      for (int i = 0; i < 3; ++i) {
        p0 = std::min(p0, n.dot(p[i])), p1 = std::max(p1, n.dot(p[i]));
        q0 = std::min(q0, n.dot(q[i])), q1 = std::max(q1, n.dot(q[i]));
      }
      if (p1 <= q0 + tol || q1 <= p0 + tol) return false;
    }
  return true;
}

// Pairs of UV triangles (non-zero area) whose interiors overlap.
long count_overlaps(const MatrixX3i& FUV, const MatrixX2d& UV) {
  std::vector<std::array<Vec2, 3>> tri;
  for (int f = 0; f < FUV.rows(); ++f) {
    std::array<Vec2, 3> t{UV.row(FUV(f, 0)), UV.row(FUV(f, 1)), UV.row(FUV(f, 2))};
    if (std::abs(twice_area(t[0], t[1], t[2])) > 1e-20) tri.push_back(t);
  }
  const int g = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(tri.size()))), 1, 1024);
  std::vector<std::vector<int>> cells(static_cast<size_t>(g) * g);
  auto cell = [g](double x) { return std::clamp(static_cast<int>(x * g), 0, g - 1); };
  std::vector<std::array<int, 4>> box(tri.size());
  for (size_t i = 0; i < tri.size(); ++i) {
    const auto& t = tri[i];
    box[i] = {cell(std::min({t[0].x(), t[1].x(), t[2].x()})), cell(std::max({t[0].x(), t[1].x(), t[2].x()})),
              cell(std::min({t[0].y(), t[1].y(), t[2].y()})), cell(std::max({t[0].y(), t[1].y(), t[2].y()}))};
    for (int x = box[i][0]; x <= box[i][1]; ++x)
      for (int y = box[i][2]; y <= box[i][3]; ++y) cells[x * g + y].push_back(static_cast<int>(i));
  }
  long overlaps = 0;
  for (int x = 0; x < g; ++x)
    for (int y = 0; y < g; ++y) {
      const std::vector<int>& c = cells[x * g + y];
      for (size_t s = 0; s < c.size(); ++s)
        for (size_t t = s + 1; t < c.size(); ++t) {
          const int i = c[s], j = c[t];
          // Count each pair once: in the first cell both boxes share.
          if (x != std::max(box[i][0], box[j][0]) || y != std::max(box[i][2], box[j][2])) continue;
          overlaps += triangles_overlap(tri[i], tri[j], 1e-10) ? 1 : 0;
        }
    }
  return overlaps;
}

// Each chart's corner mesh (its UV indices) is a disk, or a disk with holes
// (a flat plate with drilled holes is one chart): edges with one or two
// faces, every boundary vertex on one loop, and genus 0 (V - E + F = 2 minus
// the number of boundary loops).
void expect_disk_charts(const AtlasResult& r) {
  std::map<int, std::vector<int>> faces;
  for (size_t f = 0; f < r.face_chart.size(); ++f)
    if (r.face_chart[f] >= 0) faces[r.face_chart[f]].push_back(static_cast<int>(f));
  std::vector<int> uv_chart(r.UV.rows(), -1);
  for (const auto& [c, list] : faces) {
    std::map<std::pair<int, int>, int> edges;
    std::set<int> verts;
    for (int f : list)
      for (int i = 0; i < 3; ++i) {
        const int a = r.FUV(f, i), b = r.FUV(f, (i + 1) % 3);
        verts.insert(a);
        ++edges[{std::min(a, b), std::max(a, b)}];
        if (uv_chart[a] >= 0) EXPECT_EQ(uv_chart[a], c) << "UV " << a << " shared by two charts";
        uv_chart[a] = c;
      }
    std::map<int, std::vector<int>> boundary;
    for (const auto& [e, n] : edges) {
      ASSERT_LE(n, 2) << "chart " << c << ": edge with " << n << " faces";
      if (n == 1) boundary[e.first].push_back(e.second), boundary[e.second].push_back(e.first);
    }
    ASSERT_FALSE(boundary.empty()) << "chart " << c << " is closed";
    for (const auto& [v, nb] : boundary) ASSERT_EQ(nb.size(), 2u) << "chart " << c << ": boundary pinched at " << v;
    // Walk every loop once.
    std::set<int> walked;
    long loops = 0;
    for (const auto& [start, nb] : boundary) {
      if (walked.count(start)) continue;
      ++loops;
      int prev = -1, v = start;
      do {
        walked.insert(v);
        const int next = boundary[v][0] != prev ? boundary[v][0] : boundary[v][1];
        prev = v, v = next;
      } while (v != start && !walked.count(v));
      EXPECT_EQ(v, start) << "chart " << c << ": a boundary walk from " << start << " does not close";
    }
    EXPECT_EQ(static_cast<long>(verts.size()) - static_cast<long>(edges.size()) + static_cast<long>(list.size()),
              2 - loops)
        << "chart " << c << " (" << list.size() << " faces, " << loops << " boundary loops) is not of genus 0";
  }
}

// Everything the atlas promises, measured on the result.
void expect_valid_atlas(const MeshData& m, const AtlasResult& r) {
  ASSERT_EQ(r.FUV.rows(), m.F.rows());
  ASSERT_EQ(r.face_chart.size(), static_cast<size_t>(m.F.rows()));
  ASSERT_TRUE(r.UV.allFinite());
  EXPECT_GE(r.UV.minCoeff(), 0.0);
  EXPECT_LE(r.UV.maxCoeff(), 1.0);
  ASSERT_GE(r.FUV.minCoeff(), 0);
  ASSERT_LT(r.FUV.maxCoeff(), r.UV.rows());
  // The faces written: the input's, each as listed or (reorient) as 0, 2, 1.
  const MatrixX3i F = r.F.rows() ? r.F : m.F;
  ASSERT_EQ(F.rows(), m.F.rows());
  for (int f = 0; f < m.F.rows(); ++f) {
    const bool same = F.row(f) == m.F.row(f);
    const bool reversed = F(f, 0) == m.F(f, 0) && F(f, 1) == m.F(f, 2) && F(f, 2) == m.F(f, 1);
    EXPECT_TRUE(same || (reversed && r.cleaning.reversed_faces > 0)) << "face " << f;
  }
  long flipped = 0;
  for (int f = 0; f < m.F.rows(); ++f) {
    const double a = twice_area(r.UV.row(r.FUV(f, 0)), r.UV.row(r.FUV(f, 1)), r.UV.row(r.FUV(f, 2)));
    if (degenerate_3d(m, f)) {
      EXPECT_EQ(r.face_chart[f], -1);
      EXPECT_NEAR(a, 0.0, 1e-14);
    } else {
      EXPECT_GE(r.face_chart[f], 0) << "face " << f;
      flipped += a > 0 ? 0 : 1;  // counter-clockwise in the written corner order
    }
  }
  EXPECT_EQ(flipped, 0);
  EXPECT_EQ(r.flipped, 0);
  EXPECT_EQ(r.overlapping, 0);
  EXPECT_EQ(count_overlaps(r.FUV, r.UV), 0);
  test::expect_metrics_accept_atlas(m.V, m.F, r);  // judged again by `metrics`' own code
  expect_disk_charts(r);
  EXPECT_GT(r.utilization, 0.0);
  EXPECT_LE(r.utilization, 1.0);
}


// Distance between two UV triangles that do not overlap: the nearest pair is
// a vertex of one and an edge of the other.
double point_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double t = d.squaredNorm() > 0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}
double triangle_distance(const std::array<Vec2, 3>& p, const std::array<Vec2, 3>& q) {
  double d = INFINITY;
  for (int i = 0; i < 3; ++i)
    for (int e = 0; e < 3; ++e)
      d = std::min({d, point_segment(p[i], q[e], q[(e + 1) % 3]), point_segment(q[i], p[e], p[(e + 1) % 3])});
  return d;
}

// The smallest distance between UV triangles of different charts (pairs
// closer than `reach` are measured: a grid of cells at least that wide).
double closest_charts(const AtlasResult& r, double reach) {
  const int g = std::clamp(static_cast<int>(1 / reach), 1, 512);
  std::vector<std::vector<int>> cells(static_cast<size_t>(g) * g);
  std::vector<std::array<Vec2, 3>> tri(r.FUV.rows());
  auto cell = [g](double x) { return std::clamp(static_cast<int>(x * g), 0, g - 1); };
  for (int f = 0; f < r.FUV.rows(); ++f) {
    if (r.face_chart[f] < 0) continue;
    tri[f] = {r.UV.row(r.FUV(f, 0)), r.UV.row(r.FUV(f, 1)), r.UV.row(r.FUV(f, 2))};
    Vec2 lo = tri[f][0].cwiseMin(tri[f][1]).cwiseMin(tri[f][2]), hi = tri[f][0].cwiseMax(tri[f][1]).cwiseMax(tri[f][2]);
    for (int x = cell(lo.x() - reach); x <= cell(hi.x() + reach); ++x)
      for (int y = cell(lo.y() - reach); y <= cell(hi.y() + reach); ++y) cells[x * g + y].push_back(f);
  }
  double closest = INFINITY;
  for (const std::vector<int>& c : cells)
    for (size_t i = 0; i < c.size(); ++i)
      for (size_t j = i + 1; j < c.size(); ++j)
        if (r.face_chart[c[i]] != r.face_chart[c[j]]) closest = std::min(closest, triangle_distance(tri[c[i]], tri[c[j]]));
  return closest;
}

// Area-weighted L2 stretch in Sander et al.'s own formulation (texture to
// surface: the partial derivatives S_s, S_t of the surface point over the UV
// triangle), the UVs scaled by one factor so their total area is the
// surface's. Independent of the library's singular-value route.
double sander_l2(const MeshData& m, const AtlasResult& r) {
  const MatrixX3i& F = r.F;  // the faces as written: FUV follows their corner order
  double a3 = 0, a2 = 0;
  for (int f = 0; f < F.rows(); ++f) {
    if (r.face_chart[f] < 0) continue;
    const Eigen::Vector3d q0 = m.V.row(F(f, 0)), q1 = m.V.row(F(f, 1)), q2 = m.V.row(F(f, 2));
    a3 += 0.5 * (q1 - q0).cross(q2 - q0).norm();
    a2 += 0.5 * std::abs(twice_area(r.UV.row(r.FUV(f, 0)), r.UV.row(r.FUV(f, 1)), r.UV.row(r.FUV(f, 2))));
  }
  const double k = std::sqrt(a3 / a2);
  double sum = 0;
  for (int f = 0; f < F.rows(); ++f) {
    if (r.face_chart[f] < 0) continue;
    const Eigen::Vector3d q[3] = {m.V.row(F(f, 0)), m.V.row(F(f, 1)), m.V.row(F(f, 2))};
    Vec2 p[3];
    for (int c = 0; c < 3; ++c) p[c] = k * r.UV.row(r.FUV(f, c)).transpose();
    const double A = 0.5 * twice_area(p[0], p[1], p[2]);
    const Eigen::Vector3d Ss = (q[0] * (p[1].y() - p[2].y()) + q[1] * (p[2].y() - p[0].y()) + q[2] * (p[0].y() - p[1].y())) / (2 * A);
    const Eigen::Vector3d St = (q[0] * (p[2].x() - p[1].x()) + q[1] * (p[0].x() - p[2].x()) + q[2] * (p[1].x() - p[0].x())) / (2 * A);
    sum += 0.5 * (q[1] - q[0]).cross(q[2] - q[0]).norm() * std::sqrt(0.5 * (Ss.squaredNorm() + St.squaredNorm()));
  }
  return sum / a3;
}

// Seam edges (i, j): the two faces on each have different corner UVs at the
// edge (it is a chart boundary edge in the output). Returns the seams not cut.
int uncut_seams(const MeshData& m, const AtlasResult& r, const std::vector<SeamEdge>& seams) {
  const MatrixX3i& F = r.F;
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> corners;  // edge -> (uv at min vertex, uv at max vertex) per face
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = F(f, c), b = F(f, (c + 1) % 3);
      const int ua = r.FUV(f, c), ub = r.FUV(f, (c + 1) % 3);
      corners[{std::min(a, b), std::max(a, b)}].push_back(a < b ? std::make_pair(ua, ub) : std::make_pair(ub, ua));
    }
  int uncut = 0;
  for (const SeamEdge& e : seams) {
    const auto& list = corners[{std::min(e.a, e.b), std::max(e.a, e.b)}];
    for (size_t i = 0; i < list.size(); ++i)
      for (size_t j = i + 1; j < list.size(); ++j) uncut += list[i] == list[j] ? 1 : 0;
  }
  return uncut;
}

void check_file(const std::string& name) {
  SCOPED_TRACE(name);
  const MeshData m = read_mesh(test::shared_mesh(name));
  const auto t0 = std::chrono::steady_clock::now();
  const AtlasResult r = atlas(m);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("  %-34s %7ld faces %5zu charts %4d splits utilization %.3f stretch %.4f  %.2f s\n", name.c_str(),
              static_cast<long>(m.F.rows()), r.charts.size(), r.splits, r.utilization, r.stretch_l2_mean, s);
  expect_valid_atlas(m, r);
  // The distortion bound holds for the whole atlas, measured independently:
  // 95% of the surface within max_stretch (docs/maths.md §9.7).
  EXPECT_LE(test::quantile(test::face_stretch(m, r), 0.95), AtlasOptions().charts.max_stretch + 1e-9);
  const double l2 = sander_l2(m, r);
  EXPECT_NEAR(l2, r.stretch_l2_mean, 1e-6 * l2);
}

TEST(Atlas, GeneratedClosedSurfaces) {
  for (const char* name : {"sphere", "torus", "genus2"}) {
    SCOPED_TRACE(name);
    GenerateOptions o;
    o.rings = 14;
    const MeshData m = generate_surface(name, o);
    const AtlasResult r = atlas(m);
    expect_valid_atlas(m, r);
    EXPECT_GE(r.charts.size(), 2u);  // closed: cut
    EXPECT_EQ(r.components, 1);
    EXPECT_EQ(r.cleaning.inconsistent_edges, 0);  // consistently oriented input: nothing cut for orientation
  }
}

TEST(Atlas, ComponentsSegmentationCutsClosedSurfaces) {
  GenerateOptions o;
  o.rings = 10;
  AtlasOptions ao;
  ao.charts.segmentation = Segmentation::Components;  // one chart per piece first: the splits must cut the handles
  for (const char* name : {"sphere", "torus", "genus2"}) {
    SCOPED_TRACE(name);
    const MeshData m = generate_surface(name, o);
    const AtlasResult r = atlas(m, ao);
    expect_valid_atlas(m, r);
    EXPECT_GT(r.splits, 0);
  }
}

// Two triangles sharing only a vertex, three faces on one edge, a face listed
// backwards, a zero-area face, a repeated index, a Moebius strip.
TEST(Atlas, MessyHandMadeMeshes) {
  MeshData m;
  m.V.resize(12, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0.2, 1, 1, 1, 0.5, 0.5, 0, 2, 0, 0, 3, 0, 0, 5, 5, 5, 0, 0, 1,
      0.5, 0, -1;
  m.F.resize(9, 3);
  m.F << 0, 1, 2,   // base
      0, 3, 4,      // shares only vertex 0
      0, 2, 1,      // same edge (0,1) again, backwards: non-manifold edge, inconsistent
      1, 0, 10,     // third face on edge (0,1)
      1, 7, 8,      // zero area (collinear)
      1, 1, 5,      // repeated index
      2, 6, 5,      //
      6, 2, 0,      // listed against its neighbours
      0, 11, 1;     // fourth face on edge (0,1)
  const AtlasResult r = atlas(m);
  expect_valid_atlas(m, r);
  EXPECT_EQ(r.cleaning.degenerate_faces, 2);
  EXPECT_GE(r.cleaning.nonmanifold_edges, 1);
  EXPECT_EQ(r.cleaning.unreferenced_vertices, 1);  // vertex 9
  // Moebius strip: 2 x 8 grid glued with a half twist.
  MeshData s;
  const int n = 8;
  s.V.resize(2 * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2; ++j) {
      const double t = 2 * M_PI * i / n, w = (j - 0.5) * 0.6;
      s.V.row(2 * i + j) << (1 + w * std::cos(t / 2)) * std::cos(t), (1 + w * std::cos(t / 2)) * std::sin(t),
          w * std::sin(t / 2);
    }
  s.F.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    int a = 2 * i, b = 2 * i + 1, c = 2 * (i + 1), d = 2 * (i + 1) + 1;
    if (i == n - 1) c = 1, d = 0;  // the twist
    s.F.row(2 * i) << a, c, b;
    s.F.row(2 * i + 1) << b, c, d;
  }
  expect_valid_atlas(s, atlas(s));
}

// A curved strip of 12 quads; the second triangle of every third quad
// (faces 1, 7, 13, 19) is listed backwards.
MeshData strip_with_backwards_faces() {
  MeshData m;
  const int n = 12;
  m.V.resize(2 * (n + 1), 3);
  for (int i = 0; i <= n; ++i) {
    m.V.row(2 * i) << i, 0, 0.1 * i * i;
    m.V.row(2 * i + 1) << i, 1, 0.1 * i * i;
  }
  m.F.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i, b = 2 * i + 2, c = 2 * i + 1, d = 2 * i + 3;
    m.F.row(2 * i) << a, b, d;
    if (i % 3 == 0) m.F.row(2 * i + 1) << a, c, d;  // backwards
    else m.F.row(2 * i + 1) << a, d, c;
  }
  return m;
}

// A strip of quads whose second triangle is listed backwards in every third
// quad, with reorient off: the output keeps that winding, so each such face shares no edge with
// its neighbours in UV (a chart of its own, laid out counter-clockwise in its
// own listing) rather than being reoriented (which would mirror it).
TEST(Atlas, InconsistentOrientationIsCutNotMirrored) {
  const MeshData m = strip_with_backwards_faces();
  AtlasOptions keep;
  keep.charts.reorient = false;
  const AtlasResult r = atlas(m, keep);
  expect_valid_atlas(m, r);
  // By hand: a backwards face lists its diagonal as its quad's first face
  // does, and its left edge as the previous quad's first face does (none for
  // quad 0): 1 + 3 * 2 edges.
  EXPECT_EQ(r.cleaning.inconsistent_edges, 7);
  for (int f = 0; f < m.F.rows(); ++f) {
    if (f % 6 != 1) continue;
    SCOPED_TRACE(f);
    EXPECT_EQ(r.charts.at(r.face_chart[f]).faces, 1);
  }
}

// The same strip with reorient (the default): the backwards faces are written reversed
// (the minority of the piece), so nothing is cut and one chart remains.
TEST(Atlas, ReorientWritesTheMinorityReversed) {
  const MeshData m = strip_with_backwards_faces();
  const AtlasResult r = atlas(m);
  expect_valid_atlas(m, r);
  EXPECT_EQ(r.cleaning.inconsistent_edges, 7);
  EXPECT_EQ(r.cleaning.reversed_faces, 4);
  EXPECT_EQ(r.cleaning.orientation_cuts, 0);
  EXPECT_EQ(r.charts.size(), 1u);
  for (int f = 0; f < m.F.rows(); ++f) {
    SCOPED_TRACE(f);
    if (f % 6 == 1) EXPECT_EQ(r.F.row(f), Eigen::RowVector3i(m.F(f, 0), m.F(f, 2), m.F(f, 1)));
    else EXPECT_EQ(r.F.row(f), m.F.row(f));
  }
  AtlasOptions keep;
  keep.charts.reorient = false;
  EXPECT_EQ(atlas(m, keep).F, m.F);  // without it the input's winding is kept
}

// A closed surface with every third face listed backwards, through the CLI
// with --keep-winding: the written faces are the input's (winding kept), and `metrics`' own code
// finds no flipped triangle and no chart mirrored against that winding.
TEST(AtlasCli, ReversedFacesKeepWindingNoneMirrored) {
  test::TempDir dir;
  GenerateOptions o;
  o.rings = 10;
  MeshData m = generate_surface("sphere", o);
  for (int f = 0; f < m.F.rows(); f += 3) std::swap(m.F(f, 1), m.F(f, 2));
  const std::string in = dir / "in.obj", out = dir / "out.obj";
  write_mesh(in, m.V, m.F, MatrixX2d());
  ASSERT_EQ(test::run_cli("atlas " + in + " -o " + out + " --keep-winding -q", dir).code, 0);
  const MeshData src = read_mesh(in), back = read_mesh(out);
  EXPECT_EQ(back.F, src.F);
  ASSERT_TRUE(back.has_uv());
  MatrixX3d PT = MatrixX3d::Zero(back.TC.rows(), 3);
  for (int f = 0; f < back.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) PT.row(back.FTC(f, c)) = back.V.row(back.F(f, c));
  const UvAtlasMetrics um = uv_atlas_metrics(PT, back.FTC, back.TC);
  EXPECT_EQ(um.flipped_triangles, 0);
  EXPECT_EQ(um.collapsed_triangles, 0);
  EXPECT_EQ(um.mirrored_charts, 0);
  EXPECT_EQ(um.overlapping_triangles, 0);
  for (int f = 0; f < back.F.rows(); ++f) {  // and counter-clockwise face by face, in the file's corner order
    const Vec2 a = back.TC.row(back.FTC(f, 0)), b = back.TC.row(back.FTC(f, 1)), c = back.TC.row(back.FTC(f, 2));
    EXPECT_GT(twice_area(a, b, c), 0) << f;
  }
  // By default the reversed third is written back: the generated surface's
  // own faces, and as many charts as the atlas of that surface.
  const std::string fixed = dir / "fixed.obj", rep = dir / "r.json";
  ASSERT_EQ(test::run_cli("atlas " + in + " -o " + fixed + " --report " + rep + " -q", dir).code, 0);
  const MeshData original = generate_surface("sphere", o), again = read_mesh(fixed);
  EXPECT_EQ(again.F, original.F);
  const nlohmann::json j = nlohmann::json::parse(test::slurp(rep));
  EXPECT_EQ(j.at("charts").get<size_t>(), atlas(original).charts.size());
  EXPECT_EQ(j.at("cleaning").at("reversed_faces").get<long>(), (m.F.rows() + 2) / 3);
}

TEST(Atlas, DeterministicAndIndependentOfNothingElse) {
  GenerateOptions o;
  o.rings = 12;
  const MeshData m = generate_genus2(o);
  const AtlasResult a = atlas(m), b = atlas(m);
  EXPECT_EQ(a.UV, b.UV);
  EXPECT_EQ(a.FUV, b.FUV);
  EXPECT_EQ(a.face_chart, b.face_chart);
}

TEST(Atlas, BadInputIsRefusedClearly) {
  MeshData m;
  m.V.resize(3, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  m.F.resize(1, 3);
  m.F << 0, 1, 5;
  test::expect_error([&] { atlas(m); }, ErrorKind::Input, "refers to vertex 5");
  m.F << 0, 1, 2;
  m.V(1, 0) = NAN;
  test::expect_error([&] { atlas(m); }, ErrorKind::Input, "non-finite");
  m.V(1, 0) = 1;
  AtlasOptions o;
  o.pack.padding = -1;
  test::expect_error([&] { atlas(m, o); }, ErrorKind::Usage, "padding");
  MeshData empty;
  test::expect_error([&] { atlas(empty); }, ErrorKind::Input, "no vertices");
}

TEST(AtlasCorpus, SmallPatchesAndAssets) {
  REQUIRE_SHARED_MESHES();
  for (const char* name : {"cat_head.obj", "snail.obj", "camel_b.obj", "inspired_mesh.obj", "alligator.obj",
                           "maze.obj", "fairing-cross.off", "assets/decimated-knight.off", "assets/suzanne.obj",
                           "assets/horse_quad.obj", "assets/spot.obj", "assets/teapot.obj", "assets/truck.obj",
                           "assets/3holes.off", "assets/fertility.off", "assets/screwdriver.off"})
    check_file(name);
}

TEST(AtlasCorpus, LargePatches) {
  REQUIRE_SHARED_MESHES();
  for (const char* name : {"animal.obj", "beetle.off", "camelhead.off", "face-bff.obj", "inverted-triangles.obj",
                           "max-planck-partial.obj", "stanford-bunny.obj"})
    check_file(name);
}

TEST(AtlasCorpus, LargeAssets) {
  REQUIRE_SHARED_MESHES();
  for (const char* name : {"assets/cheburashka.obj", "assets/decimated-max.obj", "assets/arm.obj",
                           "assets/bumpy-cube.obj", "assets/beast.obj.gz", "assets/rocker-arm.obj",
                           "assets/ogre.obj.gz"})
    check_file(name);
}

// inverted-triangles.obj lists 42% of its faces against the rest: with
// --keep-winding each such edge is cut (thousands of charts); with reorient the
// reversed faces are the ones the shared meshes' README counts, and the faces
// written are consistently oriented.
TEST(AtlasCorpus, ReorientInvertedTriangles) {
  REQUIRE_SHARED_MESHES();
  const MeshData m = read_mesh(test::shared_mesh("inverted-triangles.obj"));
  const AtlasResult r = atlas(m);
  expect_valid_atlas(m, r);
  EXPECT_EQ(r.cleaning.reversed_faces, 10408);  // README: "10,408 faces (42 %) must be flipped"
  EXPECT_EQ(r.cleaning.orientation_cuts, 0);
  MeshData fixed = m;
  fixed.F = r.F;
  const AtlasResult again = atlas(fixed);
  EXPECT_EQ(again.cleaning.inconsistent_edges, 0);  // the faces written agree everywhere
  expect_valid_atlas(fixed, again);
}

TEST(AtlasCorpus, LargeAssetIgea) {
  REQUIRE_SHARED_MESHES();
  // igea.ply stores its faces as one `tristrips` element (134k vertices).
  check_file("assets/igea.ply.gz");
}


// Packing: `padding` texels (of a `resolution` texture) between any two
// charts' UV triangles and half of it (rounded up) around the border, measured on the triangles;
// the reported utilization is the UV triangles' own area.
void expect_padding_and_utilization(const MeshData& m) {
  for (const auto& [res, pad] : {std::pair<int, double>{256, 3}, {1024, 2}, {128, 0}}) {
    SCOPED_TRACE(res);
    AtlasOptions o;
    o.pack.resolution = res;
    o.pack.padding = pad;
    const AtlasResult r = atlas(m, o);
    expect_valid_atlas(m, r);
    const double gap = pad / res, border = std::ceil(pad / 2) / res;
    double area = 0;
    for (int f = 0; f < m.F.rows(); ++f) {
      if (r.face_chart[f] < 0) continue;
      area += 0.5 * std::abs(twice_area(r.UV.row(r.FUV(f, 0)), r.UV.row(r.FUV(f, 1)), r.UV.row(r.FUV(f, 2))));
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 2; ++k) {
          EXPECT_GE(r.UV(r.FUV(f, c), k), border * (1 - 1e-9));
          EXPECT_LE(r.UV(r.FUV(f, c), k), 1 - border * (1 - 1e-9));
        }
    }
    EXPECT_NEAR(r.utilization, area, 1e-9);
    if (pad > 0) EXPECT_GE(closest_charts(r, 2 * gap), gap * (1 - 1e-9));
  }
}

TEST(AtlasPacking, PaddingBetweenChartsAndBorderUtilizationMeasured) {
  GenerateOptions g;
  g.rings = 14;
  expect_padding_and_utilization(generate_genus2(g));
}

TEST(AtlasPackingCorpus, PaddingBetweenChartsAndBorderUtilizationMeasured) {
  REQUIRE_SHARED_MESHES();
  expect_padding_and_utilization(read_mesh(test::shared_mesh("assets/spot.obj")));
}

// A bumped grid cut straight across by a row of seam edges: exactly two
// charts (the pieces between the seams; each a valid disk, so no other
// cut), and every seam edge is a chart boundary in the output.
TEST(AtlasSeams, CutExactlyThereAndNowhereElseOnAPatch) {
  const int n = 9;
  MeshData m;
  m.V.resize(n * n, 3);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) m.V.row(y * n + x) << x, y, 0.1 * std::sin(x) * std::cos(y);
  m.F.resize(2 * (n - 1) * (n - 1), 3);
  for (int y = 0, f = 0; y + 1 < n; ++y)
    for (int x = 0; x + 1 < n; ++x) {
      const int a = y * n + x;
      m.F.row(f++) << a, a + 1, a + n + 1;
      m.F.row(f++) << a, a + n + 1, a + n;
    }
  AtlasOptions o;
  for (int x = 0; x + 1 < n; ++x) o.charts.seams.push_back({4 * n + x, 4 * n + x + 1});  // row y = 4
  const AtlasResult r = atlas(m, o);
  expect_valid_atlas(m, r);
  EXPECT_EQ(r.charts.size(), 2u);
  EXPECT_EQ(uncut_seams(m, r, o.charts.seams), 0);
  // Seam length: the listed edges' lengths, summed here. Each chart's
  // boundary: the seam plus its half of the patch's border, so the two
  // boundaries add up to twice the seam plus the border, measured here too.
  double seam = 0, border = 0;
  for (const SeamEdge& e : o.charts.seams) seam += (m.V.row(e.a) - m.V.row(e.b)).norm();
  for (int k = 0; k + 1 < n; ++k)
    for (auto [a, b] : {std::pair{k, k + 1}, {k * n, (k + 1) * n}, {k * n + n - 1, (k + 1) * n + n - 1},
                        {(n - 1) * n + k, (n - 1) * n + k + 1}})
      border += (m.V.row(a) - m.V.row(b)).norm();
  EXPECT_NEAR(r.seam_length, seam, 1e-12 * seam);
  EXPECT_NEAR(r.charts[0].boundary_length + r.charts[1].boundary_length, 2 * seam + border, 1e-12 * border);
  // Without the seams the patch is one chart, bounded by the border alone.
  const AtlasResult whole = atlas(m);
  EXPECT_EQ(whole.charts.size(), 1u);
  EXPECT_EQ(whole.seam_length, 0.0);
  EXPECT_NEAR(whole.charts[0].boundary_length, border, 1e-12 * border);
}

// Zero-area faces on a hand-made patch: a sliver (its third vertex on the
// middle of the opposite edge), a face with a repeated vertex and a face
// whose three corners are at one point. None is a chart in the report; in
// `metrics` the first two share a UV edge with a chart (so they are not
// components of their own) and only the point face, which has no edge to
// share, forms a component of zero-area faces.
TEST(Atlas, ZeroAreaFacesFormNoChartsOfTheirOwn) {
  MeshData m;
  m.V.resize(7, 3);
  m.V << 0, 0, 0,  // a
      1, 0, 0,     // b
      0.5, 0, 0,   // m: on the edge a b
      0.5, 1, 0,   // t
      0.5, -1, 0,  // l
      0.5, 1, 0,   // t again, twice
      0.5, 1, 0;
  m.F.resize(6, 3);
  m.F << 0, 1, 3,  // above a b
      0, 4, 2, 2, 4, 1,  // below, through m
      0, 2, 1,  // the sliver
      3, 3, 1,  // a repeated vertex
      3, 5, 6;  // one point
  const AtlasResult r = atlas(m);
  expect_valid_atlas(m, r);
  EXPECT_EQ(r.cleaning.degenerate_faces, 3);
  EXPECT_EQ(r.charts.size(), 2u);
  const UvAtlasMetrics um = test::measure_atlas(m.V, m.F, r);
  EXPECT_EQ(um.degenerate_charts, 1);
  EXPECT_EQ(um.charts.size(), 3u);
  for (int f : {3, 4}) EXPECT_FALSE(um.charts[um.face_chart[f]].degenerate) << f;
  EXPECT_TRUE(um.charts[um.face_chart[5]].degenerate);
}

// Scattered seams on closed surfaces (slits that end inside a chart too):
// every one is cut, the atlas stays valid.
TEST(AtlasSeams, EverySeamIsCutOnClosedSurfaces) {
  for (const char* name : {"sphere", "torus"}) {
    SCOPED_TRACE(name);
    GenerateOptions g;
    g.rings = 10;
    const MeshData m = generate_surface(name, g);
    AtlasOptions o;
    std::set<std::pair<int, int>> seen;
    for (int f = 0; f < m.F.rows(); f += 7) {
      const int a = m.F(f, 0), b = m.F(f, 1);
      if (seen.insert({std::min(a, b), std::max(a, b)}).second) o.charts.seams.push_back({a, b});
    }
    const AtlasResult r = atlas(m, o);
    expect_valid_atlas(m, r);
    EXPECT_EQ(uncut_seams(m, r, o.charts.seams), 0);
    EXPECT_GT(uncut_seams(m, atlas(m), o.charts.seams), 0);  // the check sees uncut seams
  }
}

TEST(AtlasSeams, BadSeamsAreRefused) {
  MeshData m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 1, 3, 2;
  EXPECT_EQ(parse_seams_text("# the shared edge\n1 2\n\n2 1  # again\n", "s.txt", m).size(), 1u);
  test::expect_error([&] { parse_seams_text("0 3\n", "s.txt", m); }, ErrorKind::Input, "s.txt:1: vertices 0 and 3 are not an edge");
  test::expect_error([&] { parse_seams_text("1 2\n0 4\n", "s.txt", m); }, ErrorKind::Input, "s.txt:2: vertex 4 is out of range");
  test::expect_error([&] { parse_seams_text("0 -1\n", "s.txt", m); }, ErrorKind::Input, "out of range");
  test::expect_error([&] { parse_seams_text("0\n", "s.txt", m); }, ErrorKind::Input, "s.txt:1: expected 'i j'");
  test::expect_error([&] { parse_seams_text("0 1 2\n", "s.txt", m); }, ErrorKind::Input, "s.txt:1: unexpected '2'");
  test::expect_error([&] { parse_seams_text("0 x\n", "s.txt", m); }, ErrorKind::Input, "'x' is not a vertex index");
  test::expect_error([&] { parse_seams_text("1 1\n", "s.txt", m); }, ErrorKind::Input, "not an edge");
  test::expect_error([&] { parse_seams_text("# nothing\n\n", "s.txt", m); }, ErrorKind::Input, "s.txt: no seam edges");
  test::expect_error([&] { read_seams_file("/nonexistent/seams.txt", m); }, ErrorKind::Input, "cannot open");
  AtlasOptions o;
  o.charts.seams = {{0, 3}};
  test::expect_error([&] { atlas(m, o); }, ErrorKind::Input, "seam edge 0: vertices 0 and 3 are not an edge");
  o.charts.seams = {{0, 9}};
  test::expect_error([&] { atlas(m, o); }, ErrorKind::Input, "out of range");
  // One check (find_seam_problem): the library names the seam's index, the
  // file reader maps it to the line that listed it (a repeated line skipped).
  o.charts.seams = {{1, 2}, {2, 3}, {3, 0}};
  test::expect_error([&] { atlas(m, o); }, ErrorKind::Input, "seam edge 2: vertices 3 and 0 are not an edge");
  EXPECT_EQ(find_seam_problem(m, o.charts.seams).index, 2);
  EXPECT_EQ(find_seam_problem(m, {{1, 2}, {2, 3}}).index, -1);
  test::expect_error([&] { parse_seams_text("1 2\n2 1\n# c\n\n2 3\n3 0\n", "s.txt", m); }, ErrorKind::Input,
                     "s.txt:6: vertices 3 and 0 are not an edge");
}

TEST(AtlasCli, SeamsFileOptionsAndErrors) {
  test::TempDir dir;
  const std::string g = dir / "g.obj", out = dir / "out.obj", seams = dir / "seams.txt";
  ASSERT_EQ(test::run_cli("generate torus --rings 8 -o " + g, dir).code, 0);
  const MeshData m = read_mesh(g);
  std::vector<SeamEdge> list;
  std::string text = "# seams\n";
  for (int f = 0; f < m.F.rows(); f += 5) {
    list.push_back({m.F(f, 1), m.F(f, 2)});
    text += std::to_string(m.F(f, 1)) + " " + std::to_string(m.F(f, 2)) + "\n";
  }
  test::write_text(seams, text);
  ASSERT_EQ(test::run_cli("atlas " + g + " -o " + out + " --seams " + seams + " --max-stretch 1.2 --max-charts 50 -q", dir).code, 0);
  const MeshData back = read_mesh(out);
  AtlasResult r;
  r.UV = back.TC;
  r.FUV = back.FTC;
  EXPECT_EQ(uncut_seams(m, r, list), 0);
  // A non-edge, an out-of-range index, a malformed line, an empty file: exit 2, file and line named, no output.
  int far = 1;
  std::set<int> near;
  for (int f = 0; f < m.F.rows(); ++f)
    if (m.F(f, 0) == 0 || m.F(f, 1) == 0 || m.F(f, 2) == 0) near.insert({m.F(f, 0), m.F(f, 1), m.F(f, 2)});
  while (near.count(far)) ++far;
  for (const auto& [body, message] :
       {std::pair<std::string, std::string>{"0 " + std::to_string(far) + "\n", "bad.txt:1: vertices 0 and"},
        {"# x\n0 99999999\n", "bad.txt:2: vertex 99999999 is out of range"},
        {"0 1 x\n", "bad.txt:1: unexpected 'x'"},
        {"", "bad.txt: no seam edges"}}) {
    SCOPED_TRACE(body);
    test::write_text(dir / "bad.txt", body);
    const test::CliResult bad = test::run_cli("atlas " + g + " -o " + dir / "x.obj --seams " + dir / "bad.txt", dir);
    EXPECT_EQ(bad.code, 2);
    EXPECT_NE(bad.err.find(message), std::string::npos) << bad.err;
    EXPECT_FALSE(std::ifstream(dir / "x.obj").good());
  }
}

// --max-charts merges past the stretch bound while the union stays valid.
void expect_max_charts_merges(const MeshData& m, AtlasOptions o = {}) {
  const AtlasResult free = atlas(m, o);
  o.charts.max_charts = std::max<int>(1, static_cast<int>(free.charts.size()) / 2);
  const AtlasResult fewer = atlas(m, o);
  expect_valid_atlas(m, fewer);
  EXPECT_LE(static_cast<int>(fewer.charts.size()), o.charts.max_charts);
}

// A sphere cap under a tight stretch bound: 7 charts, merged down to 3
// (closed generated surfaces have too few charts whose unions stay disks).
TEST(Atlas, MaxChartsMergesFurther) {
  GenerateOptions g;
  g.rings = 14;
  AtlasOptions o;
  o.charts.max_stretch = 1.01;
  const MeshData cap = generate_sphere_cap(g);
  ASSERT_GE(atlas(cap, o).charts.size(), 4u);
  expect_max_charts_merges(cap, o);
}

TEST(AtlasCorpus, MaxChartsMergesFurther) {
  REQUIRE_SHARED_MESHES();
  expect_max_charts_merges(read_mesh(test::shared_mesh("assets/spot.obj")));
}

// The atlas-wide stretch budget: a small closed part next to a large one
// merges past max_stretch into fewer charts, while the whole atlas's 95th
// percentile of per-face stretch (recomputed here from the output UVs and
// the input positions) stays within max_stretch.
TEST(Atlas, AtlasStretchBudgetMergesSmallParts) {
  GenerateOptions g;
  g.rings = 24;
  const MeshData torus = generate_torus(g);
  g.rings = 10;
  const MeshData sphere = generate_bumpy_sphere(g);
  MeshData m;
  m.V.resize(torus.V.rows() + sphere.V.rows(), 3);
  m.V << torus.V, (0.1 * sphere.V).rowwise() + Eigen::RowVector3d(3, 0, 0);  // stretch is scale-free: only its weight shrinks
  m.F.resize(torus.F.rows() + sphere.F.rows(), 3);
  m.F << torus.F, sphere.F.array() + static_cast<int>(torus.V.rows());
  auto small_part_charts = [&](const AtlasResult& r) {
    std::set<int> charts;
    for (int f = static_cast<int>(torus.F.rows()); f < m.F.rows(); ++f) charts.insert(r.face_chart[f]);
    return charts.size();
  };
  AtlasOptions per_chart;
  per_chart.charts.atlas_stretch_budget = false;
  const AtlasResult bounded = atlas(m, per_chart);
  const AtlasResult budget = atlas(m);
  expect_valid_atlas(m, budget);
  std::printf("  small part: %zu charts per chart bound, %zu with the atlas budget; atlas stretch %.4f / %.4f\n",
              small_part_charts(bounded), small_part_charts(budget), sander_l2(m, bounded), sander_l2(m, budget));
  EXPECT_LT(small_part_charts(budget), small_part_charts(bounded));
  EXPECT_LE(budget.charts.size(), bounded.charts.size());
  // The bound is on the whole atlas's 95th percentile of per-face stretch.
  EXPECT_LE(test::quantile(test::face_stretch(m, budget), 0.95), AtlasOptions().charts.max_stretch + 1e-9);
}

// `intrinsic atlas` on the mesh file `in`: the same bytes twice, the input's
// vertices and faces kept, a valid atlas read back, the report's keys.
void expect_atlas_cli_output(const std::string& in, const test::TempDir& dir) {
  const std::string a = dir / "a.obj", b = dir / "b.obj", rep = dir / "r.json";
  ASSERT_EQ(test::run_cli("atlas " + in + " -o " + a + " --report " + rep + " -q", dir).code, 0);
  ASSERT_EQ(test::run_cli("atlas " + in + " -o " + b + " -q", dir).code, 0);
  EXPECT_EQ(test::slurp(a), test::slurp(b));  // same input, same bytes
  const MeshData src = read_mesh(in), out = read_mesh(a);
  EXPECT_EQ(out.V, src.V);  // positions and order unchanged
  EXPECT_EQ(out.F, src.F);
  ASSERT_TRUE(out.has_uv());
  AtlasResult r;
  r.UV = out.TC;
  r.FUV = out.FTC;
  const AtlasResult lib = atlas(src);
  r.face_chart = lib.face_chart;
  r.charts = lib.charts;
  r.utilization = lib.utilization;
  expect_valid_atlas(src, r);  // what the file holds, read back
  const std::string report = test::slurp(rep);
  for (const char* key : {"\"charts\"", "\"utilization\"", "\"flipped\": 0", "\"overlapping\": 0", "\"cleaning\"",
                          "\"nonmanifold_vertices\"", "\"timings_ms\"", "\"flatten\"", "\"chart_list\""})
    EXPECT_NE(report.find(key), std::string::npos) << key;
}

TEST(AtlasCli, KeepsVerticesWritesCornersDeterministic) {
  test::TempDir dir;
  ASSERT_EQ(test::run_cli("generate genus2 --rings 10 -o " + (dir / "g.obj"), dir).code, 0);
  expect_atlas_cli_output(dir / "g.obj", dir);
}

TEST(AtlasCliCorpus, KeepsVerticesWritesCornersDeterministic) {
  REQUIRE_SHARED_MESHES();
  test::TempDir dir;
  expect_atlas_cli_output(test::shared_mesh("assets/teapot.obj"), dir);
}

TEST(AtlasCli, ClosedSurfaceFromGenerateAndErrors) {
  test::TempDir dir;
  const std::string g = dir / "g.obj", out = dir / "out.obj";
  ASSERT_EQ(test::run_cli("generate genus2 --rings 8 -o " + g, dir).code, 0);
  const test::CliResult param = test::run_cli("param " + g + " -o " + out, dir);
  EXPECT_EQ(param.code, 2);
  EXPECT_NE(param.err.find("intrinsic atlas"), std::string::npos) << param.err;
  EXPECT_EQ(test::run_cli("atlas " + g + " -o " + out + " -q", dir).code, 0);
  const test::CliResult missing = test::run_cli("atlas " + dir / "none.obj -o " + dir / "x.obj", dir);
  EXPECT_EQ(missing.code, 2);
  const test::CliResult ply = test::run_cli("atlas " + g + " -o " + dir / "x.ply", dir);
  EXPECT_EQ(ply.code, 1);
  EXPECT_NE(ply.err.find(".obj"), std::string::npos);
  EXPECT_FALSE(std::ifstream(dir / "x.obj").good());
  EXPECT_FALSE(std::ifstream(dir / "x.ply").good());
}

}  // namespace
}  // namespace intrinsic

namespace intrinsic {
namespace {

// The atlas's UVs of `m` equal `expected` (per input vertex) up to a
// similarity without reflection: distances from two far-apart vertices scale
// by one factor (which fixes every point up to a reflection) and no face of
// the atlas is flipped (expect_valid_atlas), so the reflection is excluded.
// The atlas's map of the single chart is `expected` up to a similarity (the
// packing's).
void expect_similar(const MeshData& m, const AtlasResult& r, const MatrixX2d& expected) {
  MatrixX2d uv(m.V.rows(), 2);
  for (int f = 0; f < m.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) uv.row(r.F(f, c)) = r.UV.row(r.FUV(f, c));
  int far = 1;
  for (int v = 1; v < m.V.rows(); ++v)
    if ((expected.row(v) - expected.row(0)).norm() > (expected.row(far) - expected.row(0)).norm()) far = v;
  const double s = (uv.row(far) - uv.row(0)).norm() / (expected.row(far) - expected.row(0)).norm();
  for (int v = 0; v < m.V.rows(); ++v)
    for (const int ref : {0, far}) {
      SCOPED_TRACE(v);
      EXPECT_NEAR((uv.row(v) - uv.row(ref)).norm(), s * (expected.row(v) - expected.row(ref)).norm(), 1e-9);
    }
}

// Issue 13 item 3: every `param` map per chart. One chart per piece
// (Components segmentation, a loose stretch bound), a spherical cap: the
// chart's map equals `param`'s map of the cap with the same options, up to
// the packing's similarity, for a fixed circle, a fixed square with authalic
// weights, optimal lambda and boundary optimization.
TEST(Atlas, EveryParamMapPerChart) {
  GenerateOptions g;
  g.rings = 8;
  const MeshData m = generate_sphere_cap(g);
  const Mesh mesh = make_mesh(m);
  AtlasOptions o;
  o.charts.segmentation = Segmentation::Components;
  o.charts.max_stretch = 100;
  o.charts.max_face_stretch = 1e6;  // a circle boundary on a cap stretches its rim faces more than 2x
  o.pack.padding = 0;
  struct Case {
    ChartMapOptions map;
    ChartMethod method;
  };
  std::vector<Case> cases(4);
  cases[0].map.boundary = BoundaryShape::Circle;
  cases[0].method = ChartMethod::FixedBoundary;
  cases[1].map.boundary = BoundaryShape::Square;
  cases[1].map.weights.method = Method::Authalic;
  cases[1].method = ChartMethod::FixedBoundary;
  cases[2].map.boundary = BoundaryShape::Circle;
  cases[2].map.optimizer = ChartOptimizer::OptimalLambda;
  cases[2].method = ChartMethod::OptimalLambda;
  cases[3].map.boundary = BoundaryShape::Circle;
  cases[3].map.optimizer = ChartOptimizer::OptimizeBoundary;
  cases[3].map.boundary_energy = BoundaryEnergy::Area;
  cases[3].method = ChartMethod::OptimizedBoundary;
  for (size_t k = 0; k < cases.size(); ++k) {
    SCOPED_TRACE(k);
    o.charts.chart_map = cases[k].map;
    const AtlasResult r = atlas(m, o);
    expect_valid_atlas(m, r);
    ASSERT_EQ(r.charts.size(), 1u);
    EXPECT_EQ(r.charts[0].method, cases[k].method);
    ParamOptions p;
    p.boundary = cases[k].map.boundary;
    p.weights = cases[k].map.weights;
    MatrixX2d expected;
    if (k == 2) {
      OptimalLambdaOptions l;
      l.base = p;
      expected = optimal_lambda(mesh, l).map.UV;
    } else if (k == 3) {
      // A nonlinear descent: its line searches stop where rounding takes
      // them, so the cap is given in the chart's own vertex numbering (first
      // corner first, as the atlas numbers a chart): the same matrix, the
      // same elimination order, the same arithmetic.
      std::vector<int> local(m.V.rows(), -1), input;
      MeshData renumbered = m;
      for (int f = 0; f < m.F.rows(); ++f)
        for (int c = 0; c < 3; ++c) {
          int& l = local[m.F(f, c)];
          if (l < 0) {
            l = static_cast<int>(input.size());
            input.push_back(m.F(f, c));
          }
          renumbered.F(f, c) = l;
        }
      for (size_t l = 0; l < input.size(); ++l) renumbered.V.row(static_cast<int>(l)) = m.V.row(input[l]);
      BoundaryOptimizationOptions b;
      b.base = p;
      b.energy = BoundaryEnergy::Area;
      const MatrixX2d in_chart_order = optimize_boundary(make_mesh(renumbered), b).map.UV;
      expected.resize(m.V.rows(), 2);
      for (size_t l = 0; l < input.size(); ++l) expected.row(input[l]) = in_chart_order.row(static_cast<int>(l));
    } else {
      expected = parameterize(mesh, p).UV;
    }
    expect_similar(m, r, expected);
  }
  // A chart map that cannot be is refused before any work.
  o.charts.chart_map = ChartMapOptions();
  o.charts.chart_map.optimizer = ChartOptimizer::OptimalLambda;
  test::expect_error([&] { atlas(m, o); }, ErrorKind::Usage, "fixed chart boundary");
}

// The command line spells the chart map as `param` does; --method without a
// fixed boundary is refused, with no output.
TEST(AtlasCli, ChartMapOptions) {
  test::TempDir dir;
  GenerateOptions g;
  g.rings = 10;
  const std::string in = dir / "t.obj", out = dir / "o.obj", rep = dir / "r.json";
  const MeshData m = generate_torus(g);
  write_mesh(in, m.V, m.F, MatrixX2d());
  const auto ok = test::run_cli("atlas " + in + " -o " + out + " --report " + rep +
                                    " --boundary square --method mixed --lambda 0.5 --max-stretch 3 -q",
                                dir);
  ASSERT_EQ(ok.code, 0) << ok.err;
  const nlohmann::json j = nlohmann::json::parse(test::slurp(rep));
  EXPECT_EQ(j.at("chart_map").at("boundary"), "square");
  EXPECT_EQ(j.at("chart_map").at("method"), "mixed");
  EXPECT_EQ(j.at("flipped"), 0);
  EXPECT_EQ(j.at("overlapping"), 0);
  for (const auto& c : j.at("chart_list"))
    EXPECT_TRUE(c.at("method") == "fixed-boundary" || c.at("method") == "triangle") << c.at("method");
  const std::string bad = dir / "bad.obj";
  EXPECT_NE(test::run_cli("atlas " + in + " -o " + bad + " --method authalic -q", dir).code, 0);
  EXPECT_NE(test::run_cli("atlas " + in + " -o " + bad + " --optimize-lambda edge -q", dir).code, 0);
  EXPECT_FALSE(std::filesystem::exists(bad));
}

}  // namespace
}  // namespace intrinsic
