// JSON report construction (docs/formats.md "Report").
#include "report/report_json.h"

#include "intrinsic/report.h"

#include "intrinsic/io.h"

namespace intrinsic {
namespace {

nlohmann::json chart_json(const ChartSummary& c) {
  nlohmann::json j = {{"component", c.component},
                      {"vertices", c.vertices},
                      {"faces", c.faces},
                      {"method", method_name(c.weights.method)},
                      {"boundary", boundary_shape_name(c.boundary)},
                      {"holes", holes_applied_name(c.holes)},
                      {"packed", c.packed},
                      {"residual", c.residual},
                      {"free_vertices", c.free_vertices},
                      {"fixed_vertices", c.fixed_vertices},
                      {"flipped_triangles", c.flipped_triangles},
                      {"angle_distortion_mean", c.angle_distortion_mean},
                      {"uv_box", {{"min", {c.box_min.x(), c.box_min.y()}}, {"max", {c.box_max.x(), c.box_max.y()}}}}};
  if (c.fallback != ChartFallback::None) j["fallback"] = chart_fallback_name(c.fallback);
  return j;
}

// The blend lambda * conformal + mu * authalic that was solved.
std::pair<double, double> lambda_mu(const WeightOptions& w) {
  switch (w.method) {
    case Method::Mixed: return {w.lambda, w.mu};
    case Method::Conformal: return {1.0, 0.0};
    case Method::Authalic: return {0.0, 1.0};
    default: return {0.0, 0.0};
  }
}

}  // namespace

nlohmann::json stat_json(const Stat& s) { return {{"min", s.min}, {"mean", s.mean}, {"max", s.max}}; }

nlohmann::json mesh_json(const Mesh& mesh) {
  const Topology& t = mesh.topology;
  nlohmann::json loops = nlohmann::json::array();
  for (size_t l = 0; l < t.boundary_loops.size(); ++l)
    loops.push_back({{"vertices", t.boundary_loops[l].size()}, {"length", t.loop_length[l]}});
  return {{"input", mesh.path},
          {"vertices", mesh.V.rows()},
          {"faces", mesh.F.rows()},
          {"boundary_loops", t.boundary_loops.size()},
          {"loops", loops},
          {"components", t.num_components},
          {"reoriented_faces", mesh.validation.reoriented_faces},
          {"unreferenced_vertices", mesh.validation.unreferenced_vertices}};
}

void add_distortion(nlohmann::json& r, const DistortionSummary& d) {
  r["flipped_triangles"] = d.flipped_triangles;
  r["collapsed_triangles"] = d.collapsed_triangles;
  r["angle_distortion"] = stat_json(d.angle_distortion);
  r["area_distortion"] = stat_json(d.area_distortion);
  r["stretch_l2"] = stat_json(d.stretch_l2);
  r["stretch_linf"] = stat_json(d.stretch_linf);
  r["edge_length_distortion"] = stat_json(d.edge_length_distortion);
  r["edge_length_energy"] = d.edge_length_energy;
  r["area_energy"] = d.area_energy;
  r["distortion_normalisation"] = {
      {"uv_scale_factor", d.scale_factor},
      {"note", "UVs scaled so that total parameter area equals total 3D area before computing distortion"}};
}

nlohmann::json stretch_json(const StretchSummary& s) {
  return {{"sander_l2", s.sander_l2},
          {"sander_linf", s.sander_linf},
          {"face_stretch_p50", s.face_stretch_p50},
          {"face_stretch_p95", s.face_stretch_p95},
          {"face_stretch_p99", s.face_stretch_p99},
          {"face_stretch_max", s.face_stretch_max},
          {"anisotropy_mean", s.anisotropy_mean}};
}

nlohmann::json constraints_json(const std::vector<ConstraintResidual>& residuals) {
  nlohmann::json out = nlohmann::json::array();
  for (const ConstraintResidual& r : residuals)
    out.push_back({{"label", r.label},
                   {"target", {r.target.x(), r.target.y()}},
                   {"uv", {r.value.x(), r.value.y()}},
                   {"residual", r.residual}});
  return out;
}

std::string boundary_label(BoundaryShape shape, const std::string& boundary_file) {
  return shape == BoundaryShape::Given ? "file:" + boundary_file : boundary_shape_name(shape);
}

void add_solution(nlohmann::json& report, const ParamResult& r, const std::string& boundary_file) {
  const auto [lambda, mu] = lambda_mu(r.weights);
  report["method"] = method_name(r.weights.method);
  report["lambda"] = lambda;
  report["mu"] = mu;
  report["boundary"] = boundary_label(r.boundary, boundary_file);
  report["spacing"] = spacing_name(r.spacing);
  report["scale"] = placement_name(r.placement);
  report["holes"] = holes_applied_name(r.holes);
  report["filled_holes"] = r.filled_holes;
  if (!r.pins.empty()) {
    nlohmann::json pins = nlohmann::json::array();
    for (const FixedVertex& p : r.pins) pins.push_back({{"vertex", p.vertex}, {"u", p.uv.x()}, {"v", p.uv.y()}});
    report["pins"] = pins;  // as solved, before any --scale unit fit
  }
  if (!r.charts.empty()) {
    report["charts"] = nlohmann::json::array();
    for (const ChartSummary& c : r.charts) report["charts"].push_back(chart_json(c));
  }
  report["solver"] = solvers_name(r.solvers);
  report["residual"] = r.residual;
  report["free_vertices"] = r.free_vertices;
  report["fixed_vertices"] = r.fixed_vertices;
  report["factorizations"] = r.factorizations;
  if (r.iterations > 0) report["iterations"] = r.iterations;
  if (!r.constraints.empty()) report["constraints"] = constraints_json(r.constraints);
}

nlohmann::json optimal_lambda_json(const OptimalLambdaResult& best, const OptimalLambdaOptions& o) {
  return {{"energy", lambda_energy_name(o.energy)},
          {"lambda", best.lambda},
          {"range", {o.lo, o.hi}},
          {"energy_at_lambda", best.energy},
          {"energy_at_0_authalic", best.energy_at_0},
          {"energy_at_1_conformal", best.energy_at_1},
          {"polynomial", best.coefficients},
          {"boundary_scale", best.boundary_scale},
          {"note", "map = lambda*conformal + (1-lambda)*authalic with a common fixed boundary; energies "
                   "evaluated with the boundary scaled so that parameter area = 3D area"},
          {"timings_ms", {{"conformal", best.conformal_ms}, {"authalic", best.authalic_ms},
                          {"polynomial", best.polynomial_ms}}}};
}

nlohmann::json boundary_optimization_json(const BoundaryOptimizationResult& best,
                                          const BoundaryOptimizationOptions& o) {
  return {{"boundary_energy", boundary_energy_name(o.energy)},
          {"gradient", gradient_route_name(o.route)},
          {"descent", descent_name(o.descent)},
          {"iterations", best.iterations},
          {"stop_reason", best.stop_reason},
          {"energy_initial", best.energy_history.front()},
          {"energy_final", best.energy_history.back()},
          {"energy_history", best.energy_history},
          {"solves", best.solves},
          {"response_solves", best.response_solves},
          {"factorizations", best.factorizations},
          {"flipped_initial", best.flipped_initial},
          {"flipped_final", best.flipped_final},
          {"timings_ms", {{"setup", best.setup_ms}, {"optimize", best.optimize_ms}}}};
}

nlohmann::json atlas_metrics_json(const UvAtlasMetrics& a) {
  nlohmann::json list = nlohmann::json::array();
  for (const UvChart& c : a.charts)
    list.push_back({{"faces", c.faces}, {"uv_area", c.uv_area}, {"area_3d", c.area_3d},
                    {"mirrored", c.mirrored}, {"flipped", c.flipped}, {"collapsed", c.collapsed},
                    {"degenerate", c.degenerate}});
  return {{"charts", static_cast<int>(a.charts.size()) - a.degenerate_charts},
          {"degenerate_charts", a.degenerate_charts},
          {"utilization", a.utilization},
          {"utilization_of", a.utilization_in_unit_square ? "unit_square" : "bounding_square"},
          {"utilization_bbox", a.utilization_bbox},
          {"uv_area", a.uv_area},
          {"mirrored_charts", a.mirrored_charts},
          {"mirrored_faces", a.mirrored_faces},
          {"flipped_triangles", a.flipped_triangles},
          {"collapsed_triangles", a.collapsed_triangles},
          {"degenerate_faces", a.degenerate_faces},
          {"overlapping_triangles", a.overlapping_triangles},
          {"overlapping_pairs_within_charts", a.overlapping_pairs_within_charts},
          {"overlapping_pairs_between_charts", a.overlapping_pairs_between_charts},
          {"chart_list", list}};
}

nlohmann::json texture_transfer_json(const TextureTransferReport& report) {
  nlohmann::json baked = nlohmann::json::array();
  for (const BakedTexture& b : report.baked)
    baked.push_back({{"material", b.material},
                     {"material_name", b.material_name},
                     {"slot", b.slot},
                     {"source", b.source},
                     {"output", b.output},
                     {"width", b.width},
                     {"height", b.height},
                     {"texels_covered", b.texels_covered}});
  return {{"baked", baked}, {"notes", report.notes}};
}

// The public parts as text (intrinsic/report.h).
std::string stat_report(const Stat& s) { return stat_json(s).dump(); }
std::string atlas_metrics_report(const UvAtlasMetrics& atlas) { return atlas_metrics_json(atlas).dump(); }
std::string texture_transfer_report(const TextureTransferReport& report) {
  return texture_transfer_json(report).dump();
}
std::string mesh_report(const Mesh& mesh) { return mesh_json(mesh).dump(); }
std::string distortion_report(const DistortionSummary& d) {
  nlohmann::json j = nlohmann::json::object();
  add_distortion(j, d);
  return j.dump();
}
std::string stretch_report(const StretchSummary& s) { return stretch_json(s).dump(); }
std::string constraints_report(const std::vector<ConstraintResidual>& residuals) {
  return constraints_json(residuals).dump();
}
std::string solution_report(const ParamResult& r, const std::string& boundary_file) {
  nlohmann::json j = nlohmann::json::object();
  add_solution(j, r, boundary_file);
  return j.dump();
}

}  // namespace intrinsic
