// Local/global isometric refinement (isometric_refinement.h; docs/maths.md
// §9.9). Per face, in its own 2D frame x, the energy is
//   sum over its edges (a, b), opposite corner k, of cot(theta_k) |(u_a - u_b) - R (x_a - x_b)|^2,
// which is 2 A |J - R|^2 summed over the face: the local step takes the
// rotation R nearest to the face's Jacobian, the global step solves
// K u = b for all u with one vertex kept in place (K: the conformal matrix,
// whose entries are exactly these cotangent sums).
#include "optimize/isometric_refinement.h"

#include <algorithm>
#include <cmath>

#include "weights/assemble.h"
#include "intrinsic/error.h"

namespace intrinsic::detail {
namespace {

// One face in its own frame: corner positions and the cotangent at each corner.
struct FaceFrame {
  Eigen::Vector2d x[3];
  double cot[3];
  double area;
};

std::vector<FaceFrame> face_frames_2d(const Mesh& mesh) {
  std::vector<FaceFrame> frames(mesh.F.rows());
  for (int f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d p0 = mesh.V.row(mesh.F(f, 0)), e1 = mesh.V.row(mesh.F(f, 1)) - p0.transpose(),
                          e2 = mesh.V.row(mesh.F(f, 2)) - p0.transpose();
    const double l1 = e1.norm(), twice = e1.cross(e2).norm();
    FaceFrame& t = frames[f];
    t.x[0] = {0, 0};
    t.x[1] = {l1, 0};
    t.x[2] = {e1.dot(e2) / l1, twice / l1};
    t.area = twice / 2;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d a = t.x[(k + 1) % 3] - t.x[k], b = t.x[(k + 2) % 3] - t.x[k];
      t.cot[k] = a.dot(b) / twice;
    }
  }
  return frames;
}

// The rotation nearest (Frobenius) to the face's map, from the cotangent-weighted edge products.
Eigen::Matrix2d best_rotation(const FaceFrame& t, const Eigen::Vector2d u[3]) {
  Eigen::Matrix2d S = Eigen::Matrix2d::Zero();
  for (int k = 0; k < 3; ++k) {
    const int a = (k + 1) % 3, b = (k + 2) % 3;
    S += t.cot[k] * (u[a] - u[b]) * (t.x[a] - t.x[b]).transpose();
  }
  // The rotation by the angle atan2(y, x), built from (x, y) directly: no
  // atan2, sine and cosine per face (the local step was up to a third of a
  // step's time, the solve the rest).
  const double x = S(0, 0) + S(1, 1), y = S(1, 0) - S(0, 1), h = std::hypot(x, y);
  const double c = h > 0 ? x / h : 1, s = h > 0 ? y / h : 0;
  Eigen::Matrix2d R;
  R << c, -s, s, c;
  return R;
}

// Right-hand side of the global step and the energy of UV against the rotations it implies.
Eigen::MatrixXd rotated_edges(const Mesh& mesh, const std::vector<FaceFrame>& frames, const MatrixX2d& UV,
                              double& energy) {
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(mesh.V.rows(), 2);
  energy = 0;
  for (int f = 0; f < mesh.F.rows(); ++f) {
    const FaceFrame& t = frames[f];
    Eigen::Vector2d u[3];
    for (int c = 0; c < 3; ++c) u[c] = UV.row(mesh.F(f, c)).transpose();
    const Eigen::Matrix2d R = best_rotation(t, u);
    for (int k = 0; k < 3; ++k) {
      const int a = (k + 1) % 3, b_ = (k + 2) % 3;
      const Eigen::Vector2d r = t.cot[k] * (R * (t.x[a] - t.x[b_]));
      b.row(mesh.F(f, a)) += r.transpose();
      b.row(mesh.F(f, b_)) -= r.transpose();
      energy += 0.5 * t.cot[k] * ((u[a] - u[b_]) - R * (t.x[a] - t.x[b_])).squaredNorm();
    }
  }
  return b;
}

bool fold_free(const Mesh& mesh, const MatrixX2d& UV, double ratio) {
  for (int f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector2d p0 = UV.row(mesh.F(f, 0)), p1 = UV.row(mesh.F(f, 1)), p2 = UV.row(mesh.F(f, 2));
    const Eigen::Vector2d a = p1 - p0, b = p2 - p0;
    const double twice = a.x() * b.y() - a.y() * b.x();
    const double longest = std::max({a.squaredNorm(), b.squaredNorm(), (p2 - p1).squaredNorm()});
    if (!(twice > ratio * longest)) return false;
  }
  return true;
}

}  // namespace

IsometricRefinementResult refine_isometric(const Mesh& mesh, MatrixX2d& UV, const IsometricRefinementOptions& options) {
  IsometricRefinementResult result;
  const int n = static_cast<int>(mesh.V.rows());
  if (n < 4 || options.iterations <= 0) return result;
  const std::vector<FaceFrame> frames = face_frames_2d(mesh);
  // Vertex 0 stays in place: the energy does not see translations.
  std::vector<char> fixed(n, 0), used(n, 1);
  fixed[0] = 1;
  const Partition p = partition(n, fixed, used);
  SparseMatrix K_II, K_IB;
  split_matrix(assemble_weight_matrix(mesh.V, mesh.F, WeightOptions()), p, K_II, K_IB);
  LinearSolver solver(SolverKind::Auto, true);
  try {
    solver.factor(std::move(K_II));
  } catch (const Error&) {
    return result;
  }
  double energy = 0;
  Eigen::MatrixXd b = rotated_edges(mesh, frames, UV, energy);
  result.energy_before = result.energy_after = energy;
  for (int it = 0; it < options.iterations; ++it) {
    Eigen::MatrixXd rhs(p.free_vertices.size(), 2);
    for (size_t i = 0; i < p.free_vertices.size(); ++i) rhs.row(i) = b.row(p.free_vertices[i]);
    rhs -= K_IB * Eigen::MatrixXd(UV.topRows(1));
    const Eigen::MatrixXd x = solver.solve(rhs);
    MatrixX2d next = UV;
    for (size_t i = 0; i < p.free_vertices.size(); ++i) next.row(p.free_vertices[i]) = x.row(i);
    // A step that folds is shortened toward the current (fold-free) map.
    double step = 1;
    MatrixX2d trial = next;
    while (!fold_free(mesh, trial, options.degenerate_ratio) && step > 1.0 / 16) {
      step /= 2;
      trial = UV + step * (next - UV);
    }
    if (step <= 1.0 / 16 || !trial.allFinite()) break;
    double e = 0;
    const Eigen::MatrixXd b_next = rotated_edges(mesh, frames, trial, e);
    // Each step cannot raise the energy (the local and the global step are
    // both exact minimisations, and a shortened step stays below the old
    // map for the same rotations): a rise is rounding, or something wrong.
    if (!(e <= energy * (1 + 1e-9))) break;
    // Stop once a step gains under 1e-4 of the energy: further steps change
    // the map by less than the figures are read to. The test is far from
    // rounding, so the same chart listed in another vertex order takes the
    // same number of steps.
    const bool converged = energy - e < 1e-4 * energy;
    UV = trial, b = b_next, energy = e;
    ++result.iterations;
    if (converged || energy < 1e-12 * result.energy_before) break;
  }
  result.energy_after = energy;
  return result;
}

}  // namespace intrinsic::detail
