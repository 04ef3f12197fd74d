// The local/global isometric refinement of a chart's map
// (src/optimize/isometric_refinement.h; docs/maths.md §9.9), checked
// against the energy and stretch written here with Eigen's SVD: the energy
// min_R |J - R|^2 of a face is (s1 - 1)^2 + (s2 - 1)^2.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cmath>

#include "intrinsic/generate.h"
#include "intrinsic/parameterize.h"
#include "optimize/isometric_refinement.h"
#include "test_support.h"

namespace intrinsic {
namespace {

// Per face: 3D area and the singular values of the map from the face to UV,
// the face's frame built from its unit normal (not the library's frame).
struct FaceSv {
  double area, s1, s2, det;
};
std::vector<FaceSv> singular_values(const Mesh& m, const MatrixX2d& UV) {
  std::vector<FaceSv> out;
  for (int f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    const Eigen::Vector3d t = (c - a).normalized(), s = n.cross(t);  // a frame from another edge
    Eigen::Matrix2d X, U;
    X << (b - a).dot(t), (c - a).dot(t), (b - a).dot(s), (c - a).dot(s);
    U.col(0) = (UV.row(m.F(f, 1)) - UV.row(m.F(f, 0))).transpose();
    U.col(1) = (UV.row(m.F(f, 2)) - UV.row(m.F(f, 0))).transpose();
    const Eigen::Matrix2d J = U * X.inverse();
    Eigen::JacobiSVD<Eigen::Matrix2d> svd(J);
    out.push_back({0.5 * (b - a).cross(c - a).norm(), svd.singularValues()(0), svd.singularValues()(1), J.determinant()});
  }
  return out;
}

double arap_energy(const std::vector<FaceSv>& sv) {
  double e = 0;
  for (const FaceSv& f : sv) e += f.area * ((f.s1 - 1) * (f.s1 - 1) + (f.s2 - 1) * (f.s2 - 1));
  return e;
}

double worst_stretch(const std::vector<FaceSv>& sv) {
  double w = 1;
  for (const FaceSv& f : sv) w = std::max({w, f.s1, 1 / f.s2});
  return w;
}

MatrixX2d natural_map(const Mesh& m) {
  ParamOptions o;
  o.boundary = BoundaryShape::Natural;
  o.scale = ScaleMode::Surface;
  return parameterize(m, o).UV;
}

TEST(IsometricRefinement, LowersTheEnergyItReportsOnACapWithoutFolds) {
  GenerateOptions g;
  g.rings = 12;
  g.cap_angle = 1.3;
  const Mesh m = make_mesh(generate_sphere_cap(g));
  MatrixX2d UV = natural_map(m);
  const std::vector<FaceSv> before = singular_values(m, UV);
  const detail::IsometricRefinementResult r = detail::refine_isometric(m, UV);
  const std::vector<FaceSv> after = singular_values(m, UV);
  EXPECT_GT(r.iterations, 0);
  EXPECT_NEAR(r.energy_before, arap_energy(before), 1e-9 * arap_energy(before));
  EXPECT_NEAR(r.energy_after, arap_energy(after), 1e-9 * arap_energy(before));
  EXPECT_LT(arap_energy(after), 0.5 * arap_energy(before));
  for (const FaceSv& f : after) EXPECT_GT(f.det, 0);
  // A cap cannot be flattened isometrically; the conformal map's area drift
  // (a texel's worst stretch) is what the refinement takes down.
  EXPECT_LT(worst_stretch(after), worst_stretch(before) - 0.05);
}

TEST(IsometricRefinement, FlatPatchStaysAnIsometryAndMotionsChangeNothing) {
  GenerateOptions g;
  g.rings = 8;
  const MeshData flat = generate_flat_disk(g);
  const Mesh m = make_mesh(flat);
  MatrixX2d UV = natural_map(m);
  detail::refine_isometric(m, UV);
  for (const FaceSv& f : singular_values(m, UV)) {
    EXPECT_NEAR(f.s1, 1, 1e-8);
    EXPECT_NEAR(f.s2, 1, 1e-8);
  }
  // A rigid motion of the cap gives the same singular values face by face.
  g.rings = 8;
  const MeshData cap = generate_sphere_cap(g);
  MeshData moved = cap;
  moved.V = test::rigid_motion(cap.V);
  const Mesh a = make_mesh(cap), b = make_mesh(moved);
  MatrixX2d ua = natural_map(a), ub = natural_map(b);
  detail::refine_isometric(a, ua);
  detail::refine_isometric(b, ub);
  const std::vector<FaceSv> sa = singular_values(a, ua), sb = singular_values(b, ub);
  for (size_t f = 0; f < sa.size(); ++f) {
    EXPECT_NEAR(sa[f].s1, sb[f].s1, 1e-6);
    EXPECT_NEAR(sa[f].s2, sb[f].s2, 1e-6);
  }
}

}  // namespace
}  // namespace intrinsic
