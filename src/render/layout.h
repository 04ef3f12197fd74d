// The flattened-mesh pass: triangles drawn at their UV positions, with
// interior edges, boundary edges, and flipped triangles highlighted.
#pragma once

#include <vector>

#include "intrinsic/mesh.h"
#include "render/image.h"

namespace intrinsic::render {

inline constexpr Rgb kLayoutFill = {205, 218, 238};
inline constexpr Rgb kFlippedRed = {220, 30, 30};
// Fraction of each image side left empty around the UV bounding box.
inline constexpr double kLayoutMargin = 0.04;

// With face_colours, faces take those colours and flipped ones are not
// singled out (the caller's values say what matters); otherwise light fill
// and red flips.
Image draw_layout(const MatrixX3i& F, const MatrixX2d& UV, const std::vector<Rgb>* face_colours, int width,
                  int height, int supersample);

}  // namespace intrinsic::render
