// The JSON reports of the two jobs of pipeline.h (docs/formats.md "Report",
// docs/cli.md "intrinsic atlas"): built from the request and the outcome
// only, so every shell (command line, Python, server) prints the same keys
// and values.
#include <cmath>

#include <nlohmann/json.hpp>

#include "intrinsic/gltf.h"
#include "intrinsic/pipeline.h"
#include "report/report_json.h"

namespace intrinsic {
namespace {

nlohmann::json path_or_null(const std::string& path) {
  return path.empty() ? nlohmann::json(nullptr) : nlohmann::json(path);
}

nlohmann::json atlas_chart_map_json(const ChartMapOptions& cm) {
  nlohmann::json map{{"boundary", boundary_shape_name(cm.boundary)}};
  if (cm.boundary != BoundaryShape::Natural) {
    map["method"] = method_name(cm.weights.method);
    if (cm.weights.method == Method::Mixed) map["lambda"] = cm.weights.lambda, map["mu"] = cm.weights.mu;
  }
  if (cm.optimizer == ChartOptimizer::OptimalLambda) map["optimize_lambda"] = lambda_energy_name(cm.lambda_energy);
  if (cm.optimizer == ChartOptimizer::OptimizeBoundary)
    map["optimize_boundary"] = boundary_energy_name(cm.boundary_energy);
  if (cm.boundary == BoundaryShape::Natural) map["isometric_iterations"] = cm.isometric_iterations;
  return map;
}

nlohmann::json atlas_charts_json(const std::vector<AtlasChart>& charts) {
  nlohmann::json out = nlohmann::json::array();
  for (const AtlasChart& c : charts)
    out.push_back({{"component", c.component}, {"faces", c.faces}, {"vertices", c.vertices},
                   {"method", chart_method_name(c.method)}, {"flipped", c.flipped},
                   {"angle_distortion_mean", c.angle_distortion_mean}, {"stretch_l2_mean", c.stretch_l2_mean},
                   {"stretch_l2_rms", c.stretch_l2_rms}, {"face_stretch_p95", c.face_stretch_p95},
                   {"face_stretch_max", c.face_stretch_max}, {"refined", c.refined}, {"area_3d", c.area_3d},
                   {"boundary_length", c.boundary_length}, {"rotated", c.rotated}});
  return out;
}

nlohmann::json cleaning_json(const AtlasCleaning& c) {
  return {{"degenerate_faces", c.degenerate_faces},         {"nonmanifold_edges", c.nonmanifold_edges},
          {"nonmanifold_vertices", c.nonmanifold_vertices}, {"inconsistent_edges", c.inconsistent_edges},
          {"reversed_faces", c.reversed_faces},             {"orientation_cuts", c.orientation_cuts},
          {"unreferenced_vertices", c.unreferenced_vertices}, {"welded_vertices", c.welded_vertices},
          {"hard_edges", c.hard_edges}};
}

}  // namespace

std::string param_report(const ParamRequest& request, const ParamOutcome& o, const std::string& output) {
  const Mesh& mesh = o.mesh;
  nlohmann::json report = mesh_json(mesh);
  report["input"] = path_or_null(mesh.path);
  report["output"] = path_or_null(output);
  add_solution(report, o.map, request.boundary_file);
  if (o.optimal_lambda) {
    OptimalLambdaOptions lo = request.optimal_lambda;
    report["method"] = "optimal-lambda";
    report["optimal_lambda"] = optimal_lambda_json(*o.optimal_lambda, lo);
  }
  if (o.boundary_optimization)
    report["boundary_optimization"] = boundary_optimization_json(*o.boundary_optimization, request.boundary_optimization);
  if (!request.constraints_file.empty()) report["constraints_file"] = request.constraints_file;
  if (request.has_constraints()) report["constraints"] = constraints_json(o.map.constraints);
  // The scale the map came out at: parameter area over 3D area.
  report["area_ratio"] = std::abs(parameter_area(mesh.F, o.map.UV)) / surface_area(mesh.V, mesh.F);
  add_distortion(report, o.distortion);
  const StageTimings& t = o.map.timings;
  report["timings_ms"] = {{"read", o.read_ms},         {"validate", o.validate_ms}, {"assemble", t.assemble_ms},
                          {"factor", t.factor_ms},     {"solve", t.solve_ms}};
  return report.dump();
}

std::string atlas_report(const AtlasOutcome& o, const std::string& output) {
  const AtlasOptions& opt = o.options;
  const AtlasResult& r = o.result;
  nlohmann::json j;
  j["input"] = path_or_null(o.input.mesh.path);
  j["output"] = path_or_null(output);
  j["vertices"] = o.input.mesh.V.rows();
  j["faces"] = o.input.mesh.F.rows();
  j["components"] = r.components;
  j["charts"] = r.charts.size();
  j["splits"] = r.splits;
  const AtlasSplits& sr = r.split_reasons;
  j["split_reasons"] = {{"not_disk", sr.not_disk},         {"refused", sr.refused}, {"solve_failed", sr.solve_failed},
                        {"flipped", sr.flipped},           {"boundary_crossing", sr.boundary_crossing},
                        {"sparse", sr.sparse},             {"stretch", sr.stretch}};
  if (!opt.charts.face_group.empty()) j["split_groups"] = r.split_groups;
  j["utilization"] = r.utilization;
  j["stretch_l2_mean"] = r.stretch_l2_mean;  // area-weighted mean of per-chart mean L2, not Sander's RMS
  j["stretch"] = stretch_json(r.stretch);
  j["seam_length"] = r.seam_length;
  j["flipped"] = r.flipped;
  j["overlapping"] = r.overlapping;
  j["resolution"] = opt.pack.resolution;
  j["padding"] = opt.pack.padding;
  if (opt.pack.texels_per_unit > 0) {
    // Lightmap pages: the density asked, and per page its fill.
    j["texels_per_unit"] = opt.pack.texels_per_unit;
    j["pages"] = r.pages;
    j["page_utilization"] = r.page_utilization;
    j["chart_page"] = r.chart_page;
    j["shrunk_charts"] = r.shrunk_charts;
  }
  j["max_stretch"] = opt.charts.max_stretch;
  j["max_face_stretch"] = opt.charts.max_face_stretch;
  j["atlas_stretch_budget"] = opt.charts.atlas_stretch_budget;
  j["max_charts"] = opt.charts.max_charts;
  j["seam_edges"] = opt.charts.seams.size();
  // The input's own texture coordinates, if it had any, are not in the
  // output: the atlas takes their place.
  j["replaced_texcoords"] = o.input.mesh.had_texcoords;
  if (o.input.document.gltf) {
    const SceneSummary sc = scene_summary(o.input.document);
    j["scene"] = {{"meshes", sc.meshes},     {"instances", sc.instances}, {"materials", sc.materials},
                  {"images", sc.images},     {"cameras", sc.cameras},     {"lights", sc.lights},
                  {"skipped_primitives", sc.skipped_primitives}};
  }
  j["cleaning"] = cleaning_json(r.cleaning);
  j["hard_angle"] = opt.charts.hard_angle_deg;
  j["weld"] = opt.charts.weld;
  j["reorient"] = opt.charts.reorient;
  j["chart_map"] = atlas_chart_map_json(opt.charts.chart_map);
  j["chart_list"] = atlas_charts_json(r.charts);
  const AtlasTimings& t = r.timings;
  j["timings_ms"] = {{"read", o.read_ms},     {"clean", t.clean_ms}, {"segment", t.segment_ms},
                     {"flatten", t.flatten_ms}, {"merge", t.merge_ms}, {"pack", t.pack_ms}};
  return j.dump();
}

}  // namespace intrinsic
