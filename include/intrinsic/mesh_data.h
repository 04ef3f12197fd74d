// Plain mesh data as read from a file: libigl-style Eigen matrices.
// V is #V x 3 positions, F is #F x 3 zero-based vertex indices (polygons
// already fan-triangulated). Optional texture coordinates TC (#TC x 2) with
// per-corner indices FTC (#F x 3), as OBJ stores them; for PLY u,v vertex
// properties FTC equals F.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products, 2x2 inverses
#include <memory>
#include <string>
#include <vector>

namespace intrinsic {

struct GltfDocument;  // src/io/gltf_document.h (intrinsic/gltf.h)

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
  // Set when the mesh was read from a .gltf/.glb: the whole document, so that
  // write_atlas_file can write the atlas back into it (intrinsic/gltf.h).
  std::shared_ptr<const GltfDocument> gltf;
  bool has_uv() const { return TC.rows() > 0 && FTC.rows() == F.rows(); }
};

}  // namespace intrinsic
