// The validated surface: positions, consistently oriented triangles, and the
// compact adjacency every algorithm reuses (built once, never mutated).
//
// Half-edge h = 3*f + c runs from F(f,c) to F(f,(c+1)%3); the face lies on its
// left. twin[h] is the opposite half-edge, or -1 on the boundary. Boundary
// loops are listed in half-edge order, so the surface's interior lies to the
// left when walking a loop: mapping a loop counter-clockwise in the plane
// keeps the orientation of the faces.
#pragma once

#include <string>
#include <vector>

#include "intrinsic/mesh.h"

namespace intrinsic {

struct Topology {
  int num_vertices = 0;  // rows of V, used or not
  int num_faces = 0;
  std::vector<int> twin;            // per half-edge, -1 on the boundary
  std::vector<int> vertex_out;      // one outgoing half-edge per used vertex (boundary one if any), else -1
  std::vector<char> is_boundary;    // per vertex
  std::vector<char> is_used;        // per vertex: referenced by some face
  std::vector<std::vector<int>> boundary_loops;  // vertex indices; within each component the outer (longest 3D) loop first
  std::vector<double> loop_length;  // 3D length of each loop
  std::vector<int> face_component;  // per face
  int num_components = 0;
  std::vector<int> component_faces;        // face count per component
  std::vector<std::vector<int>> component_loops;  // loop indices per component, outer first

  static int face_of(int h) { return h / 3; }
  static int next(int h) { return h - h % 3 + (h % 3 + 1) % 3; }
  static int prev(int h) { return h - h % 3 + (h % 3 + 2) % 3; }
};

// What validation found and fixed, for the report.
struct ValidationReport {
  int reoriented_faces = 0;
  int unreferenced_vertices = 0;
};

struct Mesh {
  MatrixX3d V;
  MatrixX3i F;  // consistently oriented
  Topology topology;
  ValidationReport validation;
  std::vector<int> face_line;  // source line per face for messages (may be empty)
  std::string path;            // source file for messages (may be empty)

  int source(int h) const { return F(h / 3, h % 3); }
  int target(int h) const { return F(h / 3, (h % 3 + 1) % 3); }
  // "face 12 (mesh.obj line 40)" or "face 12": how messages name a face.
  std::string describe_face(int f) const;
};

struct ValidateOptions {
  // A triangle whose area is below this fraction of its longest edge squared
  // is refused as degenerate: its cotangents would be meaningless.
  double degenerate_ratio = 1e-12;
  // Several components and closed components are normally refused here;
  // chart-based callers allow them and handle each component themselves.
  bool allow_several_components = false;
  bool allow_closed = false;
};

// Validates and builds the adjacency. Throws Error(Input) naming the first
// offending element: out-of-range index, repeated vertex in a face,
// non-finite coordinate, degenerate face, edge with more than two faces,
// non-manifold vertex, non-orientable surface, closed surface, several
// components. Faces listed against the majority orientation of their
// component are flipped (counted in validation.reoriented_faces).
Mesh make_mesh(const MeshData& data, const ValidateOptions& options = {});
Mesh make_mesh(const MatrixX3d& V, const MatrixX3i& F, const ValidateOptions& options = {});

}  // namespace intrinsic
