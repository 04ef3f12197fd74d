// Point and line constraints (paper section 4.1; docs/maths.md §5): surface
// points mapped to chosen texture positions. A point is a vertex or a face with
// barycentric coordinates; a line is a polyline of surface points mapped to a
// segment or polyline in the plane, constrained at its points and at every
// crossing with a mesh edge (the paper's "end points as well as the
// intersections of the line with the edges of the mesh").
//
// Every constraint becomes linear rows "sum_k w_k u_{v_k} = target" (one per
// coordinate, same weights for u and v). Parameterizer adds them to the system
// with Lagrange multipliers.
#pragma once

#include <string>
#include <vector>

#include "intrinsic/mesh.h"

namespace intrinsic {

// A point on the surface: vertex >= 0, or face >= 0 with barycentric
// coordinates over the face's corners F(face, 0..2).
struct SurfacePoint {
  int vertex = -1;
  int face = -1;
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
  static SurfacePoint at_vertex(int v) { SurfacePoint p; p.vertex = v; return p; }
  static SurfacePoint in_face(int f, const Eigen::Vector3d& b) { SurfacePoint p; p.face = f; p.bary = b; return p; }
};

struct PointConstraint {
  SurfacePoint point;
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  std::string label;  // for messages and the report; "points[i]" when empty
};

// `to` has 2 positions (the whole path goes onto that segment, by 3D arc
// length) or as many as `path` (path point i goes to to[i]; the crossings
// between them are spread by arc length within their piece).
struct LineConstraint {
  std::vector<SurfacePoint> path;
  std::vector<Eigen::Vector2d> to;
  std::string label;  // "lines[i]" when empty
};

struct Constraints {
  std::vector<PointConstraint> points;
  std::vector<LineConstraint> lines;
  bool empty() const { return points.empty() && lines.empty(); }
};

// One resolved row pair: sum over terms of weight * uv(vertex) = target.
struct LinearConstraint {
  std::vector<std::pair<int, double>> terms;  // vertex, weight; weights sum to 1
  Eigen::Vector2d target;
  Eigen::Vector3d position;  // the constrained point in 3D, for line spacing and the report
  std::string label;         // "points[2]", "lines[0] point 1", "lines[0] crossing 3 (edge 10-11)"
};

// How well a solution meets one constraint (for reports): value is
// sum_k w_k uv(v_k), residual the Euclidean distance to the target.
struct ConstraintResidual {
  std::string label;
  Eigen::Vector2d target, value;
  double residual = 0;
};

// Tolerance on barycentric coordinates: they must sum to 1 within it and none
// may be below -tolerance.
constexpr double kBaryTolerance = 1e-9;

// Checks every point and turns lines into their rows (walking across the faces
// between consecutive path points, see resolve_constraints.cpp). Identical
// rows with equal targets are merged; the same point with two different
// targets is refused. Throws Error(Input) naming the constraint: face or
// vertex out of range, unused vertex, barycentrics not summing to 1 or
// negative, non-finite values, a line whose path cannot be walked.
std::vector<LinearConstraint> resolve_constraints(const Mesh& mesh, const Constraints& constraints);


// Barycentric coordinates refer to the corners of the faces as the file lists
// them; validation may have reoriented faces. Permutes each face point's
// coordinates from `file_faces` corner order to `mesh.F` order.
void match_face_corners(Constraints& constraints, const MatrixX3i& file_faces, const Mesh& mesh);

}  // namespace intrinsic
