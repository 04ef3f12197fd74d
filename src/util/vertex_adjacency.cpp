// The vertex adjacency pattern of a face list (see vertex_adjacency.h): a
// counting sort of the faces' corner neighbours into per-vertex buckets,
// then a small sort per bucket (a handful of neighbours) instead of one sort
// of all 6m pairs.
#include "util/vertex_adjacency.h"

#include <algorithm>
#include <cstdint>

#include "util/parallel_for.h"

namespace intrinsic::detail {
namespace {

// Mapped: vertices renumbered through `number` (else kept as they are);
// Larger: only neighbours with a larger number. Both fixed at compile time,
// so the whole-mesh pattern (the assembly's, at 1M vertices) counts two
// entries per corner with no test at all.
template <bool Mapped, bool Larger>
SparseMatrix build(const MatrixX3i& F, int count, const int* number, bool self) {
  const auto id = [number](int v) {
    if constexpr (Mapped) return number[v];
    else return v;
  };
  const auto keep = []([[maybe_unused]] int j, [[maybe_unused]] int d) {
    if constexpr (Larger) return d > j;  // then d >= 0 too, as j is
    else if constexpr (Mapped) return d >= 0;
    else return true;
  };
  const std::int64_t m = F.rows();
  const int parts = parallel_parts(m);
  // at[p][j]: the number of part p's entries in column j, then its first slot.
  std::vector<std::vector<int>> at(parts, std::vector<int>(static_cast<size_t>(count), 0));
  parallel_for_parts(m, parts, [&](int p, std::int64_t f0, std::int64_t f1) {
    std::vector<int>& n = at[p];
    for (int c = 0; c < 3; ++c)
      for (std::int64_t f = f0; f < f1; ++f) {
        const int j = id(F(f, c));
        if (j >= 0) n[j] += keep(j, id(F(f, (c + 1) % 3))) + keep(j, id(F(f, (c + 2) % 3)));
      }
  });
  std::vector<int> begin(static_cast<size_t>(count) + 1, 0);
  for (int j = 0; j < count; ++j) {
    int slot = begin[j] + (self ? 1 : 0);  // the diagonal's slot first
    for (int p = 0; p < parts; ++p) {
      const int n = at[p][j];
      at[p][j] = slot;
      slot += n;
    }
    begin[j + 1] = slot;
  }
  std::vector<int> row(begin[count]);
  parallel_for_parts(m, parts, [&](int p, std::int64_t f0, std::int64_t f1) {
    std::vector<int>& fill = at[p];
    for (std::int64_t f = f0; f < f1; ++f)
      for (int c = 0; c < 3; ++c) {
        const int j = id(F(f, c));
        if (j < 0) continue;
        for (int d = 1; d < 3; ++d) {
          const int i = id(F(f, (c + d) % 3));
          if (keep(j, i)) row[fill[j]++] = i;
        }
      }
  });
  at.clear();
  // Sorted and deduplicated per column in place, then copied out.
  std::vector<int> distinct(count);
  parallel_for(count, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t j = first; j < last; ++j) {
      if (self) row[begin[j]] = static_cast<int>(j);
      std::sort(row.begin() + begin[j], row.begin() + begin[j + 1]);
      distinct[j] = static_cast<int>(std::unique(row.begin() + begin[j], row.begin() + begin[j + 1]) -
                                     (row.begin() + begin[j]));
    }
  });
  SparseMatrix P(count, count);
  int* outer = P.outerIndexPtr();
  outer[0] = 0;
  for (int j = 0; j < count; ++j) outer[j + 1] = outer[j] + distinct[j];
  P.resizeNonZeros(outer[count]);  // values allocated, not written
  int* inner = P.innerIndexPtr();
  parallel_for(count, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t j = first; j < last; ++j)
      std::copy(row.begin() + begin[j], row.begin() + begin[j] + distinct[j], inner + outer[j]);
  });
  return P;
}

}  // namespace

SparseMatrix vertex_adjacency_pattern(const MatrixX3i& F, int count, const std::vector<int>& number,
                                      AdjacencyNeighbours which) {
  const bool self = which == AdjacencyNeighbours::AllAndSelf;
  const bool larger = which == AdjacencyNeighbours::LargerOnly;
  if (number.empty())
    return larger ? build<false, true>(F, count, nullptr, self) : build<false, false>(F, count, nullptr, self);
  return larger ? build<true, true>(F, count, number.data(), self) : build<true, false>(F, count, number.data(), self);
}

}  // namespace intrinsic::detail
