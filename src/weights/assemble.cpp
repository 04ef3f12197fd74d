// Assembly of the weight matrix from per-face contributions (its split into
// free and fixed blocks is solve/partition.h).
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
#include "solve/partition.h"
#include "weights/assemble_stages.h"

namespace intrinsic {
namespace {

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

}  // namespace intrinsic
