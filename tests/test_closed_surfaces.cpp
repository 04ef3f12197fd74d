// The generated closed surfaces: Euler characteristic, closed,
// manifold, one consistently oriented component, outward normals.
#include <gtest/gtest.h>

#include "intrinsic/generate.h"
#include "intrinsic/mesh.h"
#include "intrinsic/metrics.h"

namespace intrinsic {
namespace {

void expect_closed(const MeshData& m, int euler) {
  ValidateOptions vo;
  vo.allow_closed = true;
  const Mesh mesh = make_mesh(m, vo);  // throws on non-manifold or non-orientable input
  const Topology& t = mesh.topology;
  EXPECT_EQ(t.num_components, 1);
  EXPECT_TRUE(t.boundary_loops.empty());
  EXPECT_EQ(mesh.validation.reoriented_faces, 0);
  EXPECT_EQ(mesh.validation.unreferenced_vertices, 0);
  const long edges = unique_edges(m.F).rows();
  EXPECT_EQ(m.V.rows() - edges + m.F.rows(), euler);
  EXPECT_EQ(2 * edges, 3 * m.F.rows());  // every edge has exactly two faces
  // Outward: the signed volume is positive.
  double volume = 0;
  for (int f = 0; f < m.F.rows(); ++f)
    volume += Eigen::Vector3d(m.V.row(m.F(f, 0))).dot(Eigen::Vector3d(m.V.row(m.F(f, 1))).cross(m.V.row(m.F(f, 2))));
  EXPECT_GT(volume, 0);
}

TEST(ClosedSurfaces, EulerCharacteristicClosedManifold) {
  for (int rings : {1, 3, 8, 25}) {
    SCOPED_TRACE(rings);
    GenerateOptions o;
    o.rings = rings;
    expect_closed(generate_surface("sphere", o), 2);
    expect_closed(generate_surface("torus", o), 0);
    expect_closed(generate_surface("genus2", o), -2);
  }
}

TEST(ClosedSurfaces, SizeFollowsRings) {
  GenerateOptions o;
  o.rings = 40;
  EXPECT_GT(generate_bumpy_sphere(o).V.rows(), 2 * 39 * 80 / 2);
  EXPECT_EQ(generate_torus(o).V.rows(), 120 * 40);
  EXPECT_GT(generate_genus2(o).V.rows(), 2 * 120 * 40 * 0.8);
  o.jitter = 0;
  const MeshData a = generate_genus2(o), b = generate_genus2(o);
  EXPECT_EQ(a.V, b.V);
  EXPECT_EQ(a.F, b.F);
}

}  // namespace
}  // namespace intrinsic
