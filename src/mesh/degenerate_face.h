// make_mesh's zero-area test, for the code that counts degenerate faces of a
// mesh it did not validate (the UV metrics): twice the area against the
// longest edge squared, so the test does not depend on the mesh's scale.
#pragma once

#include <algorithm>

#include "intrinsic/mesh_data.h"

namespace intrinsic::detail {

inline bool degenerate_face(const MatrixX3d& V, const MatrixX3i& F, int f, double ratio = 1e-12) {
  const Eigen::Vector3d x0 = V.row(F(f, 0)), x1 = V.row(F(f, 1)), x2 = V.row(F(f, 2));
  const double longest = std::max({(x1 - x0).squaredNorm(), (x2 - x1).squaredNorm(), (x0 - x2).squaredNorm()});
  return !((x1 - x0).cross(x2 - x0).norm() > ratio * longest);
}

}  // namespace intrinsic::detail
