// JSON bodies of the serve API (api_json.h).
#include "serve/api_json.h"

#include <nlohmann/json.hpp>

#include "intrinsic/metrics.h"

namespace intrinsic::app {

std::string mesh_api_json(const Mesh& mesh) {
  nlohmann::json positions = nlohmann::json::array(), triangles = nlohmann::json::array();
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
    for (int k = 0; k < 3; ++k) positions.push_back(mesh.V(i, k));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) triangles.push_back(mesh.F(f, k));
  return nlohmann::json{{"vertices", mesh.V.rows()},
                        {"faces", mesh.F.rows()},
                        {"positions", positions},
                        {"triangles", triangles},
                        {"boundary_loops", mesh.topology.boundary_loops}}
      .dump();
}

std::string solve_api_json(const Mesh& mesh, const SolveAnswer& a) {
  const DistortionSummary d = summarize_distortion(mesh.V, mesh.F, a.uv);
  nlohmann::json uv = nlohmann::json::array();
  for (Eigen::Index i = 0; i < a.uv.rows(); ++i) uv.push_back({a.uv(i, 0), a.uv(i, 1)});
  nlohmann::json out{{"uv", uv},
                     {"flipped_triangles", d.flipped_triangles},
                     {"angle_distortion_mean", d.angle_distortion.mean},
                     {"update_ms", a.update_ms},
                     {"path", a.path}};
  if (!a.pins.empty()) {
    nlohmann::json pins = nlohmann::json::array();
    for (const FixedVertex& p : a.pins) pins.push_back({p.vertex, p.uv.x(), p.uv.y()});
    out["pins"] = pins;
  }
  return out.dump();
}

std::string error_api_json(const std::string& message) {
  // A message may quote bytes of the request: never fail on invalid UTF-8.
  return nlohmann::json{{"error", message}}.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace intrinsic::app
