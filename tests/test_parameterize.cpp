// The fixed-boundary family against analytic answers: flat meshes reproduce
// themselves (docs/maths.md §1.7), rigid motions change nothing, the spherical
// cap tends to the stereographic projection, backends agree.
#include <gtest/gtest.h>

#include "intrinsic/error.h"
#include "intrinsic/metrics.h"
#include "intrinsic/parameterize.h"
#include "test_support.h"

namespace intrinsic {
namespace {

using test::diameter;

std::vector<FixedVertex> own_positions(const Mesh& mesh, const std::vector<int>& loop) {
  std::vector<FixedVertex> out;
  for (int v : loop) out.push_back({v, mesh.V.row(v).head<2>().transpose()});
  return out;
}

ParamOptions with_method(Method m, double lambda = 1, double mu = 0) {
  ParamOptions o;
  o.weights.method = m;
  o.weights.lambda = lambda;
  o.weights.mu = mu;
  return o;
}

TEST(Parameterize, FlatMeshReproducesItself) {
  GenerateOptions g;
  g.rings = 12;
  g.jitter = 0.6;
  const Mesh mesh = make_mesh(generate_flat_disk(g));
  const std::vector<int>& outer = mesh.topology.boundary_loops[0];
  MatrixX2d XY = mesh.V.leftCols(2);
  const double d = diameter(XY);
  struct Case { Method m; double lambda, mu; bool reproduces; };
  for (const Case& c : {Case{Method::Conformal, 1, 0, true}, Case{Method::Authalic, 0, 1, true},
                        Case{Method::Mixed, 0.3, 0.7, true}, Case{Method::Mixed, 2.0, -0.5, true},
                        Case{Method::Floater, 0, 0, true}, Case{Method::Tutte, 0, 0, false}}) {
    ParamOptions o = with_method(c.m, c.lambda, c.mu);
    o.boundary = BoundaryShape::Given;
    o.given = own_positions(mesh, outer);
    const ParamResult r = parameterize(mesh, o);
    const double err = (r.UV - XY).cwiseAbs().maxCoeff();
    if (c.reproduces) EXPECT_LT(err, 1e-10 * d) << method_name(c.m) << " lambda " << c.lambda;
    else EXPECT_GT(err, 1e-4 * d) << "uniform weights must not reproduce an irregular mesh";
    EXPECT_EQ(r.placement, Placement::Given);
  }
}

TEST(Parameterize, RigidMotionLeavesUVsUnchanged) {
  GenerateOptions g;
  g.rings = 14;
  const MeshData data = generate_wavy_patch(g);
  MeshData moved = data;
  moved.V = test::rigid_motion(data.V);
  const Mesh a = make_mesh(data), b = make_mesh(moved);
  for (Method m : {Method::Conformal, Method::Authalic, Method::Mixed, Method::Floater}) {
    for (BoundaryShape s : {BoundaryShape::Circle, BoundaryShape::Square}) {
      ParamOptions o = with_method(m, 0.5, 0.5);
      o.boundary = s;
      const ParamResult ra = parameterize(a, o), rb = parameterize(b, o);
      EXPECT_LT((ra.UV - rb.UV).cwiseAbs().maxCoeff(), 1e-11) << method_name(m);
    }
  }
}

// Stereographic projection of the unit sphere from the south pole, scaled so
// the cap's boundary (polar angle t0) lands on the unit circle: the exact
// conformal map of the cap onto the disk.
Eigen::Vector2d stereographic(const Eigen::Vector3d& x, double t0) {
  const Eigen::Vector2d p = x.head<2>() / (1 + x.z());
  return p / std::tan(t0 / 2);
}

// The largest distance from the exact conformal map of a spherical cap
// for the weights in `o`.
double cap_error(int rings, ParamOptions o = ParamOptions()) {
  GenerateOptions g;
  g.rings = rings;
  g.jitter = 0.4;
  g.cap_angle = 1.2;
  const Mesh mesh = make_mesh(generate_sphere_cap(g));
  o.boundary = BoundaryShape::Given;
  for (int v : mesh.topology.boundary_loops[0])
    o.given.push_back({v, stereographic(mesh.V.row(v).transpose(), g.cap_angle)});
  const ParamResult r = parameterize(mesh, o);
  double err = 0;
  for (int v = 0; v < mesh.V.rows(); ++v)
    err = std::max(err, (r.UV.row(v).transpose() - stereographic(mesh.V.row(v).transpose(), g.cap_angle)).norm());
  return err;
}

TEST(Parameterize, SphericalCapTendsToStereographicProjection) {
  const double e1 = cap_error(6), e2 = cap_error(12), e3 = cap_error(24);
  EXPECT_LT(e2, 0.6 * e1);
  EXPECT_LT(e3, 0.6 * e2);
  EXPECT_LT(e3, 2e-3);
  // Authalic weights are not conformal: the same test must not converge to 0.
  const double err = cap_error(24, with_method(Method::Authalic, 0, 1));
  EXPECT_GT(err, 10 * e3);
}

TEST(Parameterize, MixedFamilyEndpointsAndScaleOfCoefficients) {
  const Mesh mesh = test::wavy(10);
  const MatrixX2d conformal = parameterize(mesh, with_method(Method::Conformal)).UV;
  const MatrixX2d authalic = parameterize(mesh, with_method(Method::Authalic)).UV;
  EXPECT_LT((parameterize(mesh, with_method(Method::Mixed, 3, 0)).UV - conformal).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((parameterize(mesh, with_method(Method::Mixed, 0, 2)).UV - authalic).cwiseAbs().maxCoeff(), 1e-12);
  const MatrixX2d mix = parameterize(mesh, with_method(Method::Mixed, 0.3, 0.7)).UV;
  EXPECT_LT((parameterize(mesh, with_method(Method::Mixed, 3, 7)).UV - mix).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT((mix - conformal).cwiseAbs().maxCoeff(), 1e-4);
  EXPECT_GT((mix - authalic).cwiseAbs().maxCoeff(), 1e-5);
}

TEST(Parameterize, SolversAgree) {
  const Mesh mesh = test::wavy(12);
  for (Method m : {Method::Conformal, Method::Authalic}) {
    ParamOptions o = with_method(m, 0, 1);
    const MatrixX2d ref = parameterize(mesh, o).UV;
    std::vector<SolverKind> kinds = {SolverKind::EigenLU, SolverKind::BiCGSTAB};
    if (m == Method::Conformal) kinds.insert(kinds.end(), {SolverKind::EigenLLT, SolverKind::CG});
    if (solver_available(SolverKind::Umfpack)) kinds.push_back(SolverKind::Umfpack);
    if (solver_available(SolverKind::Cholmod) && m == Method::Conformal) kinds.push_back(SolverKind::Cholmod);
    if (solver_available(SolverKind::SupernodalLU)) kinds.push_back(SolverKind::SupernodalLU);
    for (SolverKind k : kinds) {
      o.solver = k;
      const ParamResult r = parameterize(mesh, o);
      EXPECT_LT((r.UV - ref).cwiseAbs().maxCoeff(), 1e-8) << solver_name(k) << " " << method_name(m);
      EXPECT_LT(r.residual, 1e-9) << solver_name(k);
    }
    if (m == Method::Authalic) {
      o.solver = SolverKind::CG;
      test::expect_error([&] { parameterize(mesh, o); }, ErrorKind::Usage,
                         "conjugate gradient needs a symmetric system");
    }
  }
}

TEST(Parameterize, BoundaryShapesAndScale) {
  const Mesh mesh = test::wavy(10);
  ParamOptions o;
  o.boundary = BoundaryShape::Square;
  const ParamResult sq = parameterize(mesh, o);
  int corners = 0;
  for (int v : mesh.topology.boundary_loops[0]) {
    const Eigen::Vector2d p = sq.UV.row(v);
    const double to_side = std::min({p.x(), 1 - p.x(), p.y(), 1 - p.y()});
    EXPECT_NEAR(to_side, 0.0, 1e-12);
    if (std::min(p.x(), 1 - p.x()) < 1e-12 && std::min(p.y(), 1 - p.y()) < 1e-12) ++corners;
  }
  EXPECT_EQ(corners, 4);
  EXPECT_EQ(summarize_distortion(mesh.V, mesh.F, sq.UV).flipped_triangles, 0);

  o.boundary = BoundaryShape::Circle;
  const ParamResult unit = parameterize(mesh, o);
  EXPECT_GE(unit.UV.minCoeff(), 0.0);
  EXPECT_LE(unit.UV.maxCoeff(), 1.0);
  for (int v : mesh.topology.boundary_loops[0])
    EXPECT_NEAR((unit.UV.row(v) - Eigen::RowVector2d(0.5, 0.5)).norm(), 0.5, 1e-12);
  o.scale = ScaleMode::Surface;
  const ParamResult surf = parameterize(mesh, o);
  EXPECT_NEAR(parameter_area(mesh.F, surf.UV), surface_area(mesh.V, mesh.F), 1e-9 * surface_area(mesh.V, mesh.F));
  EXPECT_EQ(surf.placement, Placement::Surface);
}

TEST(Parameterize, UniformAndArcLengthSpacing) {
  const Mesh mesh = test::wavy(8);
  const std::vector<int>& loop = mesh.topology.boundary_loops[0];
  const auto uniform = loop_parameters(mesh.V, loop, Spacing::Uniform);
  const auto arc = loop_parameters(mesh.V, loop, Spacing::ArcLength);
  for (size_t k = 1; k < loop.size(); ++k) {
    EXPECT_NEAR(uniform[k] - uniform[k - 1], 1.0 / loop.size(), 1e-15);
    const double len = (mesh.V.row(loop[k]) - mesh.V.row(loop[k - 1])).norm();
    EXPECT_NEAR((arc[k] - arc[k - 1]) / len, arc[1] / (mesh.V.row(loop[1]) - mesh.V.row(loop[0])).norm(), 1e-12);
  }
}

TEST(Parameterize, GivenBoundaryMustCoverOuterLoop) {
  GenerateOptions g;
  g.rings = 6;
  const Mesh mesh = make_mesh(generate_flat_disk(g));
  ParamOptions o;
  o.boundary = BoundaryShape::Given;
  o.given = own_positions(mesh, mesh.topology.boundary_loops[0]);
  const int dropped = o.given.back().vertex;
  o.given.pop_back();
  test::expect_error([&] { parameterize(mesh, o); }, ErrorKind::Input, "vertex " + std::to_string(dropped));
}

// A disk with holes: faces around a few interior vertices removed.
Mesh holed_disk(int holes) { return make_mesh(test::holed_wavy(holes)); }

TEST(Parameterize, HolesFilledOrFreeGiveValidMaps) {
  const Mesh mesh = holed_disk(3);
  ASSERT_EQ(mesh.topology.boundary_loops.size(), 4u);
  for (HoleRule rule : {HoleRule::Fill, HoleRule::Free})
    for (Method m : {Method::Conformal, Method::Authalic}) {
      ParamOptions o = with_method(m, 0, 1);
      o.holes = rule;
      const ParamResult r = parameterize(mesh, o);
      EXPECT_EQ(r.filled_holes, rule == HoleRule::Fill ? 3 : 0);
      EXPECT_EQ(summarize_distortion(mesh.V, mesh.F, r.UV).flipped_triangles, 0) << method_name(m);
      EXPECT_TRUE(r.UV.allFinite());
    }
}

TEST(Parameterize, NoFlipsOnSmoothIrregularSurfaces) {
  GenerateOptions g;
  g.rings = 20;
  g.jitter = 0.5;
  for (const MeshData& d : {generate_sphere_cap(g), generate_wavy_patch(g), generate_sphere_strip(g)}) {
    const Mesh mesh = make_mesh(d);
    for (Method m : {Method::Conformal, Method::Authalic, Method::Floater, Method::Tutte}) {
      const ParamResult r = parameterize(mesh, with_method(m, 0, 1));
      EXPECT_EQ(summarize_distortion(mesh.V, mesh.F, r.UV).flipped_triangles, 0) << method_name(m);
    }
  }
}

}  // namespace
}  // namespace intrinsic
