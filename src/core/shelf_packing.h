// Side-by-side layout of chart bounding boxes (parameterize_charts): shelves
// filled left to right, tallest first. Deterministic.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace intrinsic::detail {

// Lower-left corners for boxes of the given sizes: tallest first, left to
// right from `origin`, a new shelf when a row would exceed about 1.2 x the
// square root of the total area (or the widest box), `gap` between boxes
// and shelves. Stable: equal heights keep their order.
std::vector<Eigen::Vector2d> pack_shelves(const std::vector<Eigen::Vector2d>& sizes, const Eigen::Vector2d& origin,
                                          double gap);

}  // namespace intrinsic::detail
