// Meshes in several pieces: every connected component is parameterized as its
// own chart (the paper treats one patch at a time, section 1.3 "atlas of
// charts"), each through the one Parameterizer, then laid out side by side
// without overlap.
#pragma once

#include <vector>

#include "intrinsic/parameterize.h"

namespace intrinsic {

// Each component with `options`, except that a component without a usable
// fixed boundary (given positions that miss it, a square on a loop of fewer
// than 4 vertices) gets the natural conformal map; its ChartSummary says so
// (fallback, boundary, weights). Given boundary positions and pins are global
// vertex indices; charts they fix stay exactly where they put them. Every
// other chart is scaled so its parameter area equals its 3D area (a common
// scale for all), then shelf-packed by bounding box with a gap of 2% of the
// packed size, to the right of the fixed charts; with ScaleMode::Unit and no
// fixed chart the whole layout is then fitted to [0,1]^2 by one similarity.
// The result's figures are summed (vertices, timings) or the worst (residual)
// over the charts; result.charts has one entry per component. Throws
// Error(Input) naming the first closed component, and the errors of
// parameterize prefixed by the chart.
ParamResult parameterize_charts(const Mesh& mesh, const ParamOptions& options);

// The component with the most faces (the smallest index among equals).
int largest_component(const Mesh& mesh);
// The faces of one component; vertex indices (and V) unchanged, so vertices
// of other components become unreferenced.
MeshData component_data(const Mesh& mesh, int component);

}  // namespace intrinsic
