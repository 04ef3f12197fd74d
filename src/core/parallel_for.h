// Splits an index range over the machine's cores (at most 2 here; more where
// there are more), for loops whose iterations write disjoint outputs. Small
// ranges run inline: a thread costs tens of microseconds.
#pragma once

#include <algorithm>
#include <cstdint>
#include <thread>
#include <vector>

namespace intrinsic::detail {

// Calls fn(begin, end) on disjoint pieces covering [0, n). The pieces are the
// same for the same n and core count, so results do not depend on timing.
template <class Fn>
void parallel_for(std::int64_t n, Fn&& fn, std::int64_t min_per_thread = 50000) {
  const std::int64_t cores = std::max(1u, std::thread::hardware_concurrency());
  const std::int64_t parts = std::clamp<std::int64_t>(n / std::max<std::int64_t>(min_per_thread, 1), 1, std::min<std::int64_t>(cores, 8));
  if (parts <= 1) {
    fn(std::int64_t{0}, n);
    return;
  }
  std::vector<std::thread> threads;
  for (std::int64_t p = 1; p < parts; ++p) threads.emplace_back([&fn, n, p, parts] { fn(n * p / parts, n * (p + 1) / parts); });
  fn(std::int64_t{0}, n / parts);
  for (std::thread& t : threads) t.join();
}

}  // namespace intrinsic::detail
