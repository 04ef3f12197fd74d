// Milliseconds since a steady-clock time point: the figures of every
// report's "timings_ms".
#pragma once

#include <chrono>

namespace intrinsic::detail {

inline double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace intrinsic::detail
