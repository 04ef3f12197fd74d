// The one-call fixed-boundary map (paper section 4.1), a thin wrapper over
// Parameterizer, plus the boundary positions and the area and scaling
// helpers it shares.
#include "intrinsic/parameterize.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "core/natural_map.h"
#include "intrinsic/assemble.h"
#include "intrinsic/error.h"
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

// After a failed solve: what cheap checks can tell about why. Free vertices
// that nonzero weights do not tie to any fixed vertex make the system
// singular; non-finite weights and nearly degenerate faces make it
// ill-conditioned. Empty when nothing is found.
std::string likely_cause(const Mesh& mesh, const SparseMatrix& K, const Partition& p) {
  std::vector<std::string> causes;
  std::vector<std::vector<int>> adjacent(K.rows());
  bool finite = true;
  for (int c = 0; c < K.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(K, c); it; ++it) {
      finite = finite && std::isfinite(it.value());
      if (it.row() != it.col() && it.value() != 0) adjacent[it.row()].push_back(static_cast<int>(it.col()));
    }
  if (!finite) causes.push_back("some weights are not finite");
  std::vector<char> reached(K.rows(), 0);
  std::vector<int> queue(p.fixed_vertices.begin(), p.fixed_vertices.end());
  for (int v : queue) reached[v] = 1;
  for (size_t k = 0; k < queue.size(); ++k)
    for (int w : adjacent[queue[k]])
      if (!reached[w]) reached[w] = 1, queue.push_back(w);
  int cut_off = 0, first = -1;
  for (int v : p.free_vertices)
    if (!reached[v] && cut_off++ == 0) first = v;
  if (cut_off > 0)
    causes.push_back(std::string(first < mesh.V.rows() ? "vertex " + std::to_string(first) : "a hole's fill vertex") +
                     (cut_off > 1 ? " and " + std::to_string(cut_off - 1) + " other free vertices are" : " is") +
                     " not tied to any fixed vertex by a nonzero weight");
  double worst = INFINITY;
  int worst_face = -1;
  for (int f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d x0 = mesh.V.row(mesh.F(f, 0)), x1 = mesh.V.row(mesh.F(f, 1)), x2 = mesh.V.row(mesh.F(f, 2));
    const double longest = std::max({(x1 - x0).squaredNorm(), (x2 - x1).squaredNorm(), (x0 - x2).squaredNorm()});
    const double ratio = (x1 - x0).cross(x2 - x0).norm() / longest;
    if (ratio < worst) worst = ratio, worst_face = f;
  }
  if (worst < 1e-6) {
    causes.push_back(mesh.describe_face(worst_face) + " is nearly degenerate (area / longest edge squared " +
                     short_number(worst) + ")");
  }
  std::string out;
  for (const std::string& c : causes) out += (out.empty() ? "; likely cause: " : "; ") + c;
  return out;
}

}  // namespace

std::vector<FixedVertex> boundary_positions(const Mesh& mesh, const ParamOptions& o) {
  const Topology& t = mesh.topology;
  const std::vector<int>& outer = t.boundary_loops.at(t.component_loops.at(0).at(0));
  switch (o.boundary) {
    case BoundaryShape::Circle: return circle_boundary(mesh.V, outer, o.spacing);
    case BoundaryShape::Square: return square_boundary(mesh.V, outer, o.spacing);
    case BoundaryShape::Given: break;
    case BoundaryShape::Natural: return {};  // handled by natural_map
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

std::string hole_rule_name(HoleRule r) {
  switch (r) {
    case HoleRule::Fill: return "fill";
    case HoleRule::Free: return "free";
    case HoleRule::Natural: return "natural";
  }
  return "?";
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
  Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (int v = 0; v < UV.rows(); ++v)
    if (used[v]) {
      lo = lo.cwiseMin(UV.row(v).transpose());
      hi = hi.cwiseMax(UV.row(v).transpose());
    }
  const double extent = (hi - lo).maxCoeff();
  if (!(extent > 0)) return;
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  for (int v = 0; v < UV.rows(); ++v)
    if (used[v]) UV.row(v) = ((UV.row(v).transpose() - centre) / extent + Eigen::Vector2d(0.5, 0.5)).transpose();
}

void scale_to_surface_area(MatrixX2d& UV, const Mesh& mesh) {
  const double a_param = std::abs(parameter_area(mesh.F, UV));
  const double a_surface = surface_area(mesh.V, mesh.F);
  if (!(a_param > 0)) return;
  // About the origin, so that maps sharing a fixed boundary still share it.
  UV *= std::sqrt(a_surface / a_param);
}

ParamResult parameterize(const Mesh& mesh, const ParamOptions& o) {
  const Topology& t = mesh.topology;
  if (t.num_components != 1)
    throw_usage("parameterize takes one connected component; this mesh has " + std::to_string(t.num_components));
  if (t.component_loops[0].empty()) throw_input("the surface is closed (no boundary)");
  if (o.boundary == BoundaryShape::Natural) return natural_map(mesh, o);
  if (!o.pins.empty()) throw_usage("pins apply to the natural boundary only (use given boundary positions instead)");
  ParamResult r;
  try {
    r = Parameterizer(mesh, o).solve();
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::Numerical) throw;
    // Diagnose on the mesh itself (holes left free): cheap, and only on failure.
    std::vector<char> fixed(mesh.V.rows(), 0);
    for (const FixedVertex& fv : boundary_positions(mesh, o)) fixed[fv.vertex] = 1;
    const Partition p = partition(static_cast<int>(mesh.V.rows()), fixed,
                                  std::vector<char>(t.is_used.begin(), t.is_used.end()));
    throw_numerical(e.what() + likely_cause(mesh, assemble_weight_matrix(mesh.V, mesh.F, o.weights), p));
  }
  r.holes = t.component_loops[0].size() == 1 ? "none"
            : solves_natural_holes(mesh, o)   ? "natural"
            : o.holes == HoleRule::Natural    ? "free (method has no conformal term)"
                                              : hole_rule_name(o.holes);
  return r;
}

}  // namespace intrinsic
