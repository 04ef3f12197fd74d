// One call for the common case: a member of the intrinsic family
// lambda*DCP + mu*DAP (or Tutte/Floater for comparison) with a fixed outer
// boundary (paper sections 3 and 4.1), or the natural conformal map with two
// pinned vertices (section 4.2, eq. 7). Fixed vertices are eliminated, the
// remaining system is factored once and solved for u and v together.
#pragma once

#include <string>
#include <vector>

#include "intrinsic/boundary.h"
#include "intrinsic/linear_solver.h"
#include "intrinsic/metrics.h"
#include "intrinsic/topology.h"
#include "intrinsic/weights.h"

namespace intrinsic {

enum class ScaleMode { Unit, Surface };

// What happens to boundary loops other than the outer one (holes) when their
// positions are not given.
enum class HoleRule {
  Fill,  // each hole is closed by a fan around its centroid for the solve, then removed
  Free,  // hole vertices are free and obey the same equations with the faces they have
  // Hole loops get the natural conformal condition (eq. 7): the system is the
  // Hessian of lambda*(E_D - A) + mu*E_chi, i.e. the area term's rows, scaled
  // by lambda, are added at hole vertices (coupling u and v). Methods without
  // a conformal part (authalic, tutte, floater) have no such term: Free.
  Natural,
};

std::string hole_rule_name(HoleRule r);

struct ParamOptions {
  WeightOptions weights;
  BoundaryShape boundary = BoundaryShape::Circle;
  Spacing spacing = Spacing::ArcLength;
  std::vector<FixedVertex> given;  // BoundaryShape::Given: must include the whole outer loop
  ScaleMode scale = ScaleMode::Unit;  // ignored for Given positions (used exactly)
  HoleRule holes = HoleRule::Fill;
  // BoundaryShape::Natural only: vertices kept exactly at the given positions
  // (at least two, any used vertices). Empty: the two vertices of the outer
  // loop farthest apart in 3D (on a disk: of the boundary) at (0, 0) and
  // (d, 0), d their 3D distance, then
  // `scale` applies (Unit: fit to [0,1]^2 by a similarity; Surface: as is).
  std::vector<FixedVertex> pins;
  SolverKind solver = SolverKind::Auto;
  double max_residual = 1e-8;  // relative; larger fails with Error(Numerical)
};

struct StageTimings {
  double assemble_ms = 0, factor_ms = 0, solve_ms = 0;
};

struct ParamResult {
  MatrixX2d UV;  // #V x 2, unused vertices at (0, 0)
  std::string solver;       // backend used
  double residual = 0;      // max over u, v of |A x - b| / |b|
  int free_vertices = 0;    // unknowns per coordinate
  int fixed_vertices = 0;
  int filled_holes = 0;
  int factorizations = 0;
  int iterations = 0;       // iterative solvers only
  std::string scale;        // "unit", "surface" or "given"
  std::string holes;        // the hole rule applied: "fill", "free", "natural", "none" (no holes)
  std::vector<FixedVertex> pins;  // natural map: the pins used, at their solved positions before scaling
  StageTimings timings;
};

// Throws Error(Usage) for inconsistent options (natural boundary with a
// non-conformal method, fewer than two pins, pins without natural boundary),
// Error(Input) when the mesh cannot take them (missing outer-loop vertex in
// `given`, pin on a vertex that does not exist), Error(Numerical) when the
// solve fails or the residual is too large.
ParamResult parameterize(const Mesh& mesh, const ParamOptions& options);

// Positions of the fixed vertices before any scaling: the outer loop on the
// circle or square of [-1, 1]^2, or the given positions (checked to cover the
// outer loop; Error(Input) names a missing vertex).
std::vector<FixedVertex> boundary_positions(const Mesh& mesh, const ParamOptions& options);

// Similarity that moves UV into [0,1]^2 (centred, aspect kept), or scaling
// about the origin so the parameter area equals the 3D area.
void fit_unit_square(MatrixX2d& UV, const std::vector<char>& used);
void scale_to_surface_area(MatrixX2d& UV, const Mesh& mesh);

// Sum of signed parameter areas of the faces.
double parameter_area(const MatrixX3i& F, const MatrixX2d& UV);
double surface_area(const MatrixX3d& V, const MatrixX3i& F);

}  // namespace intrinsic
