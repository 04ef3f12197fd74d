// The fixed-boundary member of the intrinsic family (paper section 4.1):
// choose fixed vertices, close or free the holes, eliminate, factor once,
// solve u and v together, check the residual, scale.
#include "intrinsic/parameterize.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "intrinsic/assemble.h"
#include "intrinsic/error.h"

namespace intrinsic {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// "1.5e-12", "0.25": numbers in messages (std::to_string would print 0.000000).
std::string short_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

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

// Positions of the fixed vertices: the outer loop on the chosen shape, or the
// user's positions (which must cover the outer loop).
std::vector<FixedVertex> fixed_positions(const Mesh& mesh, const ParamOptions& o) {
  const Topology& t = mesh.topology;
  const std::vector<int>& outer = t.boundary_loops.at(t.component_loops.at(0).at(0));
  switch (o.boundary) {
    case BoundaryShape::Circle: return circle_boundary(mesh.V, outer, o.spacing);
    case BoundaryShape::Square: return square_boundary(mesh.V, outer, o.spacing);
    case BoundaryShape::Given: break;
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

}  // namespace

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
  const double s = std::sqrt(a_surface / a_param);
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  int count = 0;
  for (int v = 0; v < UV.rows(); ++v)
    if (mesh.topology.is_used[v]) { centroid += UV.row(v).transpose(); ++count; }
  centroid /= std::max(count, 1);
  for (int v = 0; v < UV.rows(); ++v)
    if (mesh.topology.is_used[v]) UV.row(v) = (centroid + s * (UV.row(v).transpose() - centroid)).transpose();
}

ParamResult parameterize(const Mesh& mesh, const ParamOptions& o) {
  const Topology& t = mesh.topology;
  if (t.num_components != 1)
    throw_usage("parameterize takes one connected component; this mesh has " + std::to_string(t.num_components));
  if (t.component_loops[0].empty()) throw_input("the surface is closed (no boundary)");
  if (o.weights.method == Method::Mixed && o.weights.lambda == 0 && o.weights.mu == 0)
    throw_usage("mixed method needs lambda and mu not both zero");
  if (!std::isfinite(o.weights.lambda) || !std::isfinite(o.weights.mu))
    throw_usage("lambda and mu must be finite");

  ParamResult result;
  const auto t_assemble = std::chrono::steady_clock::now();
  const int n = static_cast<int>(mesh.V.rows());
  const std::vector<FixedVertex> fixed = fixed_positions(mesh, o);

  // Working copy of the surface, extended by one vertex per filled hole.
  MatrixX3d V = mesh.V;
  MatrixX3i F = mesh.F;
  std::vector<char> is_fixed(n, 0), is_used(t.is_used.begin(), t.is_used.end());
  for (const FixedVertex& fv : fixed) is_fixed[fv.vertex] = 1;
  if (o.holes == HoleRule::Fill) {
    std::vector<Eigen::Vector3i> fan;
    std::vector<Eigen::Vector3d> centres;
    for (size_t k = 1; k < t.component_loops[0].size(); ++k) {
      const std::vector<int>& loop = t.boundary_loops[t.component_loops[0][k]];
      bool all_fixed = true;
      for (int v : loop) all_fixed = all_fixed && is_fixed[v];
      if (all_fixed) continue;  // the user placed this hole
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (int v : loop) c += mesh.V.row(v).transpose();
      c /= static_cast<double>(loop.size());
      const int centre = n + static_cast<int>(centres.size());
      bool degenerate = false;
      std::vector<Eigen::Vector3i> faces;
      for (size_t i = 0; i < loop.size(); ++i) {
        const int a = loop[i], b = loop[(i + 1) % loop.size()];
        const Eigen::Vector3d xa = mesh.V.row(a), xb = mesh.V.row(b);
        const double twice = (xa - xb).cross(c - xb).norm();
        degenerate = degenerate || !(twice > 1e-12 * std::max((xa - xb).squaredNorm(), (c - xb).squaredNorm()));
        faces.emplace_back(b, a, centre);  // opposite to the boundary half-edge a->b
      }
      if (degenerate) continue;  // this hole stays free
      centres.push_back(c);
      fan.insert(fan.end(), faces.begin(), faces.end());
    }
    if (!centres.empty()) {
      V.conservativeResize(n + static_cast<int>(centres.size()), 3);
      for (size_t k = 0; k < centres.size(); ++k) V.row(n + static_cast<int>(k)) = centres[k].transpose();
      const int m = static_cast<int>(F.rows());
      F.conservativeResize(m + static_cast<int>(fan.size()), 3);
      for (size_t k = 0; k < fan.size(); ++k) F.row(m + static_cast<int>(k)) = fan[k].transpose();
      is_fixed.resize(V.rows(), 0);
      is_used.resize(V.rows(), 1);
      result.filled_holes = static_cast<int>(centres.size());
    }
  }

  const SparseMatrix K = assemble_weight_matrix(V, F, o.weights);
  const Partition p = partition(static_cast<int>(V.rows()), is_fixed, is_used);
  SparseMatrix A, K_IB;
  split_matrix(K, p, A, K_IB);
  Eigen::MatrixXd UB(p.fixed_vertices.size(), 2);
  for (const FixedVertex& fv : fixed) UB.row(p.fixed_index[fv.vertex]) = fv.uv.transpose();
  const Eigen::MatrixXd rhs = -(K_IB * UB);
  result.free_vertices = static_cast<int>(p.free_vertices.size());
  result.fixed_vertices = static_cast<int>(p.fixed_vertices.size());
  result.timings.assemble_ms = ms_since(t_assemble);

  Eigen::MatrixXd X(0, 2);
  if (result.free_vertices > 0) {
    const auto t_factor = std::chrono::steady_clock::now();
    LinearSolver solver(o.solver, is_symmetric(o.weights));
    try {
      solver.factor(A);
    } catch (const Error& e) {
      if (e.kind() != ErrorKind::Numerical) throw;
      throw_numerical(e.what() + likely_cause(mesh, K, p));
    }
    result.timings.factor_ms = ms_since(t_factor);
    const auto t_solve = std::chrono::steady_clock::now();
    X = solver.solve(rhs);
    result.timings.solve_ms = ms_since(t_solve);
    result.solver = solver.name();
    result.factorizations = solver.factorizations();
    result.iterations = solver.iterations();
    if (!X.allFinite())
      throw_numerical("the solution has non-finite values: the system is singular or nearly so" +
                      likely_cause(mesh, K, p));
    for (int c = 0; c < 2; ++c) {
      const double b = rhs.col(c).norm();
      const double r = (A * X.col(c) - rhs.col(c)).norm();
      result.residual = std::max(result.residual, b > 0 ? r / b : r);
    }
    if (!(result.residual <= o.max_residual))
      throw_numerical("the relative residual " + short_number(result.residual) + " of solver " + result.solver +
                      " exceeds " + short_number(o.max_residual) +
                      " (an iterative solver may not have converged; try --solver auto)" + likely_cause(mesh, K, p));
  } else {
    result.solver = "none (every vertex is fixed)";
  }

  result.UV = MatrixX2d::Zero(n, 2);
  for (int v = 0; v < n; ++v) {
    if (p.free_index[v] >= 0) result.UV.row(v) = X.row(p.free_index[v]);
    else if (p.fixed_index[v] >= 0) result.UV.row(v) = UB.row(p.fixed_index[v]);
  }
  if (o.boundary == BoundaryShape::Given) {
    result.scale = "given";
  } else if (o.scale == ScaleMode::Unit) {
    // The circle and square live in [-1, 1]^2: map that box onto [0, 1]^2
    // exactly (a bounding-box fit would depend on where the vertices fall).
    for (int v = 0; v < n; ++v)
      if (t.is_used[v]) result.UV.row(v) = 0.5 * result.UV.row(v) + Eigen::RowVector2d(0.5, 0.5);
    result.scale = "unit";
  } else {
    scale_to_surface_area(result.UV, mesh);
    result.scale = "surface";
  }
  return result;
}

}  // namespace intrinsic
