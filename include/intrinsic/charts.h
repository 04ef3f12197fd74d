// Meshes in several pieces: every connected component is parameterized as its
// own chart (the paper treats one patch at a time, section 1.3 "atlas of
// charts"), then the charts are laid out side by side without overlap.
#pragma once

#include <string>
#include <vector>

#include "intrinsic/parameterize.h"

namespace intrinsic {

struct ChartSummary {
  int component = 0;            // index in mesh.topology
  int vertices = 0, faces = 0;  // used vertices and faces of the chart
  std::string boundary;         // "circle", "square", "given" or "natural"
  std::string holes;            // the hole rule applied ("none" without holes)
  bool packed = true;           // false: kept where given positions or pins put it
  int flipped_triangles = 0;
  double angle_distortion_mean = 0;
  Eigen::Vector2d box_min = Eigen::Vector2d::Zero(), box_max = Eigen::Vector2d::Zero();  // in the final layout
};

struct ChartsResult {
  MatrixX2d UV;  // #V x 2, unused vertices at (0, 0)
  std::vector<ChartSummary> charts;
  std::string solver;    // backends used, e.g. "cholmod"
  double residual = 0;   // largest over the charts
  std::string scale;     // "unit", "surface" or "given"
  StageTimings timings;  // summed over the charts
};

// Each component with `options`, except that a component without a usable
// fixed boundary (given positions that miss it, a square on a loop of fewer
// than 4 vertices) gets the natural conformal map. Given boundary positions
// and pins are global vertex indices; charts they fix stay exactly where they
// put them. Every other chart is scaled so its parameter area equals its 3D
// area (a common scale for all), then shelf-packed by bounding box with a gap
// of 2% of the packed size, to the right of the fixed charts; with
// ScaleMode::Unit and no fixed chart the whole layout is then fitted to
// [0,1]^2 by one similarity. Throws Error(Input) naming the first closed
// component, and the errors of parameterize prefixed by the chart.
ChartsResult parameterize_charts(const Mesh& mesh, const ParamOptions& options);

// The component with the most faces (the smallest index among equals).
int largest_component(const Mesh& mesh);
// The faces of one component; vertex indices (and V) unchanged, so vertices
// of other components become unreferenced.
MeshData component_data(const Mesh& mesh, int component);

}  // namespace intrinsic
