// Input validation and small mesh queries shared by the render modes, so
// every entry point rejects bad input with the same messages.
#pragma once

#include <array>
#include <vector>

#include "intrinsic/mesh.h"
#include "intrinsic/render.h"

namespace intrinsic::render {

// Error(Usage) for out-of-range sizes; Error(Input) for an unusable texture.
void check_options(const RenderOptions& o);
// Error(Input) if F is empty or indexes outside [0, num_vertices).
void check_faces(const MatrixX3i& F, Eigen::Index num_vertices, const char* what);
// Error(Input) if no face has all-finite coordinates in P (UV or V).
template <class Matrix>
void check_some_finite(const MatrixX3i& F, const Matrix& P, const char* what);

// Unique undirected edges, split by how many faces use them: one face means
// boundary; two or more (including non-manifold) means interior.
void collect_edges(const MatrixX3i& F, std::vector<std::array<int, 2>>& interior,
                   std::vector<std::array<int, 2>>& boundary);

// Affine map UV -> samples putting the finite UV bounding box in a
// width x height sample area with a margin, aspect kept, v pointing up.
struct UvFrame {
  double scale = 1, u0 = 0, v0 = 0, x0 = 0, y0 = 0;
  // Halving first keeps u - u0 finite for coordinates near the double limit.
  double x(double u) const { return x0 + (u / 2 - u0 / 2) * (2 * scale); }
  double y(double v) const { return y0 - (v / 2 - v0 / 2) * (2 * scale); }
};
UvFrame frame_uv(const MatrixX3i& F, const MatrixX2d& UV, int width, int height, double margin);

}  // namespace intrinsic::render
