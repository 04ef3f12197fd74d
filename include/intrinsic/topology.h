// The adjacency of a validated surface (built once by make_mesh, never
// mutated; see mesh.h): half-edges, boundary loops, components.
//
// Half-edge h = 3*f + c runs from F(f,c) to F(f,(c+1)%3); the face lies on its
// left. twin[h] is the opposite half-edge, or -1 on the boundary. Boundary
// loops are listed in half-edge order, so the surface's interior lies to the
// left when walking a loop: mapping a loop counter-clockwise in the plane
// keeps the orientation of the faces.
#pragma once

#include <vector>

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

}  // namespace intrinsic
