// One call for the common case: a member of the intrinsic family
// lambda*DCP + mu*DAP (or Tutte/Floater for comparison) with a fixed outer
// boundary (paper sections 3 and 4.1), or the natural conformal map with two
// pinned vertices (section 4.2, eq. 7). parameterize(mesh, options) is
// exactly Parameterizer(mesh, options).solve() (parameterizer.h); this
// header holds the options and the result every mode shares
// (docs/maths.md §2-§4).
#pragma once

#include <string>
#include <vector>

#include "intrinsic/choice.h"
#include "intrinsic/boundary.h"
#include "intrinsic/constraints.h"
#include "intrinsic/solver_kind.h"
#include "intrinsic/mesh.h"
#include "intrinsic/metrics.h"
#include "intrinsic/weights.h"

namespace intrinsic {

// The scale asked for (options).
enum class ScaleMode { Unit, Surface };
template <>
ChoiceTable<ScaleMode> choice_table<ScaleMode>();

// Where the result was placed (result): fitted into [0,1]^2, at the
// surface's own scale, or exactly where given positions or pins put it.
enum class Placement { Unit, Surface, Given };
template <>
ChoiceTable<Placement> choice_table<Placement>();
std::string placement_name(Placement p);  // "unit", "surface", "given"

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
template <>
ChoiceTable<HoleRule> choice_table<HoleRule>();

std::string hole_rule_name(HoleRule r);  // "fill", "free", "natural"

// The hole rule that was applied (result). FreeNoConformalTerm: HoleRule::Natural
// asked for with a method that has no conformal part, so the holes were free.
enum class HolesApplied { None, Fill, Free, Natural, FreeNoConformalTerm };
template <>
ChoiceTable<HolesApplied> choice_table<HolesApplied>();
// "none", "fill", "free", "natural", "free (method has no conformal term)".
std::string holes_applied_name(HolesApplied h);

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

// A chart of a mesh in several pieces (charts.h): one per component.
enum class ChartFallback {
  None,
  NoGivenPositions,  // the boundary file gives no position on this component
  LoopTooShort,      // a square needs at least 4 vertices on the outer loop
};
std::string chart_fallback_name(ChartFallback f);  // "", "no given boundary positions on this chart", ...

struct ChartSummary {
  int component = 0;            // index in mesh.topology
  int vertices = 0, faces = 0;  // used vertices and faces of the chart
  BoundaryShape boundary = BoundaryShape::Circle;  // what this chart was solved with
  WeightOptions weights;        // what this chart was solved with
  ChartFallback fallback = ChartFallback::None;  // why it got the natural map instead of the options'
  HolesApplied holes = HolesApplied::None;
  bool packed = true;           // false: kept where given positions or pins put it
  int flipped_triangles = 0;
  double angle_distortion_mean = 0;
  double residual = 0;
  int free_vertices = 0, fixed_vertices = 0;
  Eigen::Vector2d box_min = Eigen::Vector2d::Zero(), box_max = Eigen::Vector2d::Zero();  // in the final layout
};

struct ParamResult {
  MatrixX2d UV;  // #V x 2, unused vertices at (0, 0)
  // What was solved (not what was asked: optimal lambda solves a mixed map,
  // a chart may fall back to the natural map).
  WeightOptions weights;
  BoundaryShape boundary = BoundaryShape::Circle;
  Spacing spacing = Spacing::ArcLength;
  Placement placement = Placement::Unit;
  HolesApplied holes = HolesApplied::None;
  std::vector<SolverKind> solvers;  // backends used, in order of first use; empty when every vertex is fixed
  double residual = 0;      // max over u, v (and charts) of |A x - b| / |b|; with constraints |A x + C^T l - b| / |b|
  int free_vertices = 0;    // unknowns per coordinate (summed over charts)
  int fixed_vertices = 0;
  int filled_holes = 0;
  int factorizations = 0;
  int iterations = 0;       // iterative solvers only
  std::vector<FixedVertex> pins;  // natural map: the pins used, before any placement
  std::vector<ConstraintResidual> constraints;  // one per resolved constraint row
  std::vector<ChartSummary> charts;  // several components only (charts.h); empty otherwise
  StageTimings timings;
};

// "cholmod", "cholmod, umfpack", or "none (every vertex is fixed)".
std::string solvers_name(const std::vector<SolverKind>& solvers);

// Parameterizer(mesh, options).solve(). Throws Error(Usage) for
// inconsistent options (natural boundary with a non-conformal method, fewer
// than two pins, pins without natural boundary), Error(Input) when the mesh
// cannot take them (missing outer-loop vertex in `given`, pin on a vertex
// that does not exist), Error(Numerical) when the solve fails or the
// residual is too large (the message then names the likely cause).
ParamResult parameterize(const Mesh& mesh, const ParamOptions& options);

// Positions of the fixed vertices before any scaling: the outer loop on the
// circle or square of [-1, 1]^2, or the given positions (checked to cover the
// outer loop; Error(Input) names a missing vertex).
std::vector<FixedVertex> boundary_positions(const Mesh& mesh, const ParamOptions& options);

// Similarity that moves UV into [0,1]^2 (centred, aspect kept), or scaling
// about the origin so the parameter area equals the 3D area. Both are the
// one placement function of docs/maths.md §2.4.
void fit_unit_square(MatrixX2d& UV, const std::vector<char>& used);
void scale_to_surface_area(MatrixX2d& UV, const Mesh& mesh);

// Sum of signed parameter areas of the faces.
double parameter_area(const MatrixX3i& F, const MatrixX2d& UV);
double surface_area(const MatrixX3d& V, const MatrixX3i& F);

}  // namespace intrinsic
