// The parts of the JSON reports of `param`, `metrics` and `atlas` (keys
// listed in docs/formats.md "Report") as nlohmann::json, inside the library;
// the public face is intrinsic/report.h, which gives them as JSON text.
// Built from the library's result structs only: what was solved is read
// from the result, never rebuilt from the command line. The only other
// inputs are names the results cannot know (file paths).
#pragma once

#include <nlohmann/json.hpp>

#include "intrinsic/boundary_optimization.h"
#include "intrinsic/constraints.h"
#include "intrinsic/metrics.h"
#include "intrinsic/optimal_lambda.h"
#include "intrinsic/parameterize.h"
#include "intrinsic/texture_transfer.h"
#include "intrinsic/uv_mesh.h"

namespace intrinsic {

nlohmann::json stat_json(const Stat& s);
// The atlas part of the `metrics` report: charts, utilization, mirrored
// charts, flipped, collapsed and overlapping triangles, per-chart list.
nlohmann::json atlas_metrics_json(const UvAtlasMetrics& atlas);
// The report's "textures" object: {"baked": [...], "notes": [...]}.
nlohmann::json texture_transfer_json(const TextureTransferReport& report);

// Mesh facts: vertices, faces, boundary_loops, components, validation fixes.
nlohmann::json mesh_json(const Mesh& mesh);
// Adds the distortion summary's keys to `report`.
void add_distortion(nlohmann::json& report, const DistortionSummary& d);
// The "stretch" object (docs/maths.md §9.8): exactly sander_l2, sander_linf,
// face_stretch_p50, face_stretch_p95, face_stretch_p99, face_stretch_max,
// anisotropy_mean (an infinite figure, from a collapsed face, prints as null).
nlohmann::json stretch_json(const StretchSummary& s);
// One entry per constraint row: label, target, uv reached, residual.
nlohmann::json constraints_json(const std::vector<ConstraintResidual>& residuals);
// "circle", "square", "natural", or "file:PATH" for given positions.
std::string boundary_label(BoundaryShape shape, const std::string& boundary_file);

// Adds what the map was and how it was solved: method, lambda, mu, boundary,
// spacing, scale, holes, filled_holes, pins, charts, solver, residual,
// free_vertices, fixed_vertices, iterations, constraints.
void add_solution(nlohmann::json& report, const ParamResult& r, const std::string& boundary_file);
nlohmann::json optimal_lambda_json(const OptimalLambdaResult& best, const OptimalLambdaOptions& options);
nlohmann::json boundary_optimization_json(const BoundaryOptimizationResult& best,
                                          const BoundaryOptimizationOptions& options);

}  // namespace intrinsic
