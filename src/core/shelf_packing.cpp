// Shelf packing of bounding boxes (see shelf_packing.h).
#include "core/shelf_packing.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace intrinsic::detail {

std::vector<Eigen::Vector2d> pack_shelves(const std::vector<Eigen::Vector2d>& sizes, const Eigen::Vector2d& origin,
                                          double gap) {
  double area = 0, widest = 0;
  for (const Eigen::Vector2d& s : sizes) {
    area += s.x() * s.y();
    widest = std::max(widest, s.x());
  }
  const double row_width = std::max(widest, std::sqrt(area) * 1.2);
  std::vector<int> order(sizes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return sizes[a].y() > sizes[b].y(); });
  std::vector<Eigen::Vector2d> corner(sizes.size());
  double x = 0, y = 0, shelf = 0;
  for (int c : order) {
    if (x > 0 && x + sizes[c].x() > row_width) {
      y += shelf + gap;
      x = 0;
      shelf = 0;
    }
    corner[c] = origin + Eigen::Vector2d(x, y);
    x += sizes[c].x() + gap;
    shelf = std::max(shelf, sizes[c].y());
  }
  return corner;
}

}  // namespace intrinsic::detail
