// Assembly of the weight matrix from per-face contributions, and the split
// that eliminates fixed vertices (SPEC section 2: boundary rows are moved to
// the right-hand side rather than kept as identity rows, so the conformal
// block stays symmetric).
#include "intrinsic/assemble.h"

namespace intrinsic {

SparseMatrix assemble_weight_matrix(const MatrixX3d& V, const MatrixX3i& F, const WeightOptions& w) {
  const int n = static_cast<int>(V.rows());
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(12 * static_cast<size_t>(F.rows()));
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Matrix3d W = face_weights(V, F, f, w);
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) {
        if (c == d) continue;
        const int i = F(f, c), j = F(f, d);
        triplets.emplace_back(i, j, -W(c, d));
        triplets.emplace_back(i, i, W(c, d));
      }
  }
  SparseMatrix K(n, n);
  K.setFromTriplets(triplets.begin(), triplets.end());
  return K;
}

Partition partition(int num_vertices, const std::vector<char>& is_fixed, const std::vector<char>& is_used) {
  Partition p;
  p.free_index.assign(num_vertices, -1);
  p.fixed_index.assign(num_vertices, -1);
  for (int v = 0; v < num_vertices; ++v) {
    if (!is_used[v]) continue;
    if (is_fixed[v]) {
      p.fixed_index[v] = static_cast<int>(p.fixed_vertices.size());
      p.fixed_vertices.push_back(v);
    } else {
      p.free_index[v] = static_cast<int>(p.free_vertices.size());
      p.free_vertices.push_back(v);
    }
  }
  return p;
}

void split_matrix(const SparseMatrix& K, const Partition& p, SparseMatrix& K_II, SparseMatrix& K_IB) {
  std::vector<Eigen::Triplet<double>> ii, ib;
  ii.reserve(K.nonZeros());
  for (int j = 0; j < K.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(K, j); it; ++it) {
      const int r = p.free_index[it.row()];
      if (r < 0) continue;
      if (p.free_index[j] >= 0) ii.emplace_back(r, p.free_index[j], it.value());
      else if (p.fixed_index[j] >= 0) ib.emplace_back(r, p.fixed_index[j], it.value());
    }
  K_II.resize(static_cast<int>(p.free_vertices.size()), static_cast<int>(p.free_vertices.size()));
  K_IB.resize(static_cast<int>(p.free_vertices.size()), static_cast<int>(p.fixed_vertices.size()));
  K_II.setFromTriplets(ii.begin(), ii.end());
  K_IB.setFromTriplets(ib.begin(), ib.end());
}

}  // namespace intrinsic
