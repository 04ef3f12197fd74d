// The atlas job the CLI (`intrinsic atlas`) and the Python module share:
// the chart map options and the JSON report, so both write the same bytes.
#include "atlas_job.h"

#include "report.h"
#include "intrinsic/error.h"
#include "intrinsic/boundary.h"
#include "intrinsic/io.h"

namespace intrinsic::app {
ChartMapOptions chart_map_options(const ChartMapArgs& a) {
  ChartMapOptions m;
  if (a.boundary != "natural" && a.boundary != "circle" && a.boundary != "square")
    throw_usage("--boundary: a chart's boundary is natural, circle or square");
  m.boundary = a.boundary == "circle" ? BoundaryShape::Circle
               : a.boundary == "square" ? BoundaryShape::Square
                                        : BoundaryShape::Natural;
  if (m.boundary == BoundaryShape::Natural &&
      (a.weights->method != "conformal" || a.weights->lambda_set || a.weights->mu_set))
    throw_usage("--method applies to fixed chart boundaries: add --boundary circle or square");
  m.weights = a.weights->options();
  if (!a.optimize_lambda.empty() && !a.optimize_boundary.empty())
    throw_usage("--optimize-lambda and --optimize-boundary: choose one");
  if (!a.optimize_lambda.empty()) {
    m.optimizer = ChartOptimizer::OptimalLambda;
    m.lambda_energy = parse_lambda_energy(a.optimize_lambda);
  } else if (!a.optimize_boundary.empty()) {
    m.optimizer = ChartOptimizer::OptimizeBoundary;
    m.boundary_energy = parse_boundary_energy(a.optimize_boundary);
  }
  return m;
}

nlohmann::json atlas_report(const MeshData& m, const AtlasOptions& o, const AtlasResult& r) {
  nlohmann::json j;
  j["vertices"] = m.V.rows();
  j["faces"] = m.F.rows();
  j["components"] = r.components;
  j["charts"] = r.charts.size();
  j["splits"] = r.splits;
  const AtlasSplits& sr = r.split_reasons;
  j["split_reasons"] = {{"not_disk", sr.not_disk}, {"refused", sr.refused}, {"solve_failed", sr.solve_failed},
                        {"flipped", sr.flipped}, {"boundary_crossing", sr.boundary_crossing}, {"sparse", sr.sparse}, {"stretch", sr.stretch}};
  j["utilization"] = r.utilization;
  j["stretch_l2_mean"] = r.stretch_l2_mean;  // area-weighted mean of per-chart mean L2, not Sander's RMS
  j["stretch"] = stretch_json(r.stretch);
  j["seam_length"] = r.seam_length;
  j["flipped"] = r.flipped;
  j["overlapping"] = r.overlapping;
  j["resolution"] = o.resolution;
  j["padding"] = o.padding;
  j["max_stretch"] = o.max_stretch;
  j["max_face_stretch"] = o.max_face_stretch;
  j["atlas_stretch_budget"] = o.atlas_stretch_budget;
  j["max_charts"] = o.max_charts;
  j["seam_edges"] = o.seams.size();
  j["cleaning"] = {{"degenerate_faces", r.cleaning.degenerate_faces},
                   {"nonmanifold_edges", r.cleaning.nonmanifold_edges},
                   {"nonmanifold_vertices", r.cleaning.nonmanifold_vertices},
                   {"inconsistent_edges", r.cleaning.inconsistent_edges},
                   {"reversed_faces", r.cleaning.reversed_faces},
                   {"orientation_cuts", r.cleaning.orientation_cuts},
                   {"unreferenced_vertices", r.cleaning.unreferenced_vertices},
                   {"welded_vertices", r.cleaning.welded_vertices},
                   {"hard_edges", r.cleaning.hard_edges}};
  j["hard_angle"] = o.hard_angle_deg;
  j["weld"] = o.weld;
  j["reorient"] = o.reorient;
  const ChartMapOptions& cm = o.chart_map;
  nlohmann::json map{{"boundary", boundary_shape_name(cm.boundary)}};
  if (cm.boundary != BoundaryShape::Natural) {
    map["method"] = method_name(cm.weights.method);
    if (cm.weights.method == Method::Mixed) map["lambda"] = cm.weights.lambda, map["mu"] = cm.weights.mu;
  }
  if (cm.optimizer == ChartOptimizer::OptimalLambda) map["optimize_lambda"] = lambda_energy_name(cm.lambda_energy);
  if (cm.optimizer == ChartOptimizer::OptimizeBoundary)
    map["optimize_boundary"] = boundary_energy_name(cm.boundary_energy);
  if (cm.boundary == BoundaryShape::Natural) map["isometric_iterations"] = cm.isometric_iterations;
  j["chart_map"] = map;
  nlohmann::json charts = nlohmann::json::array();
  for (const AtlasChart& c : r.charts)
    charts.push_back({{"component", c.component}, {"faces", c.faces}, {"vertices", c.vertices},
                      {"method", chart_method_name(c.method)}, {"flipped", c.flipped},
                      {"angle_distortion_mean", c.angle_distortion_mean}, {"stretch_l2_mean", c.stretch_l2_mean},
                      {"stretch_l2_rms", c.stretch_l2_rms}, {"face_stretch_p95", c.face_stretch_p95},
                      {"face_stretch_max", c.face_stretch_max},
                      {"refined", c.refined},
                      {"area_3d", c.area_3d}, {"boundary_length", c.boundary_length}, {"rotated", c.rotated}});
  j["chart_list"] = charts;
  return j;
}

}  // namespace intrinsic::app
