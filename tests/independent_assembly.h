// The weights of docs/maths.md §1 assembled again from the formulas alone,
// sharing no code with src/weights: each corner angle is computed with
// atan2(|a x b|, a . b) and the cotangent or half-angle tangent taken with
// std::tan (the library divides a dot product by a cross-product norm), and
// the per-face contributions are summed by Eigen's triplet assembly. The
// tests use it to check that a map satisfies the equations of its method,
// row by row, without asking the library what those equations are.
#pragma once

#include <Eigen/Sparse>
#include <cmath>
#include <vector>

#include "intrinsic/mesh.h"
#include "intrinsic/weights.h"

namespace intrinsic::test {

using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// The angle at corner p of the 3D triangle (p, q, r).
inline double corner_angle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r) {
  const Eigen::Vector3d a = q - p, b = r - p;
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// A face (i, j, k)'s contribution to w_ij, the ordered pair i -> j, k the
// third corner (docs/maths.md §1.2, §1.3, §1.5, §1.6).
inline double pair_weight(const WeightOptions& w, const Eigen::Vector3d& xi, const Eigen::Vector3d& xj,
                          const Eigen::Vector3d& xk) {
  const double L2 = (xi - xj).squaredNorm();
  const double conformal = 1 / std::tan(corner_angle(xk, xi, xj));     // angle opposite the edge
  const double authalic = 1 / std::tan(corner_angle(xj, xk, xi)) / L2;  // angle at the far end x_j
  switch (w.method) {
    case Method::Conformal: return conformal;
    case Method::Authalic: return authalic;
    case Method::Mixed: return w.lambda * conformal + w.mu * authalic;
    case Method::Tutte: return 0.5;
    case Method::Floater: return std::tan(corner_angle(xi, xj, xk) / 2) / std::sqrt(L2);
  }
  return 0;
}

// W(i, j) = w_ij summed over the faces F (every ordered pair of every face).
inline RowSparse weight_table(const MatrixX3d& V, const MatrixX3i& F, const WeightOptions& w) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(6 * F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int i = F(f, c), j = F(f, (c + 1) % 3), k = F(f, (c + 2) % 3);
      const Eigen::Vector3d xi = V.row(i), xj = V.row(j), xk = V.row(k);
      t.emplace_back(i, j, pair_weight(w, xi, xj, xk));
      t.emplace_back(j, i, pair_weight(w, xj, xi, xk));
    }
  RowSparse W(V.rows(), V.rows());
  W.setFromTriplets(t.begin(), t.end());
  return W;
}

// Row i of "sum_j w_ij (u_i - u_j)" for both coordinates.
inline Eigen::RowVector2d row_value(const RowSparse& W, const MatrixX2d& UV, int i) {
  Eigen::RowVector2d r = Eigen::RowVector2d::Zero();
  for (RowSparse::InnerIterator it(W, i); it; ++it) r += it.value() * (UV.row(i) - UV.row(it.col()));
  return r;
}

// The magnitude of the terms of row i: sum_j |w_ij| times the map's size
// `extent` (largest |u|), the scale against which a rounding-level row value
// is judged (a backward error relative to the weights and the map).
inline double row_scale(const RowSparse& W, int i, double extent) {
  double s = 0;
  for (RowSparse::InnerIterator it(W, i); it; ++it) s += std::abs(it.value());
  return s * extent;
}

// The worst row of the method's equations over the used vertices not in
// `skip`, each row's value divided by its row_scale (plus the area term's
// 2 |lambda_h| extent):
//   sum_j w_ij (u_i - u_j) - lambda_h (v_b - v_p) = 0
//   sum_j w_ij (v_i - v_j) + lambda_h (u_b - u_p) = 0
// where the area term of the natural condition (docs/maths.md §3.3, §4.3)
// is present only on the loops listed in `natural_loops` (b, p: the vertex's
// successor and predecessor on its loop). `where` receives the worst vertex.
inline double worst_row(const RowSparse& W, const MatrixX2d& UV, const std::vector<char>& used,
                        const std::vector<char>& skip, const std::vector<std::vector<int>>& natural_loops,
                        double lambda_h, int* where = nullptr) {
  const Eigen::Index n = UV.rows();
  double extent = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (used[i]) extent = std::max(extent, UV.row(i).cwiseAbs().maxCoeff());
  MatrixX2d area = MatrixX2d::Zero(n, 2);
  for (const std::vector<int>& loop : natural_loops)
    for (size_t k = 0; k < loop.size(); ++k) {
      const int i = loop[k], b = loop[(k + 1) % loop.size()], p = loop[(k + loop.size() - 1) % loop.size()];
      area.row(i) = lambda_h * Eigen::RowVector2d(-(UV(b, 1) - UV(p, 1)), UV(b, 0) - UV(p, 0));
    }
  double worst = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!used[i] || skip[i]) continue;
    const Eigen::RowVector2d r = row_value(W, UV, static_cast<int>(i)) + area.row(i);
    const double s = row_scale(W, static_cast<int>(i), extent) + 2 * std::abs(lambda_h) * extent;
    const double rel = r.cwiseAbs().maxCoeff() / s;
    if (rel > worst) {
      worst = rel;
      if (where) *where = static_cast<int>(i);
    }
  }
  return worst;
}

}  // namespace intrinsic::test
