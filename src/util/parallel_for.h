// The project's one threading idiom: split an index range over the machine's
// cores (at most 8), for loops whose pieces write disjoint outputs. Small
// ranges run inline: a thread costs tens of microseconds. The pieces are the
// same for the same n and core count, so results never depend on timing.
// Used by mesh/, weights/, metrics/ and render/; depends on nothing else in
// the project.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

namespace intrinsic::detail {

// The machine's cores, asked once: glibc answers hardware_concurrency by
// reading /sys/devices/system/cpu/online, and the atlas asks once per chart
// solve (thousands of opens on a small asset, 5% of an atlas's time).
inline int machine_cores() {
  static const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return cores;
}

// The threads to use instead of the cores (0: the cores; at most 8 either
// way). For tests that check a result does not depend on the threads.
inline std::atomic<int>& thread_limit() {
  static std::atomic<int> limit{0};
  return limit;
}

// How many pieces parallel_for cuts [0, n) into.
inline int parallel_parts(std::int64_t n, std::int64_t min_per_thread = 50000) {
  const int limit = thread_limit().load(std::memory_order_relaxed);
  const std::int64_t cores = limit > 0 ? limit : machine_cores();
  return static_cast<int>(
      std::clamp<std::int64_t>(n / std::max<std::int64_t>(min_per_thread, 1), 1, std::min<std::int64_t>(cores, 8)));
}

// Calls fn(part, begin, end) for part = 0 .. parts-1 on disjoint pieces
// covering [0, n), part 0 on the calling thread. For loops that accumulate
// into one buffer per part (see assemble.cpp).
template <class Fn>
void parallel_for_parts(std::int64_t n, int parts, Fn&& fn) {
  if (parts <= 1) {
    fn(0, std::int64_t{0}, n);
    return;
  }
  std::vector<std::thread> threads;
  for (int p = 1; p < parts; ++p)
    threads.emplace_back([&fn, n, p, parts] { fn(p, n * p / parts, n * (p + 1) / parts); });
  fn(0, std::int64_t{0}, n / parts);
  for (std::thread& t : threads) t.join();
}

// Calls fn(begin, end) on disjoint pieces covering [0, n).
template <class Fn>
void parallel_for(std::int64_t n, Fn&& fn, std::int64_t min_per_thread = 50000) {
  parallel_for_parts(n, parallel_parts(n, min_per_thread),
                     [&fn](int, std::int64_t begin, std::int64_t end) { fn(begin, end); });
}

}  // namespace intrinsic::detail
