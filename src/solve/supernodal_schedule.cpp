// The subtree split of a supernodal elimination tree (see
// supernodal_schedule.h).
#include "solve/supernodal_schedule.h"

#ifdef INTRINSIC_HAVE_SUITESPARSE

#include <algorithm>
#include <queue>

namespace intrinsic::detail {

// Asked once: glibc answers hardware_concurrency by reading
// /sys/devices/system/cpu/online, and every factorization asks (the atlas
// builds two per chart map it solves, hundreds on a small asset: 17% of the
// chart maps' time on decimated-knight).
int hardware_threads() {
  static const int threads = static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 8u));
  return threads;
}

DescendantLists descendant_lists(const SupernodalSymbolic& S) {
  const int ns = S.nsuper;
  DescendantLists out;
  std::vector<std::int64_t> count(ns + 1, 0);
  auto walk = [&](auto&& visit) {
    for (int d = 0; d < ns; ++d) {
      const std::int64_t p0 = S.pi[d], nsrow = S.nsrow(d);
      int last = -1;
      for (std::int64_t p = S.nscol(d); p < nsrow; ++p) {
        const int t = S.super_of[S.rows[p0 + p]];
        if (t != last) visit(t, d, static_cast<int>(p));
        last = t;
      }
    }
  };
  walk([&](int t, int, int) { ++count[t + 1]; });
  for (int s = 0; s < ns; ++s) count[s + 1] += count[s];
  out.start = count;
  out.d.resize(count[ns]);
  out.p.resize(count[ns]);
  walk([&](int t, int d, int p) {
    const std::int64_t at = count[t]++;
    out.d[at] = d;
    out.p[at] = p;
  });
  return out;
}

SupernodalSchedule subtree_schedule(const SupernodalSymbolic& S, const std::vector<double>& cost) {
  const int ns = S.nsuper;
  // Postorder: a subtree is [first[s], s]; its cost accumulates upwards.
  std::vector<int> first(ns), child_head(ns, -1), sibling(ns, -1);
  std::vector<double> total(cost.begin(), cost.end());
  double all = 0;
  for (int s = 0; s < ns; ++s) first[s] = s;
  for (int s = 0; s < ns; ++s) {
    const int p = S.parent[s];
    if (p < 0) { all += total[s]; continue; }
    first[p] = std::min(first[p], first[s]);
    total[p] += total[s];
  }
  for (int s = ns - 1; s >= 0; --s)
    if (S.parent[s] >= 0) { sibling[s] = child_head[S.parent[s]]; child_head[S.parent[s]] = s; }
  // Largest first; ties by supernode, so the split is a function of the tree.
  auto less = [&](int a, int b) { return total[a] != total[b] ? total[a] < total[b] : a < b; };
  std::priority_queue<int, std::vector<int>, decltype(less)> heap(less);
  for (int s = 0; s < ns; ++s)
    if (S.parent[s] < 0) heap.push(s);
  SupernodalSchedule out;
  std::vector<int> roots;
  const double limit = all / 16;
  while (!heap.empty()) {
    const int s = heap.top();
    heap.pop();
    if (total[s] <= limit || child_head[s] < 0 || out.top.size() >= 4096) {
      roots.push_back(s);
      continue;
    }
    out.top.push_back(s);
    for (int c = child_head[s]; c >= 0; c = sibling[c]) heap.push(c);
  }
  std::sort(roots.begin(), roots.end(), [&](int a, int b) { return less(b, a); });
  for (int r : roots) out.subtrees.emplace_back(first[r], r);
  std::sort(out.top.begin(), out.top.end());
  return out;
}

}  // namespace intrinsic::detail

#endif
