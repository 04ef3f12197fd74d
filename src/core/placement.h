// Where a solved map goes in output coordinates (docs/cli.md "--scale",
// docs/maths.md §2.4): the one function every caller places a map with.
#pragma once

#include <vector>

#include "intrinsic/mesh.h"

namespace intrinsic::detail {

enum class PlacementRule {
  AsSolved,       // given positions, the user's pins: kept exactly
  UnitBox,        // circle and square live in [-1,1]^2: that box onto [0,1]^2 exactly
  FitUnitSquare,  // bounding box of the used vertices onto [0,1]^2, centred, aspect kept
  SurfaceArea,    // scaled about the origin so that |parameter area| = 3D area
};

// uv -> scale * uv + offset.
struct Similarity {
  double scale = 1;
  Eigen::RowVector2d offset = Eigen::RowVector2d::Zero();
};

// The similarity of `rule` for the map UV of the faces F of positions V
// (only used vertices count). Identity when the map is degenerate (zero
// extent or area).
Similarity placement(PlacementRule rule, const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV,
                     const std::vector<char>& used);

// Applies s to the rows of UV of used vertices.
void apply(const Similarity& s, MatrixX2d& UV, const std::vector<char>& used);

}  // namespace intrinsic::detail
