// After a failed solve: what cheap checks can tell about why, appended to
// the Error(Numerical) message (docs/formats.md "Exit codes").
#pragma once

#include <string>
#include <vector>

#include "intrinsic/boundary.h"
#include "intrinsic/weights.h"

namespace intrinsic::detail {

// "; likely cause: ..." or "" when nothing is found. Checks, on the mesh
// itself (holes left open): free vertices that nonzero weights do not tie to
// any of `fixed` (a singular system), non-finite weights, and nearly
// degenerate faces (an ill-conditioned one).
std::string likely_cause(const Mesh& mesh, const WeightOptions& weights, const std::vector<FixedVertex>& fixed);

}  // namespace intrinsic::detail
