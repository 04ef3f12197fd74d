// The atlas job shared by `intrinsic atlas` and the Python module: writing
// the atlas OBJ and building its report from the result only.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "intrinsic/atlas.h"
#include "weight_args.h"

namespace intrinsic::app {

// The input's vertices in input order, one `vt` per atlas UV, the result's
// faces (the input's, reoriented ones reversed) `f v/vt` (seams only through
// the per-corner texture coordinates); atomically.
void write_atlas_obj(const std::string& path, const MeshData& m, const AtlasResult& r);

// The atlas in the format the extension names: .obj (write_atlas_obj) or .glb
// (write_glb, vertices split at seams). Throws Error(Usage) for any other
// extension, before anything is written.
void check_atlas_output(const std::string& path);
void write_atlas_file(const std::string& path, const MeshData& m, const AtlasResult& r);

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
