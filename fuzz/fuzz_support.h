// What every fuzz target shares: intrinsic::Error is the one expected way to
// refuse an input; anything else escaping (another exception type, a crash, a
// sanitizer report, a leak, a timeout) is a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "intrinsic/error.h"
#include "intrinsic/io.h"

namespace intrinsic::fuzz {

// Small caps keep each execution fast and the inflate limit low (a few MB).
inline ReadOptions small_limits() {
  ReadOptions o;
  o.max_vertices = 2000;
  o.max_faces = 4000;
  return o;
}

// Runs `body`; Error is expected, every other exception aborts (a finding).
template <class Body>
int expect_only_error(Body&& body) {
  try {
    body();
  } catch (const Error&) {
  }
  return 0;
}

}  // namespace intrinsic::fuzz
