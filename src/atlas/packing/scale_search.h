// Packing, step 5: the scale. All charts share one scale (texels per unit of
// surface: equal texel density), and the layout is finally stretched to fill
// [0,1]^2, so the figure to maximize is scale / extent (the utilization is
// the charts' area times its square). Packing is not monotone in the scale,
// but nearly: the search brackets the largest scale at which every chart
// fits, bisects it, and keeps the best scale / extent of every layout found.
#pragma once

#include <vector>

#include "atlas/packing/placement.h"

namespace intrinsic::detail::packing {

// A chart as the packer sees it: its triangles and its UV in each pose
// angle (chart_pose.h: turned_to, corner at the origin).
struct PackChart {
  const MatrixX3i* F = nullptr;
  std::vector<MatrixX2d> poses;
};

struct Layout {
  double scale = 0;  // texels per unit of surface
  int extent = 0;    // side of the square the layout needs, texels
  std::vector<Placement> at;  // per chart, on the layout's grid; pose = 4 * angle index + quarter turns
  // The grid the charts were placed on: `zoom` texels a side per cell (a
  // layout of the half-size bitmap taken as it is: every texel a chart
  // covers lies in a cell its coarse mask covers), masks dilated by `pad`
  // cells. Chart c's texel coordinates are zoom * (texel_coordinates(pose,
  // scale / zoom, turns) + at[c] + pad).
  int zoom = 1, pad = 0;
};

// Every chart's masks at `scale`: 4 quarter turns per pose angle, for the
// pose angles [first, last) (clamped to the chart's), appended to masks[c];
// `serial`: on the calling thread only (a try running beside another).
void add_masks(const std::vector<PackChart>& charts, double scale, int pad, size_t first, size_t last,
               std::vector<std::vector<Mask>>& masks, bool serial = false);

// Packs at `scale` on a `side`-texel bitmap, each chart in the quarter
// turns of its smallest-box pose, or with `angles` of every pose angle it
// has. False when a chart does not fit.
bool try_scale(const std::vector<PackChart>& charts, double scale, int side, int pad, bool angles, Layout& out,
               bool serial = false);

// The layout with the largest scale / extent found on a `side`-texel bitmap
// (`side` doubles when even tiny scales do not fit: more charts than the
// bitmap holds with their padding). `area`: the charts' total area.
Layout search_layout(const std::vector<PackChart>& charts, double area, int& side, int pad);

}  // namespace intrinsic::detail::packing
