// HoleRule::Fill (docs/maths.md §4.1): each hole that the caller did not
// place is closed, for the solve only, by a fan of triangles around the
// centroid of its loop.
#pragma once

#include <vector>

#include "intrinsic/mesh.h"

namespace intrinsic::detail {

struct FilledSurface {
  MatrixX3d V;  // the mesh's positions, then one centre per filled hole
  MatrixX3i F;  // the mesh's faces, then the fans
  int filled = 0;
};

// The holes of the first component (loops after the outer one) not entirely
// in `is_fixed`, each closed by a fan whose faces keep the surface's
// orientation. A hole whose fan would have a degenerate triangle (the
// centroid on a loop edge's line) stays open, i.e. free.
FilledSurface fill_holes(const Mesh& mesh, const std::vector<char>& is_fixed);

}  // namespace intrinsic::detail
