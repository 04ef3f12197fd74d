// Tangent-space normal maps under a new layout: a map stores the normal in
// the frame (T, B, N) of its layout, and the new layout's frame differs (the
// chart may be rotated or mirrored in UV). The transfer decodes n = 2c - 1 in
// the old frame, forms the object-space vector n.x T + n.y B + n.z N, and
// re-expresses it in the new frame (docs/maths.md "Texture transfer").
// Frames follow glTF's TANGENT: bitangent = w * cross(normal, tangent).
#include <Eigen/Geometry>
#include <cmath>

#include "texture/texture_internal.h"

namespace intrinsic::detail {

Frame corner_frame(const Eigen::MatrixX3d& normal, const Eigen::MatrixX4d& tangent, int f, const double b[3]) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero(), t = Eigen::Vector3d::Zero();
  double w = 0;
  for (int k = 0; k < 3; ++k) {
    n += b[k] * normal.row(3 * f + k).transpose();
    t += b[k] * tangent.row(3 * f + k).head<3>().transpose();
    w += b[k] * tangent(3 * f + k, 3);
  }
  Frame fr;
  fr.n = n.normalized();
  Eigen::Vector3d tt = t - fr.n * fr.n.dot(t);
  if (!(tt.squaredNorm() > 1e-24)) {
    // A tangent along the normal (bad input): any perpendicular direction
    // keeps the frame orthonormal; both layouts see the same fallback.
    tt = fr.n.unitOrthogonal();
  }
  fr.t = tt.normalized();
  fr.b = (w < 0 ? -1.0 : 1.0) * fr.n.cross(fr.t);
  return fr;
}

std::array<float, 3> reexpress_normal(const std::array<float, 3>& rgb, const Frame& from, const Frame& to) {
  const Eigen::Vector3d ts(2.0 * rgb[0] - 1, 2.0 * rgb[1] - 1, 2.0 * rgb[2] - 1);
  const Eigen::Vector3d world = ts.x() * from.t + ts.y() * from.b + ts.z() * from.n;
  Eigen::Vector3d out(world.dot(to.t), world.dot(to.b), world.dot(to.n));
  const double len = out.norm();
  if (len > 1e-12) out /= len;
  else out = Eigen::Vector3d(0, 0, 1);  // a zero normal (black texel): flat
  return {static_cast<float>(0.5 * out.x() + 0.5), static_cast<float>(0.5 * out.y() + 0.5),
          static_cast<float>(0.5 * out.z() + 0.5)};
}

}  // namespace intrinsic::detail
