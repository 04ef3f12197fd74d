// The atlas job shared by `intrinsic atlas` and the Python module: the
// chart map options and the report, built from the result only.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "intrinsic/atlas.h"
#include "weight_args.h"

namespace intrinsic::app {

// The chart map as `param` spells it: --boundary natural|circle|square,
// --method/--lambda/--mu (fixed boundaries only), --optimize-lambda
// edge|area or --optimize-boundary edge|area|dirichlet.
struct ChartMapArgs {
  std::string boundary = "natural", optimize_lambda, optimize_boundary;
  std::shared_ptr<WeightArgs> weights = std::make_shared<WeightArgs>();
};
// Throws Error(Usage) for inconsistent or unknown values.
ChartMapOptions chart_map_options(const ChartMapArgs& a);

// vertices, faces, components, charts, splits, split_reasons, utilization,
// flipped, overlapping, resolution, padding, cleaning, chart_list (docs/cli.md
// "intrinsic atlas"). The caller adds input, output and timings_ms.
nlohmann::json atlas_report(const MeshData& m, const AtlasOptions& options, const AtlasResult& r);

}  // namespace intrinsic::app
