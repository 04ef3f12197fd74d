// The validated surface every algorithm takes: positions, consistently
// oriented triangles and their adjacency (topology.h), built from raw file
// data (mesh_data.h) by make_mesh, which refuses what the maps cannot take.
#pragma once

#include <string>
#include <vector>

#include "intrinsic/mesh_data.h"
#include "intrinsic/topology.h"

namespace intrinsic {

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
