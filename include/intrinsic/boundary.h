// Fixed boundary positions (paper section 4.1; docs/maths.md §2.2): the outer
// loop mapped to a circle or a square, spaced by 3D arc length or uniformly,
// or positions the user gives for any vertices (outer loop, holes'
// "additional boundary vertices", even interior points). BoundaryShape::Natural
// fixes no loop at all: the natural conformal map (paper section 4.2, eq. 7)
// finds the boundary itself, with two pinned vertices.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "intrinsic/choice.h"
#include "intrinsic/mesh.h"

namespace intrinsic {

enum class BoundaryShape { Circle, Square, Given, Natural };
template <>
ChoiceTable<BoundaryShape> choice_table<BoundaryShape>();
enum class Spacing { ArcLength, Uniform };
template <>
ChoiceTable<Spacing> choice_table<Spacing>();

std::string boundary_shape_name(BoundaryShape s);  // "circle", "square", "given", "natural"
std::string spacing_name(Spacing s);               // "arclength", "uniform"

struct FixedVertex {
  int vertex;
  Eigen::Vector2d uv;
};

// Parameter t in [0, 1) of each loop vertex, by 3D arc length or uniformly.
std::vector<double> loop_parameters(const MatrixX3d& V, const std::vector<int>& loop, Spacing spacing);

// The loop on the unit circle (centre 0, radius 1), counter-clockwise, so the
// faces keep their orientation.
std::vector<FixedVertex> circle_boundary(const MatrixX3d& V, const std::vector<int>& loop, Spacing spacing);
// The loop on the square [-1, 1]^2, counter-clockwise; the corners are the four
// loop vertices whose parameter is nearest 0, 1/4, 1/2 and 3/4, and each side's
// vertices are spaced between its corners. Needs at least 4 vertices.
std::vector<FixedVertex> square_boundary(const MatrixX3d& V, const std::vector<int>& loop, Spacing spacing);


}  // namespace intrinsic
