// Exact minimisation of the quartic edge-length and area energies along
// U(lambda) = lambda U_A + (1 - lambda) U_chi (paper section 5.1;
// docs/maths.md §7). Both maps come from the one Parameterizer
// (parameterize with the common boundary given).
#include "intrinsic/optimal_lambda.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "core/placement.h"
#include "intrinsic/error.h"
#include "intrinsic/choice.h"
#include "intrinsic/metrics.h"
#include "util/stopwatch.h"

namespace intrinsic {
using detail::ms_since;
namespace {

// Adds (p0 + p1 x + p2 x^2)^2 to c.
void add_square(Quartic& c, double p0, double p1, double p2) {
  c[0] += p0 * p0;
  c[1] += 2 * p0 * p1;
  c[2] += p1 * p1 + 2 * p0 * p2;
  c[3] += 2 * p1 * p2;
  c[4] += p2 * p2;
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Real roots of a x^3 + b x^2 + c x + d (any degree down to constant),
// polished by Newton steps.
std::vector<double> real_roots_cubic(double a, double b, double c, double d) {
  std::vector<double> roots;
  const double scale = std::max({std::abs(a), std::abs(b), std::abs(c), std::abs(d)});
  if (scale == 0) return roots;
  a /= scale; b /= scale; c /= scale; d /= scale;
  if (std::abs(a) < 1e-14) {
    if (std::abs(b) < 1e-14) {
      if (std::abs(c) > 0) roots.push_back(-d / c);
      return roots;
    }
    const double disc = c * c - 4 * b * d;
    if (disc >= 0) {
      const double q = -0.5 * (c + std::copysign(std::sqrt(disc), c));
      roots.push_back(q / b);
      if (q != 0) roots.push_back(d / q);
    }
    return roots;
  }
  // Depressed cubic t^3 + p t + q with x = t - b/(3a).
  const double B = b / a, C = c / a, D = d / a;
  const double p = C - B * B / 3, q = 2 * B * B * B / 27 - B * C / 3 + D;
  const double disc = q * q / 4 + p * p * p / 27;
  if (disc > 0) {
    const double s = std::sqrt(disc);
    roots.push_back(std::cbrt(-q / 2 + s) + std::cbrt(-q / 2 - s) - B / 3);
  } else {
    const double r = std::sqrt(-p / 3);
    const double phi = std::acos(std::clamp(-q / (2 * r * r * r), -1.0, 1.0));
    for (int k = 0; k < 3; ++k) roots.push_back(2 * r * std::cos((phi - 2 * M_PI * k) / 3) - B / 3);
  }
  for (double& x : roots)
    for (int it = 0; it < 4; ++it) {
      const double f = ((a * x + b) * x + c) * x + d, df = (3 * a * x + 2 * b) * x + c;
      if (df == 0) break;
      x -= f / df;
    }
  return roots;
}

// U(lambda*) with the diagnostics of both solves, placed as base.scale says
// (docs/maths.md §2.4): the circle and square live in [-1, 1]^2 as in
// parameterize(); a boundary file is kept as given.
ParamResult blended_map(const Mesh& mesh, const OptimalLambdaOptions& o, const ParamResult& conformal,
                        const ParamResult& authalic, const OptimalLambdaResult& best) {
  ParamResult map = conformal;
  map.UV = best.lambda * conformal.UV + (1 - best.lambda) * authalic.UV;
  map.weights = {Method::Mixed, best.lambda, 1 - best.lambda};
  map.boundary = o.base.boundary;
  map.residual = std::max(conformal.residual, authalic.residual);
  for (SolverKind k : authalic.solvers)
    if (std::find(map.solvers.begin(), map.solvers.end(), k) == map.solvers.end()) map.solvers.push_back(k);
  map.factorizations += authalic.factorizations;
  map.timings.assemble_ms += authalic.timings.assemble_ms;
  map.timings.factor_ms += authalic.timings.factor_ms;
  map.timings.solve_ms += authalic.timings.solve_ms + best.polynomial_ms;
  const std::vector<char> used(mesh.topology.is_used.begin(), mesh.topology.is_used.end());
  detail::PlacementRule rule = detail::PlacementRule::AsSolved;
  map.placement = Placement::Given;
  if (o.base.boundary != BoundaryShape::Given) {
    map.placement = o.base.scale == ScaleMode::Unit ? Placement::Unit : Placement::Surface;
    rule = o.base.scale == ScaleMode::Unit ? detail::PlacementRule::UnitBox : detail::PlacementRule::AsSolved;
  }
  detail::Similarity s = detail::placement(rule, mesh.V, mesh.F, map.UV, used);
  if (map.placement == Placement::Surface) s.scale = best.boundary_scale;  // the boundary the energies used
  detail::apply(s, map.UV, used);
  return map;
}

}  // namespace

double evaluate(const Quartic& c, double x) { return (((c[4] * x + c[3]) * x + c[2]) * x + c[1]) * x + c[0]; }

LambdaEnergy parse_lambda_energy(const std::string& name) {
  return parse_choice<LambdaEnergy>(name, "optimize-lambda");
}

std::string lambda_energy_name(LambdaEnergy e) { return choice_name(e); }

Quartic lambda_energy_polynomial(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UA, const MatrixX2d& UX,
                                 LambdaEnergy energy) {
  Quartic c{0, 0, 0, 0, 0};
  const MatrixX2d D = UA - UX;  // U(lambda) = UX + lambda D
  if (energy == LambdaEnergy::EdgeLength) {
    const Eigen::MatrixX2i E = unique_edges(F);
    for (int k = 0; k < E.rows(); ++k) {
      const int i = E(k, 0), j = E(k, 1);
      const double L2 = (V.row(i) - V.row(j)).squaredNorm();
      const Eigen::Vector2d a = (UX.row(i) - UX.row(j)).transpose(), b = (D.row(i) - D.row(j)).transpose();
      add_square(c, a.squaredNorm() / L2 - 1, 2 * a.dot(b) / L2, b.squaredNorm() / L2);
    }
  } else {
    for (int f = 0; f < F.rows(); ++f) {
      const Eigen::Vector3d x0 = V.row(F(f, 0)), x1 = V.row(F(f, 1)), x2 = V.row(F(f, 2));
      const double A3 = 0.5 * (x1 - x0).cross(x2 - x0).norm();
      const Eigen::Vector2d p = (UX.row(F(f, 1)) - UX.row(F(f, 0))).transpose();
      const Eigen::Vector2d r = (UX.row(F(f, 2)) - UX.row(F(f, 0))).transpose();
      const Eigen::Vector2d q = (D.row(F(f, 1)) - D.row(F(f, 0))).transpose();
      const Eigen::Vector2d s = (D.row(F(f, 2)) - D.row(F(f, 0))).transpose();
      // Signed area (1/2) cross(p + l q, r + l s), divided by the 3D area.
      add_square(c, 0.5 * cross2(p, r) / A3 - 1, 0.5 * (cross2(p, s) + cross2(q, r)) / A3, 0.5 * cross2(q, s) / A3);
    }
  }
  return c;
}

double minimize_quartic(const Quartic& c, double lo, double hi) {
  double best = lo, best_e = evaluate(c, lo);
  auto consider = [&](double x) {
    if (!(x >= lo && x <= hi)) return;
    const double e = evaluate(c, x);
    if (e < best_e) { best_e = e; best = x; }
  };
  consider(hi);
  for (double x : real_roots_cubic(4 * c[4], 3 * c[3], 2 * c[2], c[1])) consider(x);
  return best;
}

OptimalLambdaResult optimal_lambda(const Mesh& mesh, const OptimalLambdaOptions& o) {
  if (!(o.lo <= o.hi) || !std::isfinite(o.lo) || !std::isfinite(o.hi))
    throw_usage("the lambda range must be finite with lo <= hi");
  if (o.base.boundary == BoundaryShape::Natural)
    throw_usage("--optimize-lambda blends two maps with a common fixed boundary (circle, square or a file), not natural");
  OptimalLambdaResult result;
  // Both maps share one fixed boundary: the positions are computed once and
  // passed as given, so neither solve rescales its result.
  ParamOptions p = o.base;
  p.given = boundary_positions(mesh, p);
  p.boundary = BoundaryShape::Given;
  auto t0 = std::chrono::steady_clock::now();
  p.weights = {Method::Conformal, 1, 0};
  ParamResult conformal = parameterize(mesh, p);
  result.conformal_ms = ms_since(t0);
  t0 = std::chrono::steady_clock::now();
  p.weights = {Method::Authalic, 0, 1};
  ParamResult authalic = parameterize(mesh, p);
  result.authalic_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  // The solution is linear in the boundary: scaling the boundary by s scales
  // both maps by s, so the area normalisation is applied to the results.
  const double a_param = std::abs(parameter_area(mesh.F, conformal.UV));
  if (!(a_param > 0)) throw_numerical("the conformal map has zero parameter area; cannot normalise the boundary");
  result.boundary_scale = std::sqrt(surface_area(mesh.V, mesh.F) / a_param);
  const MatrixX2d UA = result.boundary_scale * conformal.UV, UX = result.boundary_scale * authalic.UV;
  result.coefficients = lambda_energy_polynomial(mesh.V, mesh.F, UA, UX, o.energy);
  result.lambda = minimize_quartic(result.coefficients, o.lo, o.hi);
  result.energy = evaluate(result.coefficients, result.lambda);
  result.energy_at_0 = evaluate(result.coefficients, 0);
  result.energy_at_1 = evaluate(result.coefficients, 1);
  result.polynomial_ms = ms_since(t0);

  result.map = blended_map(mesh, o, conformal, authalic, result);
  return result;
}

// How the command line, Python and the reports spell these (intrinsic/choice.h).
template <>
ChoiceTable<LambdaEnergy> choice_table<LambdaEnergy>() {
  static const Choice<LambdaEnergy> rows[] = {{LambdaEnergy::EdgeLength, "edge"}, {LambdaEnergy::Area, "area"}};
  return make_choice_table(rows);
}

}  // namespace intrinsic
