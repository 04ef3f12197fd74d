// Assembly of the weight matrix from per-face contributions, and the split
// that eliminates fixed vertices (docs/maths.md §2.3: boundary rows are moved to
// the right-hand side rather than kept as identity rows, so the conformal
// block stays symmetric).
//
// Both go straight into compressed column storage: the pattern of K is the
// vertex adjacency plus the diagonal, built from the faces by a counting
// pass, and each face then adds its weights in place (no triplet list, which
// at 1M vertices costs 12 x #F triplets of 16 bytes and a sort).
#include "intrinsic/assemble.h"

#include <algorithm>

#include "util/parallel_for.h"

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
void add_faces(const MatrixX3d& V, const MatrixX3i& F, const WeightOptions& w, int f0, int f1,
               const std::vector<int>& begin, const std::vector<int>& row, const std::vector<int>& diag,
               double* value) {
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

}  // namespace

SparseMatrix assemble_weight_matrix(const MatrixX3d& V, const MatrixX3i& F, const WeightOptions& w) {
  const int n = static_cast<int>(V.rows());
  const int m = static_cast<int>(F.rows());
  // Pattern: every vertex's column holds itself and its face neighbours
  // (each incident face names two), then sorted and deduplicated.
  std::vector<int> begin(n + 1, 0);
  for (int f = 0; f < m; ++f)
    for (int c = 0; c < 3; ++c) begin[F(f, c) + 1] += 2;
  for (int v = 0; v < n; ++v) begin[v + 1] += begin[v] + 1;
  std::vector<int> row(begin[n]), fill(begin.begin(), begin.end() - 1);
  for (int v = 0; v < n; ++v) row[fill[v]++] = v;
  for (int f = 0; f < m; ++f)
    for (int c = 0; c < 3; ++c) {
      const int j = F(f, c);
      row[fill[j]++] = F(f, (c + 1) % 3);
      row[fill[j]++] = F(f, (c + 2) % 3);
    }
  std::vector<int> diag(n);
  detail::parallel_for(n, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t v = first; v < last; ++v) std::sort(row.begin() + begin[v], row.begin() + begin[v + 1]);
  });
  int out = 0;
  for (int v = 0; v < n; ++v) {
    const int b = begin[v], e = begin[v + 1];
    begin[v] = out;
    for (int k = b; k < e; ++k)
      if (k == b || row[k] != row[k - 1]) {
        if (row[k] == v) diag[v] = out;
        row[out++] = row[k];
      }
  }
  begin[n] = out;

  // Values: each part of the faces adds into its own array (faces share
  // vertices), summed after in part order.
  const int parts = detail::parallel_parts(m, 50000);
  std::vector<std::vector<double>> values(parts, std::vector<double>(out, 0.0));
  detail::parallel_for_parts(m, parts, [&](int part, std::int64_t f0, std::int64_t f1) {
    add_faces(V, F, w, static_cast<int>(f0), static_cast<int>(f1), begin, row, diag, values[part].data());
  });
  std::vector<double> value = std::move(values[0]);
  for (int part = 1; part < parts; ++part)
    for (int k = 0; k < out; ++k) value[k] += values[part][k];
  return make_csc(n, n, begin, std::move(row), std::move(value));
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
