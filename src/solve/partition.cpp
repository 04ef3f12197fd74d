// The split of a system's unknowns into free and fixed ones, and of its
// matrix into the blocks that elimination needs (docs/maths.md §2.3: fixed
// rows move to the right-hand side rather than staying as identity rows, so
// a symmetric system keeps a symmetric free block).
#include "solve/partition.h"

#include <algorithm>

namespace intrinsic {

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
