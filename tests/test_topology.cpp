// Validation: each refused kind of mesh gets a message naming the element;
// orientation repair, loops and components are counted right.
#include <gtest/gtest.h>

#include <map>

#include "intrinsic/error.h"
#include "intrinsic/generate.h"
#include "test_support.h"

namespace intrinsic {
namespace {

void expect_refused(const MatrixX3d& V, const MatrixX3i& F, const std::string& fragment) {
  test::expect_error([&] { make_mesh(V, F); }, ErrorKind::Input, fragment);
}

MatrixX3d grid_vertices(int n) {
  MatrixX3d V((n + 1) * (n + 1), 3);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) V.row(i * (n + 1) + j) << j, i, 0.1 * i * j;
  return V;
}

MatrixX3i grid_faces(int n) {
  MatrixX3i F(2 * n * n, 3);
  int f = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
      F.row(f++) << a, b, d;
      F.row(f++) << a, d, c;
    }
  return F;
}

TEST(Topology, GridDisk) {
  const Mesh m = make_mesh(grid_vertices(4), grid_faces(4));
  EXPECT_EQ(m.topology.boundary_loops.size(), 1u);
  EXPECT_EQ(m.topology.boundary_loops[0].size(), 16u);
  EXPECT_EQ(m.topology.num_components, 1);
  EXPECT_EQ(m.validation.reoriented_faces, 0);
  // The interior lies left of the boundary loop: the loop runs counter-clockwise.
  double area = 0;
  const auto& loop = m.topology.boundary_loops[0];
  for (size_t k = 0; k < loop.size(); ++k) {
    const auto a = m.V.row(loop[k]), b = m.V.row(loop[(k + 1) % loop.size()]);
    area += a.x() * b.y() - b.x() * a.y();
  }
  EXPECT_GT(area, 0);
}

TEST(Topology, InconsistentOrientationIsRepairedAndCounted) {
  MatrixX3i F = grid_faces(4);
  for (int f : {3, 7, 8}) std::swap(F(f, 1), F(f, 2));
  const Mesh m = make_mesh(grid_vertices(4), F);
  EXPECT_EQ(m.validation.reoriented_faces, 3);
  EXPECT_EQ(m.F, grid_faces(4));
}

// Twins against a plain map of directed edges, whether validation kept the
// adjacency of its orientation pass (nothing flipped) or rebuilt it (faces
// flipped), on a generated irregular disk.
TEST(Topology, TwinsMatchADirectedEdgeMap) {
  const MeshData d = generate_wavy_patch([] { GenerateOptions g; g.rings = 30; return g; }());
  MatrixX3i flipped = d.F;
  for (int f = 0; f < flipped.rows(); f += 97) std::swap(flipped(f, 1), flipped(f, 2));
  for (const MatrixX3i& F : {d.F, flipped}) {
    const Mesh m = make_mesh(d.V, F);
    EXPECT_EQ(m.F, d.F);
    std::map<std::pair<int, int>, int> directed;
    for (int h = 0; h < 3 * static_cast<int>(m.F.rows()); ++h) directed[{m.source(h), m.target(h)}] = h;
    int boundary = 0;
    for (int h = 0; h < 3 * static_cast<int>(m.F.rows()); ++h) {
      const auto it = directed.find({m.target(h), m.source(h)});
      EXPECT_EQ(m.topology.twin[h], it == directed.end() ? -1 : it->second);
      boundary += it == directed.end();
    }
    EXPECT_EQ(static_cast<size_t>(boundary), m.topology.boundary_loops[0].size());
  }
}

TEST(Topology, UnreferencedVerticesAreCounted) {
  MatrixX3d V = grid_vertices(2);
  V.conservativeResize(V.rows() + 2, 3);
  V.bottomRows(2).setConstant(5.0);
  const Mesh m = make_mesh(V, grid_faces(2));
  EXPECT_EQ(m.validation.unreferenced_vertices, 2);
}

