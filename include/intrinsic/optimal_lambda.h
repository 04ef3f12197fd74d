// Near-optimal maps (paper section 5.1; docs/maths.md §7): within the line of
// maps U(lambda) = lambda U_A + (1 - lambda) U_chi sharing one fixed boundary,
// the lambda that minimises the edge-length or the area distortion, found
// exactly: both energies are quartic polynomials in lambda, so the minimum is
// at a real root of the cubic derivative or at an end of the interval.
#pragma once

#include <array>
#include <string>

#include "intrinsic/choice.h"
#include "intrinsic/parameterize.h"

namespace intrinsic {

enum class LambdaEnergy { EdgeLength, Area };
template <>
ChoiceTable<LambdaEnergy> choice_table<LambdaEnergy>();

// E(lambda) = sum_k c[k] lambda^k.
using Quartic = std::array<double, 5>;
double evaluate(const Quartic& c, double lambda);

// Coefficients of the energy of U(lambda) = U_chi + lambda (U_A - U_chi).
Quartic lambda_energy_polynomial(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& U_conformal,
                                 const MatrixX2d& U_authalic, LambdaEnergy energy);

// The minimiser of the quartic on [lo, hi] (exact up to root polishing).
double minimize_quartic(const Quartic& c, double lo, double hi);

struct OptimalLambdaOptions {
  ParamOptions base;  // boundary, spacing, holes, solver, scale; weights are ignored
  LambdaEnergy energy = LambdaEnergy::EdgeLength;
  double lo = 0, hi = 1;
};

struct OptimalLambdaResult {
  double lambda = 0;                 // lambda*
  double energy = 0;                 // E(lambda*)
  double energy_at_0 = 0, energy_at_1 = 0;  // pure authalic, pure conformal
  Quartic coefficients{};
  double boundary_scale = 1;         // factor applied so parameter area = 3D area
  ParamResult map;                   // U(lambda*), scaled as base.scale says
  double conformal_ms = 0, authalic_ms = 0, polynomial_ms = 0;
};

// Two solves (conformal and authalic with the same boundary), then O(edges)
// work. The energies are evaluated with the boundary scaled so that the
// parameter area equals the 3D area (docs/maths.md §7); the returned map is
// then scaled as base.scale says (or kept as given for a boundary file).
OptimalLambdaResult optimal_lambda(const Mesh& mesh, const OptimalLambdaOptions& options);

LambdaEnergy parse_lambda_energy(const std::string& name);  // "edge" | "area"
std::string lambda_energy_name(LambdaEnergy e);             // "edge" | "area"

}  // namespace intrinsic
