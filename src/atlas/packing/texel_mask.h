// Packing, step 2: a chart as texels. At a given scale (texels per unit of
// surface) a chart covers the texels its triangles touch (closed: a texel
// that a triangle only grazes counts, so no part of a triangle is ever
// outside its mask). The mask is then dilated by the padding (Chebyshev:
// every texel within `pad` texels in x and y): a chart may be placed only
// where its dilated mask meets no texel another chart covers, which keeps
// `pad` empty texels between any two charts. Masks are run-length rows
// (spans), so a test against the bitmap skips whole runs at once.
#pragma once

#include <array>
#include <utility>
#include <vector>

#include "atlas/atlas_internal.h"

namespace intrinsic::detail::packing {

// Texel spans of one row: [begin, end) pairs, sorted, disjoint.
using Spans = std::vector<std::pair<int, int>>;

// A chart rasterized in one pose: the texels it covers (`own`) and the same
// dilated by the padding (`rows`), in one frame `w` x `h` that starts `pad`
// texels left of and below the chart's own texels.
struct Mask {
  int w = 0, h = 0;         // size of the dilated frame
  std::vector<Spans> rows;  // dilated, per row of the frame
  std::vector<Spans> own;   // undilated, per row of the frame
  long texels = 0;          // undilated
  std::vector<int> widest;  // per row of the frame: its widest dilated span
  std::vector<int> by_width;  // the frame's rows, widest span first
  bool box = false;         // the dilated texels fill the frame
  // The largest rectangle of dilated texels (corner x, y in the frame; w, h):
  // wherever the mask fits, this box fits too (placement.cpp's cursors).
  std::array<int, 4> inner{0, 0, 0, 0};
};

// The chart's size in whole texels at `scale` (UV with its corner at the origin).
Eigen::Vector2i cells_of(const MatrixX2d& UV, double scale);

// The covered texels (row-major, cells_of wide and high) of the triangles F
// of UV (corner at the origin) at `scale`.
std::vector<char> rasterize(const MatrixX3i& F, const MatrixX2d& UV, double scale);

// A quarter turn counter-clockwise of a w x h texel grid: texel (x, y) goes
// to (h - 1 - y, x); the result is h x w.
std::vector<char> quarter_turn(const std::vector<char>& grid, int w, int h);

// The mask of a covered-texel grid (w x h, row-major): the frame, the spans,
// and the dilation by `pad`.
// `inner`: Mask::inner searched for (else left empty).
Mask mask_of(const std::vector<char>& grid, int w, int h, int pad, bool inner = true);

// The mask with its dilated texels grown to the whole frame. Small charts
// are placed as such boxes: the few corner texels given up cost little, and
// a box that does not fit somewhere tells that no larger box does
// (placement.cpp's search cursors).
void fill_frame(Mask& m);

// The chart (UV, corner at the origin) at `scale` in its four quarter turns,
// counter-clockwise: masks[k] is the first turned k times. The grid turns
// onto itself (texel_coordinates), so one rasterization serves all four.
// With `as_box`, the masks it accepts (given the mask and `pad`) come
// filled (fill_frame): as filling each afterwards, without the search for
// a largest box that filling replaces.
std::vector<Mask> quarter_turn_masks(const MatrixX3i& F, const MatrixX2d& UV, double scale, int pad,
                                     bool (*as_box)(const Mask&, int) = nullptr);

// UV (corner at the origin) in texel units at `scale` after `turns` quarter
// turns counter-clockwise, each (x, y) -> (h - y, x) with h the texel height
// of the grid before it: the same turn as quarter_turn's, so the turned
// chart lies on the turned mask's texels.
MatrixX2d texel_coordinates(const MatrixX2d& UV, double scale, int turns);

}  // namespace intrinsic::detail::packing
