// What every fuzz target shares: intrinsic::Error is the one expected way to
// refuse an input; anything else escaping (another exception type, a crash, a
// sanitizer report, a leak, a timeout) is a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "intrinsic/mesh.h"

namespace intrinsic::fuzz {

// Small caps keep each execution fast and the inflate limit low (a few MB).
inline ReadOptions small_limits() {
  ReadOptions o;
  o.max_vertices = 2000;
  o.max_faces = 4000;
  return o;
}

// A bumped 5 x 5 vertex grid (vertex y * 5 + x; two faces per quad, row by
// row), optionally without its quad at (1, 1) so paths can leave the surface
// through that hole too (30 faces; fuzz/make_corpus.py assumes that count).
inline Mesh bumped_grid(bool with_hole) {
  MatrixX3d V(25, 3);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x) V.row(y * 5 + x) << x, y, 0.3 * ((x * y) % 3);
  MatrixX3i F(with_hole ? 30 : 32, 3);
  int f = 0;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      if (with_hole && x == 1 && y == 1) continue;
      const int a = y * 5 + x;
      F.row(f++) << a, a + 1, a + 6;
      F.row(f++) << a, a + 6, a + 5;
    }
  return make_mesh(V, F);
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
