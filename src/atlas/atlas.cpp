// intrinsic::atlas (atlas.h): the one-call form, the charts stage and the
// pack stage in turn (chart_stage.cpp, pack_stage.cpp), every option checked
// first so that a bad packing option fails before the charts are computed.
#include "atlas/atlas_internal.h"

namespace intrinsic {

const char* chart_method_name(ChartMethod m) {
  switch (m) {
    case ChartMethod::Natural: return "natural";
    case ChartMethod::Triangle: return "triangle";
    case ChartMethod::FixedBoundary: return "fixed-boundary";
    case ChartMethod::OptimalLambda: return "optimal-lambda";
    case ChartMethod::OptimizedBoundary: return "optimized-boundary";
  }
  return "natural";
}

AtlasResult atlas(const MeshData& input, const AtlasOptions& options) {
  const ChartOptions chart = chart_options(options);
  const PackOptions pack = pack_options(options);
  detail::check_chart_options(chart);
  detail::check_pack_options(pack);
  return pack_charts(compute_charts(input, chart), pack);
}

}  // namespace intrinsic