TEST(Topology, RefusedMeshes) {
  const MatrixX3d V = grid_vertices(2);
  MatrixX3i F = grid_faces(2);
  {
    MatrixX3i G = F;
    G(2, 1) = 99;
    expect_refused(V, G, "face 2 refers to vertex 99");
  }
  {
    MatrixX3i G = F;
    G(1, 2) = G(1, 0);
    expect_refused(V, G, "face 1 repeats vertex");
  }
  {
    MatrixX3d W = V;
    W(4, 1) = NAN;
    expect_refused(W, F, "vertex 4 has a non-finite coordinate");
  }
  {
    MatrixX3d W = V;
    W.row(4) = W.row(0);  // faces touching 0 and 4 collapse
    expect_refused(W, F, "is degenerate");
  }
  {
    // A third face on the interior edge (0, 4).
    MatrixX3d W(V.rows() + 1, 3);
    W << V, Eigen::RowVector3d(0.5, 0.5, 3);
    MatrixX3i G(F.rows() + 1, 3);
    G << F, Eigen::RowVector3i(0, 4, static_cast<int>(V.rows()));
    expect_refused(W, G, "edge (0, 4) has 3 faces");
  }
  {
    // Two triangles sharing only a vertex: a bow tie.
    MatrixX3d W(5, 3);
    W << 0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0;
    MatrixX3i G(2, 3);
    G << 0, 1, 2, 0, 3, 4;
    expect_refused(W, G, "vertex 0 is non-manifold");
  }
  {
    // Closed: a tetrahedron.
    MatrixX3d W(4, 3);
    W << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
    MatrixX3i G(4, 3);
    G << 0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2;
    expect_refused(W, G, "closed");
  }
  {
    MatrixX3d W(6, 3);
    W << 0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 0, 0, 6, 0, 0, 5, 1, 0;
    MatrixX3i G(2, 3);
    G << 0, 1, 2, 3, 4, 5;
    expect_refused(W, G, "2 connected components");
  }
}

TEST(Topology, MoebiusStripIsNotOrientable) {
  const int n = 12;
  MatrixX3d V(2 * n, 3);
  for (int k = 0; k < n; ++k) {
    const double t = 2 * M_PI * k / n, w = 0.3 * std::cos(t / 2), h = 0.3 * std::sin(t / 2);
    const Eigen::Vector3d c(std::cos(t), std::sin(t), 0), r(std::cos(t) * w, std::sin(t) * w, h);
    V.row(2 * k) = (c + r).transpose();
    V.row(2 * k + 1) = (c - r).transpose();
  }
  MatrixX3i F(2 * n, 3);
  for (int k = 0; k < n; ++k) {
    int a = 2 * k, b = 2 * k + 1, c = 2 * ((k + 1) % n), d = c + 1;
    if (k == n - 1) std::swap(c, d);  // the half twist
    F.row(2 * k) << a, b, d;
    F.row(2 * k + 1) << a, d, c;
  }
  expect_refused(V, F, "not orientable");
}

TEST(Topology, AnnulusHasOuterLoopFirst) {
  // Two rings of 8 vertices, radii 1 and 2.
  const int n = 8;
  MatrixX3d V(2 * n, 3);
  for (int k = 0; k < n; ++k) {
    const double t = 2 * M_PI * k / n;
    V.row(k) << std::cos(t), std::sin(t), 0;
    V.row(n + k) << 2 * std::cos(t), 2 * std::sin(t), 0;
  }
  MatrixX3i F(2 * n, 3);
  for (int k = 0; k < n; ++k) {
    const int a = k, b = (k + 1) % n, c = n + k, d = n + (k + 1) % n;
    F.row(2 * k) << a, c, d;
    F.row(2 * k + 1) << a, d, b;
  }
  const Mesh m = make_mesh(V, F);
  ASSERT_EQ(m.topology.boundary_loops.size(), 2u);
  EXPECT_GT(m.topology.loop_length[0], m.topology.loop_length[1]);
  EXPECT_GE(m.topology.boundary_loops[0][0], n);  // outer ring vertices
}

}  // namespace
}  // namespace intrinsic
