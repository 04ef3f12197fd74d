// Union-find over indices 0..n-1 (parent[i] == i for a root): the root of
// x's set, halving the path on the way.
#pragma once

#include <vector>

namespace intrinsic::detail {

inline int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

}  // namespace intrinsic::detail
