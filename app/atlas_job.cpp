// The atlas job the CLI (`intrinsic atlas`) and the Python module share:
// the OBJ with per-corner texture coordinates and the JSON report, so both
// write the same bytes.
#include "atlas_job.h"

#include <charconv>

#include "mesh_paths.h"
#include "report.h"
#include "intrinsic/error.h"
#include "intrinsic/boundary.h"
#include "intrinsic/io.h"

namespace intrinsic::app {
namespace {

void put(std::string& s, double x) {
  char b[32];
  s.append(b, std::to_chars(b, b + sizeof b, x).ptr);
}

void put(std::string& s, long x) {
  char b[24];
  s.append(b, std::to_chars(b, b + sizeof b, x).ptr);
}

}  // namespace

void check_atlas_output(const std::string& path) {
  const std::string ext = mesh_extension(path);
  if (ext != ".obj" && ext != ".glb")
    throw_usage("output '" + path + "': the atlas is written as .obj (one texture coordinate per corner) or .glb");
  if (ext == ".glb" && path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0)
    throw_usage("output '" + path + "': .glb is written uncompressed (drop the .gz)");
}

void write_atlas_file(const std::string& path, const MeshData& m, const AtlasResult& r) {
  check_atlas_output(path);
  if (mesh_extension(path) == ".glb") write_glb(path, m.V, r.F, r.UV, r.FUV);  // the faces as written (reorient)
  else write_atlas_obj(path, m, r);
}

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

// The OBJ, streamed in blocks of lines.
void write_atlas_obj(const std::string& path, const MeshData& m, const AtlasResult& r) {
  write_file_atomically(path, [&](const ByteSink& sink) {
    std::string s = "# intrinsic atlas: " + std::to_string(r.charts.size()) + " charts\n";
    auto flush = [&](bool force) {
      if (force || s.size() > (1 << 20)) sink(s.data(), s.size()), s.clear();
    };
    for (int v = 0; v < m.V.rows(); ++v) {
      s += "v";
      for (int c = 0; c < 3; ++c) s += ' ', put(s, m.V(v, c));
      s += '\n';
      flush(false);
    }
    for (int t = 0; t < r.UV.rows(); ++t) {
      s += "vt ";
      put(s, r.UV(t, 0));
      s += ' ';
      put(s, r.UV(t, 1));
      s += '\n';
      flush(false);
    }
    for (int f = 0; f < r.F.rows(); ++f) {
      s += "f";
      for (int c = 0; c < 3; ++c) {
        s += ' ';
        put(s, static_cast<long>(r.F(f, c)) + 1);
        s += '/';
        put(s, static_cast<long>(r.FUV(f, c)) + 1);
      }
      s += '\n';
      flush(false);
    }
    flush(true);
  });
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
