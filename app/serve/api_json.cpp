// JSON bodies of the serve API (api_json.h).
#include "serve/api_json.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>

#include "intrinsic/metrics.h"

namespace intrinsic::app {

std::string mesh_api_json(const Mesh& mesh, const MatrixX3i& file_faces) {
  nlohmann::json positions = nlohmann::json::array(), triangles = nlohmann::json::array();
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
    for (int k = 0; k < 3; ++k) positions.push_back(mesh.V(i, k));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) triangles.push_back(mesh.F(f, k));
  nlohmann::json out{{"vertices", mesh.V.rows()},
                     {"faces", mesh.F.rows()},
                     {"positions", positions},
                     {"triangles", triangles},
                     {"boundary_loops", mesh.topology.boundary_loops}};
  nlohmann::json reordered = nlohmann::json::object();
  for (Eigen::Index f = 0; f < mesh.F.rows() && f < file_faces.rows(); ++f)
    if (mesh.F.row(f) != file_faces.row(f))
      reordered[std::to_string(f)] = {file_faces(f, 0), file_faces(f, 1), file_faces(f, 2)};
  if (!reordered.empty()) out["file_triangles"] = reordered;
  return out.dump();
}

namespace {

// "[[u0,v0],[u1,v1],...]" with shortest round-trip numbers (exact when read
// back), written directly: a json array of arrays costs 10x more at 100k vertices.
std::string uv_array(const MatrixX2d& uv) {
  std::string out;
  out.reserve(static_cast<size_t>(uv.rows()) * 48 + 2);
  out += '[';
  char buf[64];
  for (Eigen::Index i = 0; i < uv.rows(); ++i) {
    out += i ? ",[" : "[";
    for (int k = 0; k < 2; ++k) {
      const double x = std::isfinite(uv(i, k)) ? uv(i, k) : 0.0;  // JSON has no NaN; the solver refuses them anyway
      out.append(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
      out += k ? ']' : ',';
    }
  }
  out += ']';
  return out;
}

struct Figures {
  int flipped = 0;
  double angle_mean = 0;  // area-weighted over finite values, as summarize_distortion's angle_distortion.mean
  double area_mean = 0;   // likewise for area_distortion
};

double weighted_mean(const Eigen::VectorXd& x, const Eigen::VectorXd& w) {
  double sum = 0, wsum = 0;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i])) continue;
    sum += w[i] * x[i];
    wsum += w[i];
  }
  return wsum > 0 ? sum / wsum : 0.0;
}

// The two figures the page shows, without the rest of summarize_distortion
// (its edge statistics cost more than the update itself on large meshes).
Figures figures(const Mesh& mesh, const FaceFrames& frames, const MatrixX2d& uv) {
  const FaceDistortion d = face_distortion(frames, mesh.F, uv);
  Figures f;
  for (const bool flipped : d.flipped) f.flipped += flipped ? 1 : 0;
  f.angle_mean = weighted_mean(d.angle, d.area_3d);
  f.area_mean = weighted_mean(d.area, d.area_3d);
  return f;
}

nlohmann::json answer_json_without_figures(const SolveAnswer& a) {
  nlohmann::json out{{"uv", nullptr}, {"update_ms", a.update_ms}, {"path", a.path}, {"factorizations", a.factorizations}};
  if (!a.pins.empty()) {
    nlohmann::json pins = nlohmann::json::array();
    for (const FixedVertex& p : a.pins) pins.push_back({p.vertex, p.uv.x(), p.uv.y()});
    out["pins"] = pins;
  }
  return out;
}

nlohmann::json answer_json(const Mesh& mesh, const FaceFrames& frames, const SolveAnswer& a) {
  const Figures d = figures(mesh, frames, a.uv);
  nlohmann::json out = answer_json_without_figures(a);
  out["flipped_triangles"] = d.flipped;
  out["angle_distortion_mean"] = d.angle_mean;
  out["area_distortion_mean"] = d.area_mean;
  return out;
}

}  // namespace

std::string solve_api_header(const Mesh& mesh, const FaceFrames& frames, const SolveAnswer& a, bool flips_only) {
  nlohmann::json out;
  if (flips_only) {
    out = answer_json_without_figures(a);
    out["flipped_triangles"] = count_flipped(frames, mesh.F, a.uv);
  } else {
    out = answer_json(mesh, frames, a);
  }
  out.erase("uv");
  return out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string uv_binary(const MatrixX2d& uv, bool float32) {
  static_assert(sizeof(double) == 8 && sizeof(float) == 4, "float64 and float32 expected");
  const int width = float32 ? 4 : 8;
  std::string out(static_cast<size_t>(uv.rows()) * 2 * width, '\0');
  char* p = out.data();
  for (Eigen::Index i = 0; i < uv.rows(); ++i)
    for (int k = 0; k < 2; ++k, p += width) {
      const double x = std::isfinite(uv(i, k)) ? uv(i, k) : 0.0;
      std::uint64_t bits = 0;
      if (float32) {
        const float f = static_cast<float>(x);
        std::uint32_t b32;
        std::memcpy(&b32, &f, 4);
        bits = b32;
      } else {
        std::memcpy(&bits, &x, 8);
      }
      for (int b = 0; b < width; ++b) p[b] = static_cast<char>((bits >> (8 * b)) & 0xff);  // little-endian whatever the host
    }
  return out;
}

std::string solve_api_json(const Mesh& mesh, const FaceFrames& frames, const SolveAnswer& a,
                           const nlohmann::json& extra) {
  nlohmann::json out = answer_json(mesh, frames, a);
  for (const auto& item : extra.items()) out[item.key()] = item.value();
  // The UVs replace the placeholder (keys are sorted: "uv" is last).
  std::string text = out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  const std::string placeholder = "\"uv\":null";
  text.replace(text.rfind(placeholder), placeholder.size(), "\"uv\":" + uv_array(a.uv));
  return text;
}

std::string error_api_json(const std::string& message) {
  // A message may quote bytes of the request: never fail on invalid UTF-8.
  return nlohmann::json{{"error", message}}.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace intrinsic::app
