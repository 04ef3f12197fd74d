// Temporary fans that close holes for the solve (docs/maths.md §4.1).
#include "core/hole_fill.h"

#include <algorithm>

namespace intrinsic::detail {
namespace {

// The fan of one loop around centre c (vertex index `centre`): faces opposite
// to the boundary half-edges. False when a fan triangle is degenerate.
bool fan_of(const MatrixX3d& V, const std::vector<int>& loop, const Eigen::Vector3d& c, int centre,
            std::vector<Eigen::Vector3i>& faces) {
  for (size_t i = 0; i < loop.size(); ++i) {
    const int a = loop[i], b = loop[(i + 1) % loop.size()];
    const Eigen::Vector3d xa = V.row(a), xb = V.row(b);
    const double twice = (xa - xb).cross(c - xb).norm();
    if (!(twice > 1e-12 * std::max((xa - xb).squaredNorm(), (c - xb).squaredNorm()))) return false;
    faces.emplace_back(b, a, centre);  // opposite to the boundary half-edge a->b
  }
  return true;
}

}  // namespace

FilledSurface fill_holes(const Mesh& mesh, const std::vector<char>& is_fixed) {
  const Topology& t = mesh.topology;
  const int n = static_cast<int>(mesh.V.rows());
  std::vector<Eigen::Vector3i> fan;
  std::vector<Eigen::Vector3d> centres;
  for (size_t k = 1; k < t.component_loops[0].size(); ++k) {
    const std::vector<int>& loop = t.boundary_loops[t.component_loops[0][k]];
    if (std::all_of(loop.begin(), loop.end(), [&](int v) { return is_fixed[v] != 0; })) continue;  // the user placed it
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int v : loop) c += mesh.V.row(v).transpose();
    c /= static_cast<double>(loop.size());
    std::vector<Eigen::Vector3i> faces;
    if (!fan_of(mesh.V, loop, c, n + static_cast<int>(centres.size()), faces)) continue;  // stays free
    centres.push_back(c);
    fan.insert(fan.end(), faces.begin(), faces.end());
  }
  FilledSurface s{mesh.V, mesh.F, static_cast<int>(centres.size())};
  if (centres.empty()) return s;
  s.V.conservativeResize(n + s.filled, 3);
  for (int k = 0; k < s.filled; ++k) s.V.row(n + k) = centres[k].transpose();
  const int m = static_cast<int>(s.F.rows());
  s.F.conservativeResize(m + static_cast<int>(fan.size()), 3);
  for (size_t k = 0; k < fan.size(); ++k) s.F.row(m + static_cast<int>(k)) = fan[k].transpose();
  return s;
}

}  // namespace intrinsic::detail
