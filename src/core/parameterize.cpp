// parameterize() (= Parameterizer(mesh, options).solve()), the fixed
// boundary positions (paper section 4.1), the names of the result's
// enumerations, and the area helpers (docs/maths.md §2).
#include "intrinsic/parameterize.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "core/placement.h"
#include "intrinsic/error.h"
#include "intrinsic/choice.h"
#include "intrinsic/parameterizer.h"

namespace intrinsic {

namespace {

// Two fixed vertices at one point fold the parameterization (a boundary that
// touches itself, or collapsed triangles): refused, naming both vertices.
void check_distinct_positions(const std::vector<FixedVertex>& given) {
  std::vector<int> order(given.size());
  std::iota(order.begin(), order.end(), 0);
  const auto key = [&](int i) { return std::make_pair(given[i].uv.x(), given[i].uv.y()); };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  for (size_t k = 1; k < order.size(); ++k) {
    const FixedVertex &a = given[order[k - 1]], &b = given[order[k]];
    if (a.uv == b.uv)
      throw_input("the boundary positions give vertices " + std::to_string(std::min(a.vertex, b.vertex)) + " and " +
                  std::to_string(std::max(a.vertex, b.vertex)) + " the same position (" + short_number(a.uv.x()) +
                  ", " + short_number(a.uv.y()) + ")");
  }
}

}  // namespace

std::vector<FixedVertex> boundary_positions(const Mesh& mesh, const ParamOptions& o) {
  const Topology& t = mesh.topology;
  const std::vector<int>& outer = t.boundary_loops.at(t.component_loops.at(0).at(0));
  switch (o.boundary) {
    case BoundaryShape::Circle: return circle_boundary(mesh.V, outer, o.spacing);
    case BoundaryShape::Square: return square_boundary(mesh.V, outer, o.spacing);
    case BoundaryShape::Given: break;
    case BoundaryShape::Natural: return {};  // pins instead: natural_pins()
  }
  std::vector<char> given(mesh.V.rows(), 0);
  for (const FixedVertex& fv : o.given) {
    if (fv.vertex < 0 || fv.vertex >= mesh.V.rows())
      throw_input("boundary position for vertex " + std::to_string(fv.vertex) + ", which does not exist");
    if (!t.is_used[fv.vertex])
      throw_input("boundary position for vertex " + std::to_string(fv.vertex) + ", which no face uses");
    given[fv.vertex] = 1;
  }
  int missing = 0, first_missing = -1;
  for (int v : outer)
    if (!given[v]) {
      if (missing++ == 0) first_missing = v;
    }
  if (missing > 0)
    throw_input("the boundary positions miss " + std::to_string(missing) + " of the " +
                std::to_string(outer.size()) + " outer-loop vertices, e.g. vertex " + std::to_string(first_missing));
  check_distinct_positions(o.given);
  return o.given;
}

std::string hole_rule_name(HoleRule r) { return choice_name(r); }

std::string holes_applied_name(HolesApplied h) { return choice_name(h); }

std::string placement_name(Placement p) { return choice_name(p); }

std::string chart_fallback_name(ChartFallback f) {
  switch (f) {
    case ChartFallback::None: return "";
    case ChartFallback::NoGivenPositions: return "natural map: the boundary file gives no position on this chart";
    case ChartFallback::LoopTooShort: return "natural map: the outer loop has fewer than 4 vertices for a square";
  }
  return "?";
}

std::string solvers_name(const std::vector<SolverKind>& solvers) {
  if (solvers.empty()) return "none (every vertex is fixed)";
  std::string out;
  for (SolverKind k : solvers) out += (out.empty() ? "" : ", ") + solver_name(k);
  return out;
}

double parameter_area(const MatrixX3i& F, const MatrixX2d& UV) {
  double area = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector2d a = UV.row(F(f, 0)), b = UV.row(F(f, 1)), c = UV.row(F(f, 2));
    area += 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
  }
  return area;
}

double surface_area(const MatrixX3d& V, const MatrixX3i& F) {
  double area = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

void fit_unit_square(MatrixX2d& UV, const std::vector<char>& used) {
  // F is not needed to fit a bounding box.
  detail::apply(detail::placement(detail::PlacementRule::FitUnitSquare, MatrixX3d(), MatrixX3i(), UV, used), UV, used);
}

void scale_to_surface_area(MatrixX2d& UV, const Mesh& mesh) {
  const std::vector<char> used(mesh.topology.is_used.begin(), mesh.topology.is_used.end());
  detail::apply(detail::placement(detail::PlacementRule::SurfaceArea, mesh.V, mesh.F, UV, used), UV, used);
}

ParamResult parameterize(const Mesh& mesh, const ParamOptions& o) { return Parameterizer(mesh, o).solve(); }

// How the command line, Python and the reports spell these (intrinsic/choice.h).
template <>
ChoiceTable<ScaleMode> choice_table<ScaleMode>() {
  static const Choice<ScaleMode> rows[] = {{ScaleMode::Unit, "unit"}, {ScaleMode::Surface, "surface"}};
  return make_choice_table(rows);
}

// A result's placement: "given" is where given positions or pins put it.
template <>
ChoiceTable<Placement> choice_table<Placement>() {
  static const Choice<Placement> rows[] = {
      {Placement::Unit, "unit"}, {Placement::Surface, "surface"}, {Placement::Given, "given", false}};
  return make_choice_table(rows);
}

template <>
ChoiceTable<HoleRule> choice_table<HoleRule>() {
  static const Choice<HoleRule> rows[] = {
      {HoleRule::Fill, "fill"}, {HoleRule::Free, "free"}, {HoleRule::Natural, "natural"}};
  return make_choice_table(rows);
}

// What a result applied to its holes (reports only, never parsed).
template <>
ChoiceTable<HolesApplied> choice_table<HolesApplied>() {
  static const Choice<HolesApplied> rows[] = {{HolesApplied::None, "none", false},
                                              {HolesApplied::Fill, "fill", false},
                                              {HolesApplied::Free, "free", false},
                                              {HolesApplied::Natural, "natural", false},
                                              {HolesApplied::FreeNoConformalTerm,
                                               "free (method has no conformal term)", false}};
  return make_choice_table(rows);
}

}  // namespace intrinsic
