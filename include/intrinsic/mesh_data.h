// Plain mesh data as read from a file: libigl-style Eigen matrices.
// V is #V x 3 positions, F is #F x 3 zero-based vertex indices (polygons
// already fan-triangulated). Optional texture coordinates TC (#TC x 2) with
// per-corner indices FTC (#F x 3), as OBJ stores them; for PLY u,v vertex
// properties FTC equals F.
// Geometry only, with the file it came from for messages: what a file
// carries beyond it (an OBJ's normals and labels, a glTF document) is kept
// beside it, in a MeshFile (intrinsic/mesh_document.h, the io layer).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products, 2x2 inverses
#include <string>
#include <vector>

namespace intrinsic {

using Eigen::MatrixX2d;
using Eigen::MatrixX3d;
using Eigen::MatrixX3i;

struct MeshData {
  MatrixX3d V;
  MatrixX3i F;
  MatrixX2d TC;   // empty when the file has no texture coordinates
  MatrixX3i FTC;  // #F x 3 when TC is present, else empty
  // For error messages: the 1-based source line of each face in text formats
  // (several triangles share the line of their polygon), or 0 for binary files.
  std::vector<int> face_line;
  std::string path;  // the file it came from, for messages
  // The file had texture coordinates (OBJ vt lines, PLY u, v), whether or
  // not they were kept in TC (an OBJ's are dropped unless every face indexes
  // them): an atlas written from this mesh replaces them.
  bool had_texcoords = false;

  bool has_uv() const { return TC.rows() > 0 && FTC.rows() == F.rows(); }
};

}  // namespace intrinsic
