// Circle and square boundaries for the outer loop (paper section 4.1).
#include <cmath>

#include "intrinsic/boundary.h"
#include "intrinsic/error.h"
#include "intrinsic/choice.h"

namespace intrinsic {

std::string boundary_shape_name(BoundaryShape s) { return choice_name(s); }

std::string spacing_name(Spacing s) { return choice_name(s); }

std::vector<double> loop_parameters(const MatrixX3d& V, const std::vector<int>& loop, Spacing spacing) {
  const size_t n = loop.size();
  std::vector<double> t(n, 0.0);
  if (spacing == Spacing::Uniform || n == 0) {
    for (size_t k = 0; k < n; ++k) t[k] = static_cast<double>(k) / static_cast<double>(n);
    return t;
  }
  double total = 0;
  for (size_t k = 0; k < n; ++k) {
    t[k] = total;
    total += (V.row(loop[(k + 1) % n]) - V.row(loop[k])).norm();
  }
  if (!(total > 0)) throw_input("the boundary loop has zero length (all its vertices coincide)");
  for (double& x : t) x /= total;
  return t;
}

std::vector<FixedVertex> circle_boundary(const MatrixX3d& V, const std::vector<int>& loop, Spacing spacing) {
  if (loop.size() < 3) throw_input("the boundary loop has fewer than 3 vertices");
  const std::vector<double> t = loop_parameters(V, loop, spacing);
  std::vector<FixedVertex> out(loop.size());
  for (size_t k = 0; k < loop.size(); ++k) {
    const double a = 2 * M_PI * t[k];
    out[k] = {loop[k], Eigen::Vector2d(std::cos(a), std::sin(a))};
  }
  return out;
}

namespace {

// Point at perimeter parameter s in [0, 4) on the square [-1,1]^2, going
// counter-clockwise from the corner (-1, -1).
Eigen::Vector2d square_point(double s) {
  const int side = std::min(3, static_cast<int>(std::floor(s)));
  const double f = 2 * (s - side) - 1;  // -1 .. 1 along the side
  switch (side) {
    case 0: return {f, -1};
    case 1: return {1, f};
    case 2: return {-f, 1};
    default: return {-1, -f};
  }
}

}  // namespace

std::vector<FixedVertex> square_boundary(const MatrixX3d& V, const std::vector<int>& loop, Spacing spacing) {
  const size_t n = loop.size();
  if (n < 4) throw_input("a square boundary needs at least 4 boundary vertices; the loop has " + std::to_string(n));
  const std::vector<double> t = loop_parameters(V, loop, spacing);
  // Corner c is the vertex whose parameter is nearest c/4, kept strictly increasing.
  size_t corner[5];
  corner[0] = 0;
  for (int c = 1; c < 4; ++c) {
    size_t best = corner[c - 1] + 1;
    for (size_t k = best; k + (4 - c) <= n; ++k)
      if (std::abs(t[k] - c / 4.0) < std::abs(t[best] - c / 4.0)) best = k;
    corner[c] = best;
  }
  corner[4] = n;
  std::vector<FixedVertex> out(n);
  for (int c = 0; c < 4; ++c) {
    const double t0 = t[corner[c]];
    const double t1 = c == 3 ? 1.0 : t[corner[c + 1]];
    for (size_t k = corner[c]; k < corner[c + 1]; ++k) {
      const double f = (t[k] - t0) / (t1 - t0);
      out[k] = {loop[k], square_point(c + f)};
    }
  }
  return out;
}

// How the command line, Python and the reports spell these (intrinsic/choice.h).
// Given positions come from a file the command line names by its path.
template <>
ChoiceTable<BoundaryShape> choice_table<BoundaryShape>() {
  static const Choice<BoundaryShape> rows[] = {{BoundaryShape::Circle, "circle"},
                                               {BoundaryShape::Square, "square"},
                                               {BoundaryShape::Natural, "natural"},
                                               {BoundaryShape::Given, "given", false}};
  return make_choice_table(rows);
}

template <>
ChoiceTable<Spacing> choice_table<Spacing>() {
  static const Choice<Spacing> rows[] = {{Spacing::ArcLength, "arclength"}, {Spacing::Uniform, "uniform"}};
  return make_choice_table(rows);
}

}  // namespace intrinsic
