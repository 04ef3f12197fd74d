// Wall-clock milliseconds and medians, as every benchmark program here
// reports them (medians of several runs: the machine is shared and noisy).
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

namespace intrinsic::bench {

inline double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The middle value; the mean of the two middle ones for an even count.
inline double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  const size_t n = x.size();
  return n == 0 ? 0 : n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

}  // namespace intrinsic::bench
