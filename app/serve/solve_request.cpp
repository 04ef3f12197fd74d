// Parsing and checking of `POST /api/solve` bodies (solve_request.h).
#include "solve_request.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "intrinsic/io.h"
#include "intrinsic/error.h"
#include "intrinsic/intrinsic.h"
#include "intrinsic/param_option_table.h"

namespace intrinsic::app {
namespace {

using nlohmann::json;

double finite_number(const json& j, const std::string& where) {
  if (!j.is_number()) throw_usage(where + ": expected a number");
  const double x = j.get<double>();
  if (!std::isfinite(x)) throw_usage(where + ": not a finite number");
  return x;
}

std::string text(const json& j, const std::string& where) {
  if (!j.is_string()) throw_usage(where + ": expected a string");
  return j.get<std::string>();
}

// [[vertex, u, v], ...] with vertices in range and not repeated.
std::vector<FixedVertex> vertex_positions(const json& j, const std::string& key, int n) {
  if (!j.is_array()) throw_usage(key + ": expected an array of [vertex, u, v]");
  std::vector<FixedVertex> out;
  std::vector<char> seen(n, 0);
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string where = key + "[" + std::to_string(i) + "]";
    const json& e = j[i];
    if (!e.is_array() || e.size() != 3) throw_usage(where + ": expected [vertex, u, v]");
    if (!e[0].is_number_integer()) throw_usage(where + ": vertex must be an integer");
    const long long v = e[0].get<long long>();
    if (v < 0 || v >= n)
      throw_usage(where + ": vertex " + std::to_string(v) + " out of range (the mesh has " + std::to_string(n) +
                  " vertices)");
    if (seen[v]) throw_usage(where + ": vertex " + std::to_string(v) + " listed twice");
    seen[v] = 1;
    FixedVertex fv{static_cast<int>(v), {finite_number(e[1], where + "[1]"), finite_number(e[2], where + "[2]")}};
    out.push_back(fv);
  }
  return out;
}

// The blend, checked as `param` checks it (param_option_table.h), its
// messages naming the request's keys.
WeightOptions read_weights(const json& body) {
  GivenOptions given;
  if (body.contains("method")) given.emplace_back("method", text(body["method"], "method"));
  for (const char* key : {"lambda", "mu"})
    if (body.contains(key)) given.emplace_back(key, finite_number(body[key], key));
  return param_request(given, OptionSpelling::Keyword).options.weights;
}

// Nesting deeper than any valid request is refused before parsing, so no
// recursive walk (dump, destruction) can exhaust the stack.
void check_depth(const std::string& s, int max_depth) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (const char c : s) {
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) throw_usage("request body nested deeper than " + std::to_string(max_depth));
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

}  // namespace

nlohmann::json parse_request_body(const std::string& body_text) {
  check_depth(body_text, 32);
  json body = json::parse(body_text, nullptr, false);
  if (body.is_discarded()) throw_usage("request body is not valid JSON");
  if (!body.is_object()) throw_usage("request body must be a JSON object");
  return body;
}

SolveRequest solve_request_from(const nlohmann::json& body, const Mesh& mesh, const MatrixX3i& file_faces,
                                const std::vector<std::string>& extra_keys) {
  static const char* known[] = {"method", "lambda", "mu", "boundary", "pins", "constraints", "moves"};
  for (const auto& item : body.items())
    if (std::find(std::begin(known), std::end(known), item.key()) == std::end(known) &&
        std::find(extra_keys.begin(), extra_keys.end(), item.key()) == extra_keys.end())
      throw_usage("unknown key '" + item.key() + "'");
  SolveRequest r;
  r.weights = read_weights(body);
  if (body.contains("boundary")) r.boundary = parse_choice<BoundaryShape>(text(body["boundary"], "boundary"), "boundary");
  const int n = static_cast<int>(mesh.V.rows());
  if (body.contains("pins")) r.pins = vertex_positions(body["pins"], "pins", n);
  if (body.contains("moves")) r.moves = vertex_positions(body["moves"], "moves", n);
  if (!r.pins.empty() && r.boundary != BoundaryShape::Natural) throw_usage("pins apply to boundary natural only (use moves)");
  if (r.pins.size() == 1) throw_usage("pins: at least two are needed");
  if (!r.moves.empty() && r.boundary == BoundaryShape::Natural) throw_usage("moves apply to a fixed boundary (use pins)");
  if (body.contains("constraints") && !body["constraints"].is_null()) {
    r.constraints_key = body["constraints"].dump();
    r.constraints = parse_constraints_json(r.constraints_key, "constraints");
    match_face_corners(r.constraints, file_faces, mesh);
  }
  return r;
}

SolveRequest parse_solve_request(const std::string& body_text, const Mesh& mesh, const MatrixX3i& file_faces) {
  return solve_request_from(parse_request_body(body_text), mesh, file_faces, {});
}

}  // namespace intrinsic::app
