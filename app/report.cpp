// JSON report construction and writing.
#include "report.h"

#include "intrinsic/io.h"

namespace intrinsic::app {

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

nlohmann::json constraints_json(const std::vector<ConstraintResidual>& residuals) {
  nlohmann::json out = nlohmann::json::array();
  for (const ConstraintResidual& r : residuals)
    out.push_back({{"label", r.label},
                   {"target", {r.target.x(), r.target.y()}},
                   {"uv", {r.value.x(), r.value.y()}},
                   {"residual", r.residual}});
  return out;
}

void write_report(const std::string& path, const nlohmann::json& report) {
  write_file_atomically(path, report.dump(2) + "\n");
}

}  // namespace intrinsic::app
