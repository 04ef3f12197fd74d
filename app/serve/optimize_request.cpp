// Parsing and checking of the optimization endpoints' bodies (optimize_request.h).
#include "serve/optimize_request.h"

#include "intrinsic/error.h"
#include "intrinsic/intrinsic.h"

namespace intrinsic::app {
namespace {

using nlohmann::json;

std::string energy_name(const json& body) {
  if (!body.contains("energy")) return choice_name(LambdaEnergy::EdgeLength);  // edge, for either energy
  if (!body["energy"].is_string()) throw_usage("energy: expected a string");
  return body["energy"].get<std::string>();
}

void check_fixed_unconstrained(const SolveRequest& r, const std::string& what) {
  if (r.boundary == BoundaryShape::Natural) throw_usage(what + " starts from a fixed boundary (circle or square), not natural");
  if (!r.constraints.empty()) throw_usage(what + " takes no constraints");
}

}  // namespace

OptimalLambdaRequest parse_optimal_lambda_request(const std::string& text, const Mesh& mesh,
                                                  const MatrixX3i& file_faces) {
  const json body = parse_request_body(text);
  OptimalLambdaRequest r;
  r.solve = solve_request_from(body, mesh, file_faces, {"energy"});
  check_fixed_unconstrained(r.solve, "optimal lambda");
  const std::string e = energy_name(body);
  r.energy = parse_choice<LambdaEnergy>(e, "energy");
  return r;
}

OptimizeBoundaryRequest parse_optimize_boundary_request(const std::string& text, const Mesh& mesh,
                                                        const MatrixX3i& file_faces) {
  const json body = parse_request_body(text);
  OptimizeBoundaryRequest r;
  r.solve = solve_request_from(body, mesh, file_faces, {"energy", "max_iterations"});
  check_fixed_unconstrained(r.solve, "boundary optimization");
  const std::string e = energy_name(body);
  r.energy = parse_choice<BoundaryEnergy>(e, "energy");
  if (body.contains("max_iterations")) {
    const json& m = body["max_iterations"];
    if (!m.is_number_integer()) throw_usage("max_iterations: expected an integer");
    const long long k = m.get<long long>();
    if (k < 1 || k > 1000) throw_usage("max_iterations: expected 1..1000, not " + std::to_string(k));
    r.max_iterations = static_cast<int>(k);
  }
  return r;
}

}  // namespace intrinsic::app
