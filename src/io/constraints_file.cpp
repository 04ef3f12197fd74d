// The JSON constraint file (paper section 4.1 as a file format): strict
// parsing, every message names the file and the JSON path of the offending
// element, so a typo in a 200-point file is found at once.
#include <cmath>
#include <nlohmann/json.hpp>

#include "intrinsic/io.h"
#include "intrinsic/constraints.h"
#include "intrinsic/error.h"
#include "io/text_file.h"

namespace intrinsic {
namespace {

using nlohmann::json;

struct Parser {
  std::string name;

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw_input(name + ": " + where + ": " + what);
  }

  void only_keys(const json& j, const std::string& where, std::initializer_list<const char*> allowed) const {
    if (!j.is_object()) fail(where, "expected an object, found " + std::string(j.type_name()));
    for (auto it = j.begin(); it != j.end(); ++it) {
      bool ok = false;
      for (const char* k : allowed) ok = ok || it.key() == k;
      if (!ok) fail(where, "unknown key '" + it.key() + "'");
    }
  }

  double number(const json& j, const std::string& where) const {
    if (!j.is_number()) fail(where, "expected a number, found " + std::string(j.type_name()));
    const double x = j.get<double>();
    if (!std::isfinite(x)) fail(where, "non-finite value");
    return x;
  }

  int index(const json& j, const std::string& where) const {
    if (!j.is_number_integer()) fail(where, "expected an integer index, found " + j.dump());
    const long long i = j.get<long long>();
    if (i < 0 || i > 2'000'000'000) fail(where, "index " + std::to_string(i) + " is out of range");
    return static_cast<int>(i);
  }

  Eigen::Vector2d uv(const json& j, const std::string& where) const {
    if (!j.is_array() || j.size() != 2) fail(where, "expected [u, v]");
    return {number(j[0], where + "[0]"), number(j[1], where + "[1]")};
  }

  // A surface point; `with_uv` for entries of "points" (which need "uv").
  SurfacePoint point(const json& j, const std::string& where, bool with_uv, Eigen::Vector2d* target) const {
    if (with_uv) only_keys(j, where, {"face", "bary", "vertex", "uv"});
    else only_keys(j, where, {"face", "bary", "vertex"});
    SurfacePoint p;
    const bool has_vertex = j.contains("vertex"), has_face = j.contains("face");
    if (has_vertex == has_face) fail(where, "give either \"vertex\" or \"face\" with \"bary\"");
    if (has_vertex) {
      if (j.contains("bary")) fail(where, "\"bary\" goes with \"face\", not \"vertex\"");
      p.vertex = index(j["vertex"], where + ".vertex");
    } else {
      p.face = index(j["face"], where + ".face");
      if (!j.contains("bary")) fail(where, "\"face\" needs \"bary\": [b1, b2, b3]");
      const json& b = j["bary"];
      if (!b.is_array() || b.size() != 3) fail(where + ".bary", "expected [b1, b2, b3]");
      for (int k = 0; k < 3; ++k) p.bary[k] = number(b[k], where + ".bary[" + std::to_string(k) + "]");
    }
    if (with_uv) {
      if (!j.contains("uv")) fail(where, "missing \"uv\": [u, v]");
      *target = uv(j["uv"], where + ".uv");
    }
    return p;
  }

  Constraints parse(const json& root) const {
    only_keys(root, "top level", {"points", "lines"});
    Constraints c;
    if (root.contains("points")) {
      const json& pts = root["points"];
      if (!pts.is_array()) fail("points", "expected an array");
      for (size_t i = 0; i < pts.size(); ++i) {
        const std::string where = "points[" + std::to_string(i) + "]";
        PointConstraint pc;
        pc.point = point(pts[i], where, true, &pc.uv);
        pc.label = where;
        c.points.push_back(pc);
      }
    }
    if (root.contains("lines")) {
      const json& lines = root["lines"];
      if (!lines.is_array()) fail("lines", "expected an array");
      for (size_t i = 0; i < lines.size(); ++i) {
        const std::string where = "lines[" + std::to_string(i) + "]";
        const json& l = lines[i];
        only_keys(l, where, {"path", "to"});
        if (!l.contains("path") || !l["path"].is_array()) fail(where, "missing \"path\": [surface points]");
        if (!l.contains("to") || !l["to"].is_array()) fail(where, "missing \"to\": [[u0, v0], [u1, v1]]");
        LineConstraint lc;
        lc.label = where;
        for (size_t k = 0; k < l["path"].size(); ++k)
          lc.path.push_back(point(l["path"][k], where + ".path[" + std::to_string(k) + "]", false, nullptr));
        for (size_t k = 0; k < l["to"].size(); ++k)
          lc.to.push_back(uv(l["to"][k], where + ".to[" + std::to_string(k) + "]"));
        c.lines.push_back(lc);
      }
    }
    return c;
  }
};

}  // namespace

Constraints parse_constraints_json(const std::string& text, const std::string& name) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {
    // nlohmann's message carries the line and column of a syntax error, or
    // the offending literal for a number that overflows a double.
    throw_input(name + ": malformed JSON: " + e.what());
  }
  return Parser{name}.parse(root);
}

Constraints read_constraints_file(const std::string& path) {
  return parse_constraints_json(detail::read_text_file(path, "constraint file"), path);
}

void match_face_corners(Constraints& constraints, const MatrixX3i& file_faces, const Mesh& mesh) {
  auto fix = [&](SurfacePoint& p) {
    if (p.face < 0 || p.face >= mesh.F.rows() || p.face >= file_faces.rows()) return;  // resolve reports it
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d)
        if (mesh.F(p.face, d) == file_faces(p.face, c)) b[d] = p.bary[c];
    p.bary = b;
  };
  for (PointConstraint& pc : constraints.points) fix(pc.point);
  for (LineConstraint& lc : constraints.lines)
    for (SurfacePoint& p : lc.path) fix(p);
}

}  // namespace intrinsic
