// Packing, step 1: how a chart is turned before it is rasterized. Every
// chart is first turned to its smallest bounding box (a side of that box lies
// on a convex hull edge), which for most charts is also the pose that wastes
// least of a square. Charts whose hull fills that box poorly (an L, a
// crescent) get a few more angles to try: one of them may let the chart wrap
// another or sit in a corner. Only rotations: a mirrored chart would flip its
// triangles' orientation.
#pragma once

#include <vector>

#include "atlas/atlas_internal.h"

namespace intrinsic::detail::packing {

// Andrew's monotone chain: the convex hull, counter-clockwise, no repeated point.
std::vector<Eigen::Vector2d> convex_hull(const MatrixX2d& UV);

// The angle that turns UV to its smallest axis-aligned box; `box_area` gets that box's area.
double smallest_box_angle(const MatrixX2d& UV, double& box_area);

// UV turned by `angle` (radians, counter-clockwise), its box's lower corner
// moved to the origin. The same arithmetic for rasterizing and for the
// output, so the output lies exactly on the rasterized texels.
MatrixX2d turned_to(const MatrixX2d& UV, double angle);

// Turns the chart to its smallest box and moves its corner to the origin.
void orient_chart(FlatChart& chart);

// The angles (radians, added to the smallest-box pose) at which the chart is
// rasterized, 0 first; each is then tried in its four quarter turns. Only
// charts that are at least `min_share` of the atlas's area and whose hull
// fills at most `max_fill` of their box get more than 0: tiny charts gain
// nothing from finer angles, and each angle costs a rasterization.
struct PoseOptions {
  double min_share = 0.005;
  double max_fill = 0.75;
  int extra_angles = 3;  // evenly between 0 and 90 degrees (3: 22.5, 45, 67.5)
  // At most this many charts get them, the largest: they decide the
  // layout's square, and each pose costs a search per placement.
  int max_charts = 12;
};
std::vector<double> pose_angles(const FlatChart& chart, double atlas_area, const PoseOptions& options);
// pose_angles for every chart, extra angles only for the max_charts largest that qualify.
std::vector<std::vector<double>> all_pose_angles(const std::vector<FlatChart>& charts, double atlas_area,
                                                 const PoseOptions& options);

}  // namespace intrinsic::detail::packing
