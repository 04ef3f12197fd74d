// Assembly of the weight matrix from per-face contributions, and the split
// that eliminates fixed vertices (docs/maths.md §2.3: boundary rows are moved to
// the right-hand side rather than kept as identity rows, so the conformal
// block stays symmetric).
//
// Both go straight into compressed column storage: the pattern of K is the
// vertex adjacency plus the diagonal, built from the faces by a counting
// pass (util/vertex_adjacency.h), and each face then adds its weights in
// place (no triplet list, which at 1M vertices costs 12 x #F triplets of 16
// bytes and a sort). Every pass runs on all cores with the same result on
// any number of them.
#include "weights/assemble.h"

#include <algorithm>

#include "util/parallel_for.h"
#include "util/vertex_adjacency.h"
#include "weights/assemble_stages.h"

namespace intrinsic {
namespace {

// Compressed-column matrix from its three arrays.
SparseMatrix make_csc(int rows, int cols, const std::vector<int>& begin, std::vector<int>&& index,
                      std::vector<double>&& value) {
  SparseMatrix M(rows, cols);
  const int nnz = begin[cols];
  M.resizeNonZeros(nnz);
  std::copy(begin.begin(), begin.end(), M.outerIndexPtr());
  std::copy(index.begin(), index.begin() + nnz, M.innerIndexPtr());
  std::copy(value.begin(), value.begin() + nnz, M.valuePtr());
  return M;
}

// Adds the contributions of faces [f0, f1) to the values of K (pattern in
// begin/row, diagonal positions in diag).
void add_faces(const MatrixX3d& V, const MatrixX3i& F, const WeightOptions& w, int f0, int f1, const int* begin,
               const int* row, const std::vector<int>& diag, double* value) {
  for (int f = f0; f < f1; ++f) {
    const Eigen::Matrix3d W = face_weights(V, F, f, w);
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) {
        if (c == d) continue;
        const int i = F(f, c), j = F(f, d);
        // Row i of column j (K_ij = -w_ij): columns hold a handful of rows.
        int k = begin[j];
        while (row[k] != i) ++k;
        value[k] -= W(c, d);
        value[diag[i]] += W(c, d);
      }
  }
}

// diag[v]: the position of (v, v) in K's values.
std::vector<int> diagonal_positions(const SparseMatrix& K) {
  const int n = static_cast<int>(K.cols());
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  std::vector<int> diag(n);
  detail::parallel_for(n, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t v = first; v < last; ++v)
      diag[v] = static_cast<int>(std::lower_bound(inner + outer[v], inner + outer[v + 1], static_cast<int>(v)) - inner);
  });
  return diag;
}

}  // namespace

SparseMatrix assemble_weight_matrix(const MatrixX3d& V, const MatrixX3i& F, const WeightOptions& w) {
  SparseMatrix K = detail::weight_matrix_pattern(F, static_cast<int>(V.rows()));
  detail::assemble_weight_values(V, F, w, K);
  return K;
}

namespace detail {

// The pattern is the vertex adjacency with the diagonal, built on all cores
// (util/vertex_adjacency.h): the same on any number of threads.
SparseMatrix weight_matrix_pattern(const MatrixX3i& F, int n) {
  return vertex_adjacency_pattern(F, n, {}, AdjacencyNeighbours::AllAndSelf);
}

void assemble_weight_values(const MatrixX3d& V, const MatrixX3i& F, const WeightOptions& w, SparseMatrix& K) {
  const int m = static_cast<int>(F.rows());
  const std::vector<int> diag = diagonal_positions(K);
  const int nnz = static_cast<int>(K.nonZeros());
  // Values: each part of the faces adds into its own array (faces share
  // vertices; part 0 into K's), summed after in part order, entry by entry
  // on all cores: the same sums whatever the threads.
  const int parts = detail::parallel_parts(m, 50000);
  double* value = K.valuePtr();
  std::fill(value, value + nnz, 0.0);
  std::vector<std::vector<double>> values(parts - 1, std::vector<double>(nnz, 0.0));
  detail::parallel_for_parts(m, parts, [&](int part, std::int64_t f0, std::int64_t f1) {
    add_faces(V, F, w, static_cast<int>(f0), static_cast<int>(f1), K.outerIndexPtr(), K.innerIndexPtr(), diag,
              part == 0 ? value : values[part - 1].data());
  });
  if (parts > 1)
    detail::parallel_for(nnz, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t k = first; k < last; ++k)
        for (int part = 1; part < parts; ++part) value[k] += values[part - 1][k];
    });
}

}  // namespace detail

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
  // Free and fixed indices increase with the vertex index, so each column's
  // rows stay sorted when copied in order.
  const int nf = static_cast<int>(p.free_vertices.size()), nb = static_cast<int>(p.fixed_vertices.size());
  auto extract = [&](const std::vector<int>& columns, SparseMatrix& out) {
    const int cols = static_cast<int>(columns.size());
    std::vector<int> begin(cols + 1, 0);
    for (int c = 0; c < cols; ++c) {
      int count = 0;
      for (SparseMatrix::InnerIterator it(K, columns[c]); it; ++it) count += p.free_index[it.row()] >= 0;
      begin[c + 1] = begin[c] + count;
    }
    std::vector<int> row(begin[cols]);
    std::vector<double> value(begin[cols]);
    for (int c = 0; c < cols; ++c) {
      int k = begin[c];
      for (SparseMatrix::InnerIterator it(K, columns[c]); it; ++it) {
        const int r = p.free_index[it.row()];
        if (r < 0) continue;
        row[k] = r;
        value[k++] = it.value();
      }
    }
    out = make_csc(nf, cols, begin, std::move(row), std::move(value));
  };
  extract(p.free_vertices, K_II);
  extract(p.fixed_vertices, K_IB);
  (void)nb;
}

}  // namespace intrinsic
