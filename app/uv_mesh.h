// Meshes that come with their own UVs (OBJ vt, PLY u,v). A vertex may carry
// several texture coordinates (a seam), so per-face work re-indexes the faces
// by texture coordinate, copying each position once per coordinate. Shared by
// `metrics` and `render`.
#pragma once

#include <string>

#include "intrinsic/mesh.h"

namespace intrinsic::app {

struct UvMesh {
  MatrixX3d V;   // #TC x 3: the position of each texture coordinate's corners
  MatrixX3i F;   // the input's FTC
  MatrixX2d UV;  // the input's TC, one row per row of V
  Eigen::Index input_vertices = 0;  // rows of V in the file, for reports
};

// Throws Error(Input) naming the file when it has no texture coordinates, a
// texture index is out of range, or one coordinate is used by corners at
// different positions.
UvMesh split_by_texcoord(const MeshData& data);

}  // namespace intrinsic::app
