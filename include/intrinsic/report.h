// The parts of the JSON reports of `param`, `metrics`, `atlas`, `edit` and
// `compare` (keys listed in docs/formats.md "Report") as JSON text, built
// from the library's result structs only. A shell composes its report from
// them with its own JSON reader (the command line with nlohmann::json, the
// Python module with json.loads), so no JSON library's type is part of the
// API. The whole reports of the two jobs are pipeline.h's param_report and
// atlas_report.
#pragma once

#include <string>
#include <vector>

#include "intrinsic/constraints.h"
#include "intrinsic/metrics.h"
#include "intrinsic/parameterize.h"
#include "intrinsic/texture_transfer.h"
#include "intrinsic/uv_mesh.h"

namespace intrinsic {

// {"min", "mean", "max"}.
std::string stat_report(const Stat& s);
// The atlas part of the `metrics` report: charts, utilization, mirrored
// charts, flipped, collapsed and overlapping triangles, per-chart list.
std::string atlas_metrics_report(const UvAtlasMetrics& atlas);
// The report's "textures" object: {"baked": [...], "notes": [...]}.
std::string texture_transfer_report(const TextureTransferReport& report);
// Mesh facts: input, vertices, faces, boundary_loops, components, validation fixes.
std::string mesh_report(const Mesh& mesh);
// The distortion summary's keys, which a report carries at its top level.
std::string distortion_report(const DistortionSummary& d);
// The "stretch" object (docs/maths.md §9.8).
std::string stretch_report(const StretchSummary& s);
// One entry per constraint row: label, target, uv reached, residual.
std::string constraints_report(const std::vector<ConstraintResidual>& residuals);
// What the map was and how it was solved (method, lambda, mu, boundary,
// spacing, scale, holes, pins, charts, solver, residual, ...), keys that a
// report carries at its top level.
std::string solution_report(const ParamResult& r, const std::string& boundary_file);

}  // namespace intrinsic
