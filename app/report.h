// The JSON distortion report shared by `param` and `metrics` (keys listed in
// README "Report").
#pragma once

#include <nlohmann/json.hpp>

#include "intrinsic/constraints.h"
#include "intrinsic/metrics.h"
#include "intrinsic/topology.h"

namespace intrinsic::app {

nlohmann::json stat_json(const Stat& s);
// Mesh facts: vertices, faces, boundary_loops, components, validation fixes.
nlohmann::json mesh_json(const Mesh& mesh);
// Adds the distortion summary's keys to `report`.
void add_distortion(nlohmann::json& report, const DistortionSummary& d);
// One entry per constraint row: label, target, uv reached, residual.
nlohmann::json constraints_json(const std::vector<ConstraintResidual>& residuals);
// Writes the report atomically (pretty-printed).
void write_report(const std::string& path, const nlohmann::json& report);

}  // namespace intrinsic::app
