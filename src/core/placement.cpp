// Output placement (docs/maths.md §2.4): one similarity per rule.
#include "core/placement.h"

#include <cmath>

#include "intrinsic/parameterize.h"

namespace intrinsic::detail {

Similarity placement(PlacementRule rule, const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV,
                     const std::vector<char>& used) {
  Similarity s;
  switch (rule) {
    case PlacementRule::AsSolved: return s;
    case PlacementRule::UnitBox:
      s.scale = 0.5;
      s.offset = Eigen::RowVector2d(0.5, 0.5);
      return s;
    case PlacementRule::FitUnitSquare: {
      Eigen::RowVector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
      for (int v = 0; v < UV.rows(); ++v)
        if (used[v]) {
          lo = lo.cwiseMin(UV.row(v));
          hi = hi.cwiseMax(UV.row(v));
        }
      const double extent = (hi - lo).maxCoeff();
      if (!(extent > 0) || !std::isfinite(extent)) return s;
      s.scale = 1.0 / extent;
      s.offset = Eigen::RowVector2d(0.5, 0.5) - 0.5 * (lo + hi) / extent;
      return s;
    }
    case PlacementRule::SurfaceArea: {
      // About the origin, so that maps sharing a fixed boundary still share it.
      const double a_param = std::abs(parameter_area(F, UV));
      if (a_param > 0) s.scale = std::sqrt(surface_area(V, F) / a_param);
      return s;
    }
  }
  return s;
}

void apply(const Similarity& s, MatrixX2d& UV, const std::vector<char>& used) {
  if (s.scale == 1 && s.offset.isZero()) return;
  for (int v = 0; v < UV.rows(); ++v)
    if (used[v]) UV.row(v) = s.scale * UV.row(v) + s.offset;
}

}  // namespace intrinsic::detail
