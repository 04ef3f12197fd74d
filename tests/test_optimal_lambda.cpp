// The exact lambda* (paper section 5.1) against a dense scan of the energy
// computed directly from the two maps.
#include <gtest/gtest.h>

#include <random>

#include "intrinsic/metrics.h"
#include "intrinsic/optimal_lambda.h"
#include "test_support.h"

namespace intrinsic {
namespace {

struct Maps {
  Mesh mesh;
  MatrixX2d UA, UX;  // at the area-normalised boundary scale
};

Maps maps_for(const MeshData& data) {
  Maps m{make_mesh(data), {}, {}};
  ParamOptions p;
  p.scale = ScaleMode::Surface;  // circle scaled so parameter area = 3D area
  p.weights.method = Method::Conformal;
  m.UA = parameterize(m.mesh, p).UV;
  p.weights.method = Method::Authalic;
  m.UX = parameterize(m.mesh, p).UV;
  return m;
}

double direct_energy(const Maps& m, LambdaEnergy e, double lambda) {
  const MatrixX2d U = lambda * m.UA + (1 - lambda) * m.UX;
  return e == LambdaEnergy::EdgeLength ? edge_length_energy(m.mesh.V, m.mesh.F, U)
                                       : area_energy(m.mesh.V, m.mesh.F, U);
}

TEST(OptimalLambda, PolynomialReproducesEnergy) {
  GenerateOptions g;
  g.rings = 12;
  const Maps m = maps_for(generate_wavy_patch(g));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> lam(-2, 3);
  for (LambdaEnergy e : {LambdaEnergy::EdgeLength, LambdaEnergy::Area}) {
    const Quartic c = lambda_energy_polynomial(m.mesh.V, m.mesh.F, m.UA, m.UX, e);
    for (int k = 0; k < 10; ++k) {
      const double x = lam(rng);
      const double direct = direct_energy(m, e, x);
      EXPECT_NEAR(evaluate(c, x), direct, 1e-10 * std::max(1.0, direct)) << x;
    }
  }
}

TEST(OptimalLambda, ExactMinimumBeatsDenseScan) {
  GenerateOptions g;
  g.rings = 14;
  for (const MeshData& d : {generate_wavy_patch(g), generate_sphere_cap(g)}) {
    const Maps m = maps_for(d);
    for (LambdaEnergy e : {LambdaEnergy::EdgeLength, LambdaEnergy::Area}) {
      for (auto [lo, hi] : {std::pair{0.0, 1.0}, std::pair{-1.0, 2.0}, std::pair{0.2, 0.3}}) {
        OptimalLambdaOptions o;
        o.energy = e;
        o.lo = lo;
        o.hi = hi;
        const OptimalLambdaResult r = optimal_lambda(m.mesh, o);
        EXPECT_GE(r.lambda, lo);
        EXPECT_LE(r.lambda, hi);
        const double at_star = direct_energy(m, e, r.lambda);
        EXPECT_NEAR(r.energy, at_star, 1e-10 * at_star);
        for (int k = 0; k <= 2000; ++k) {
          const double x = lo + (hi - lo) * k / 2000.0;
          ASSERT_LE(at_star, direct_energy(m, e, x) * (1 + 1e-12)) << "lambda " << x;
        }
        EXPECT_NEAR(r.energy_at_0, direct_energy(m, e, 0), 1e-9 * r.energy_at_0);
        EXPECT_NEAR(r.energy_at_1, direct_energy(m, e, 1), 1e-9 * r.energy_at_1);
      }
    }
  }
}

TEST(OptimalLambda, ReturnedMapIsTheBlend) {
  GenerateOptions g;
  g.rings = 10;
  const Maps m = maps_for(generate_wavy_patch(g));
  OptimalLambdaOptions o;
  o.base.scale = ScaleMode::Surface;
  const OptimalLambdaResult r = optimal_lambda(m.mesh, o);
  const MatrixX2d expected = r.lambda * m.UA + (1 - r.lambda) * m.UX;
  EXPECT_LT((r.map.UV - expected).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_EQ(r.map.placement, Placement::Surface);
  EXPECT_NEAR(parameter_area(m.mesh.F, r.map.UV), surface_area(m.mesh.V, m.mesh.F), 1e-9);
}

TEST(OptimalLambda, QuarticMinimizerOnKnownPolynomials) {
  // (x - 0.3)^2 (x + 2)^2 has minima at 0.3 and -2 (both zero).
  // Expand (x-0.3)^2 (x+2)^2 = (x^2 + 1.7x - 0.6)^2 = x^4 + 3.4x^3 + 1.69x^2 - 2.04x + 0.36.
  const Quartic q{0.36, -2.04, 1.69, 3.4, 1};
  EXPECT_NEAR(minimize_quartic(q, 0, 1), 0.3, 1e-12);
  EXPECT_NEAR(minimize_quartic(q, -3, -1), -2, 1e-12);
  EXPECT_NEAR(minimize_quartic(q, 0.5, 1), 0.5, 0);  // increasing there: left end
  const Quartic line{1, -1, 0, 0, 0};                 // 1 - x: right end
  EXPECT_EQ(minimize_quartic(line, 0, 4), 4);
}

}  // namespace
}  // namespace intrinsic
