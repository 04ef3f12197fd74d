// The atlas's options: the pack stage's options as the one call runs them,
// and each stage's range checks (Error(Usage)), done before any work.
#include "atlas/atlas_internal.h"
#include "intrinsic/error.h"

namespace intrinsic {

PackOptions pack_options(const AtlasOptions& o) {
  PackOptions p = o.pack;
  p.keep_orientation = o.pack_only;
  return p;
}

namespace detail {

void check_chart_options(const ChartOptions& o) {
  if (!(o.max_normal_deviation_deg > 0 && o.max_normal_deviation_deg <= 180))
    throw_usage("the normal deviation must be in (0, 180] degrees");
  if (!(o.hard_angle_deg >= 0 && o.hard_angle_deg < 180))
    throw_usage("the hard angle must be in [0, 180) degrees (0: no hard edges)");
  if (!(o.sharp_angle_deg > 0 && o.sharp_angle_deg <= 180)) throw_usage("the sharp angle must be in (0, 180] degrees");
  if (o.min_chart_faces < 0) throw_usage("the minimum chart size must be at least 0 faces");
  if (!(o.max_stretch >= 1)) throw_usage("the stretch bound must be at least 1");
  if (!(o.max_face_stretch >= 1)) throw_usage("the per-face stretch bound must be at least 1");
  if (o.chart_map.isometric_iterations < 0) throw_usage("the isometric refinement steps must be at least 0");
  if (o.max_charts < 0) throw_usage("the chart limit must be at least 0 (0: no limit)");
  if (!(o.degenerate_ratio >= 0 && o.degenerate_ratio < 1)) throw_usage("the degenerate ratio must be in [0, 1)");
  if (!(o.weld >= 0 && o.weld < 1))
    throw_usage("the weld distance must be in [0, 1) (a fraction of the bounding box diagonal)");
  const ChartMapOptions& m = o.chart_map;
  if (m.boundary != BoundaryShape::Natural && m.boundary != BoundaryShape::Circle &&
      m.boundary != BoundaryShape::Square)
    throw_usage("a chart's boundary is natural, circle or square");
  if (m.optimizer != ChartOptimizer::None && m.boundary == BoundaryShape::Natural)
    throw_usage("optimal lambda and boundary optimization need a fixed chart boundary (circle or square)");
  // Checked here rather than per chart: a chart whose solve fails is split,
  // so a bad option would otherwise end in single triangles, not an error.
  check_weights(m.weights);
}

void check_pack_options(const PackOptions& o) {
  if (o.resolution < 1 || o.resolution > 1 << 20) throw_usage("the resolution must be between 1 and 1048576 texels");
  if (!(o.padding >= 0 && o.padding < o.resolution / 4.0))
    throw_usage("the padding must be at least 0 and less than a quarter of the resolution");
  if (!(o.texels_per_unit >= 0 && o.texels_per_unit <= 1e12))
    throw_usage("texels_per_unit must be 0 (fill one page) or a positive density");
  if (o.max_pages < 0) throw_usage("max_pages must be 0 (no limit) or positive");
}

}  // namespace detail
// How the command line, Python and the reports spell these (intrinsic/choice.h).
template <>
ChoiceTable<Segmentation> choice_table<Segmentation>() {
  static const Choice<Segmentation> rows[] = {{Segmentation::NormalCones, "normal-cones"},
                                              {Segmentation::Components, "components"}};
  return make_choice_table(rows);
}

// How a chart was flattened (atlas reports only).
template <>
ChoiceTable<ChartMethod> choice_table<ChartMethod>() {
  static const Choice<ChartMethod> rows[] = {{ChartMethod::Natural, "natural", false},
                                             {ChartMethod::Triangle, "triangle", false},
                                             {ChartMethod::FixedBoundary, "fixed-boundary", false},
                                             {ChartMethod::OptimalLambda, "optimal-lambda", false},
                                             {ChartMethod::OptimizedBoundary, "optimized-boundary", false}};
  return make_choice_table(rows);
}

template <>
ChoiceTable<ChartOptimizer> choice_table<ChartOptimizer>() {
  static const Choice<ChartOptimizer> rows[] = {{ChartOptimizer::None, "none"},
                                                {ChartOptimizer::OptimalLambda, "optimal-lambda"},
                                                {ChartOptimizer::OptimizeBoundary, "optimize-boundary"}};
  return make_choice_table(rows);
}

template <>
ChoiceTable<AtlasScope> choice_table<AtlasScope>() {
  static const Choice<AtlasScope> rows[] = {{AtlasScope::Whole, "whole"}, {AtlasScope::PerMesh, "per-mesh"}};
  return make_choice_table(rows);
}

// Declared in atlas.h as a C string, for callers that print it directly.
const char* chart_method_name(ChartMethod m) {
  for (const Choice<ChartMethod>& c : choice_table<ChartMethod>())
    if (c.value == m) return c.name;
  return "?";
}

}  // namespace intrinsic
