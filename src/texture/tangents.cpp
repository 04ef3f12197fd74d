// Per-corner tangent frames for normal mapping, in the manner of MikkTSpace
// (Mikkelsen 2008, the glTF reference for TANGENT): corners sharing
// position, normal and uv are one vertex; each face's tangent and bitangent
// come from its uv gradients (dp/du, dp/dv); each corner accumulates them
// projected onto its tangent plane, normalized, weighted by the corner's
// angle; faces of opposite uv orientation (mirrored charts) and faces with
// degenerate uv are not averaged together. Handedness w says whether the
// bitangent is +cross(n, t) or -cross(n, t) (docs/maths.md "Texture transfer").
#include <Eigen/Geometry>
#include <cmath>
#include <algorithm>
#include <array>
#include <map>

#include "intrinsic/error.h"
#include "intrinsic/texture.h"

namespace intrinsic {
namespace {

struct Accum {
  Eigen::Vector3d t = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
  bool used = false;
};

// One welded vertex id per corner: equal position, normal and uv.
std::vector<int> weld_corners(const Eigen::MatrixX3d& p, const Eigen::MatrixX3d& n, const Eigen::MatrixX2d& uv) {
  std::map<std::array<double, 8>, int> ids;
  std::vector<int> out(p.rows());
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    std::array<double, 8> key{p(i, 0), p(i, 1), p(i, 2), n(i, 0), n(i, 1), n(i, 2), uv(i, 0), uv(i, 1)};
    for (double& k : key) k += 0.0;  // -0 and +0 are one value
    out[i] = ids.emplace(key, static_cast<int>(ids.size())).first->second;
  }
  return out;
}

void check_inputs(const Eigen::MatrixX3d& p, const Eigen::MatrixX3d& n, const Eigen::MatrixX2d& uv) {
  if (p.rows() % 3 != 0 || n.rows() != p.rows() || uv.rows() != p.rows())
    throw_usage("compute_tangents: position, normal and uv need the same number of rows, 3 per face");
  for (Eigen::Index i = 0; i < p.rows(); ++i)
    if (!p.row(i).allFinite() || !n.row(i).allFinite() || !uv.row(i).allFinite())
      throw_input("compute_tangents: corner " + std::to_string(i % 3) + " of face " + std::to_string(i / 3) +
                  " has a non-finite position, normal or uv");
}

Eigen::Vector3d unit_normal(const Eigen::MatrixX3d& n, Eigen::Index i) {
  const Eigen::Vector3d v = n.row(i).transpose();
  return v.norm() > 0 ? Eigen::Vector3d(v.normalized()) : Eigen::Vector3d(0, 0, 1);
}

// The component of v in the plane normal to n, normalized (zero if none).
Eigen::Vector3d in_plane(const Eigen::Vector3d& v, const Eigen::Vector3d& n) {
  const Eigen::Vector3d r = v - n * n.dot(v);
  const double len = r.norm();
  return len > 1e-300 ? Eigen::Vector3d(r / len) : Eigen::Vector3d::Zero();
}

}  // namespace

Eigen::MatrixX4d compute_tangents(const Eigen::MatrixX3d& position, const Eigen::MatrixX3d& normal,
                                  const Eigen::MatrixX2d& uv) {
  check_inputs(position, normal, uv);
  const std::vector<int> vid = weld_corners(position, normal, uv);
  const Eigen::Index faces = position.rows() / 3;
  // Two accumulators per welded vertex: one per uv orientation.
  std::vector<Accum> acc(2 * (vid.empty() ? 0 : *std::max_element(vid.begin(), vid.end()) + 1));
  std::vector<int> side(faces, -1);  // 0: det > 0, 1: det < 0, -1: degenerate uv
  for (Eigen::Index f = 0; f < faces; ++f) {
    const Eigen::Vector3d p0 = position.row(3 * f).transpose();
    const Eigen::Vector3d e1 = position.row(3 * f + 1).transpose() - p0, e2 = position.row(3 * f + 2).transpose() - p0;
    const double du1 = uv(3 * f + 1, 0) - uv(3 * f, 0), dv1 = uv(3 * f + 1, 1) - uv(3 * f, 1);
    const double du2 = uv(3 * f + 2, 0) - uv(3 * f, 0), dv2 = uv(3 * f + 2, 1) - uv(3 * f, 1);
    const double det = du1 * dv2 - du2 * dv1;
    const double scale = std::max({std::abs(du1), std::abs(dv1), std::abs(du2), std::abs(dv2)});
    if (!(std::abs(det) > 1e-12 * scale * scale)) continue;
    side[f] = det > 0 ? 0 : 1;
    const Eigen::Vector3d t = (e1 * dv2 - e2 * dv1) / det, b = (e2 * du1 - e1 * du2) / det;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Index i = 3 * f + k;
      const Eigen::Vector3d a = position.row(3 * f + (k + 1) % 3) - position.row(i);
      const Eigen::Vector3d c = position.row(3 * f + (k + 2) % 3) - position.row(i);
      const double angle = std::atan2(a.cross(c).norm(), a.dot(c));
      const Eigen::Vector3d n = unit_normal(normal, i);
      Accum& s = acc[2 * vid[i] + side[f]];
      s.t += angle * in_plane(t, n);
      s.b += angle * in_plane(b, n);
      s.used = true;
    }
  }
  Eigen::MatrixX4d out(position.rows(), 4);
  for (Eigen::Index i = 0; i < position.rows(); ++i) {
    const Eigen::Vector3d n = unit_normal(normal, i);
    const int f_side = side[i / 3];
    // A corner of a face with degenerate uv borrows its vertex's frame.
    const Accum* s = nullptr;
    if (f_side >= 0) s = &acc[2 * vid[i] + f_side];
    else if (acc[2 * vid[i]].used) s = &acc[2 * vid[i]];
    else if (acc[2 * vid[i] + 1].used) s = &acc[2 * vid[i] + 1];
    Eigen::Vector3d t = s ? in_plane(s->t, n) : Eigen::Vector3d::Zero();
    double w = 1;
    if (t.squaredNorm() == 0) t = n.unitOrthogonal();  // no uv gradient here: any frame
    else w = n.cross(t).dot(s->b) < 0 ? -1 : 1;
    out.row(i) << t.x(), t.y(), t.z(), w;
  }
  return out;
}

}  // namespace intrinsic
