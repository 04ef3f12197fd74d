// The `param` pipeline shared by the command line and the Python module
// (param_job.h): moved unchanged from cmd_param.cpp, plus constraints given in
// memory.
#include "param_job.h"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "intrinsic/io.h"
#include "intrinsic/boundary_optimization.h"
#include "intrinsic/charts.h"
#include "intrinsic/error.h"
#include "intrinsic/optimal_lambda.h"
#include "intrinsic/parameterizer.h"
#include "report.h"

namespace intrinsic::app {
namespace {

Solved solve_optimal_lambda(const ParamArgs& a, const Mesh& mesh, const ParamOptions& options) {
  OptimalLambdaOptions lo;
  lo.base = options;
  lo.energy = parse_lambda_energy(a.optimize_lambda);
  lo.lo = a.lambda_range.at(0);
  lo.hi = a.lambda_range.at(1);
  const OptimalLambdaResult best = optimal_lambda(mesh, lo);
  return {best.map, optimal_lambda_json(best, lo), nullptr};
}

Solved solve_boundary_optimization(const ParamArgs& a, const Mesh& mesh, const ParamOptions& options) {
  BoundaryOptimizationOptions bo;
  bo.base = options;
  bo.energy = parse_boundary_energy(a.optimize_boundary);
  bo.route = parse_gradient_route(a.gradient);
  bo.descent = parse_descent(a.descent);
  bo.max_iterations = a.iterations;
  bo.tolerance = a.tolerance;
  const bool tty = isatty(fileno(stderr));
  if (!a.quiet)
    bo.progress = [tty](int it, double e) {
      std::cerr << (tty ? "\r" : "") << "boundary optimization: iteration " << it << ", energy " << e
                << (tty ? "   " : "\n") << std::flush;
    };
  const BoundaryOptimizationResult best = optimize_boundary(mesh, bo);
  if (!a.quiet && tty && best.iterations > 0) std::cerr << "\n";
  return {best.map, nullptr, boundary_optimization_json(best, bo)};
}

}  // namespace

FixedVertex parse_pin(const std::string& text) {
  const auto bad = [&]() -> FixedVertex {
    throw_usage("--pin '" + text + "': expected VERTEX:U,V, e.g. --pin 12:0.5,0");
  };
  const size_t colon = text.find(':'), comma = text.find(',', colon == std::string::npos ? 0 : colon);
  if (colon == std::string::npos || comma == std::string::npos) return bad();
  FixedVertex p{};
  const char* b = text.data();
  auto [end, ec] = std::from_chars(b, b + colon, p.vertex);
  if (ec != std::errc() || end != b + colon || colon == 0) return bad();
  auto number = [&](size_t from, size_t to, double& x) {
    // strtod, not from_chars<double>: the latter is missing from older libstdc++
    const std::string part = text.substr(from, to - from);
    char* stop = nullptr;
    x = std::strtod(part.c_str(), &stop);
    return !part.empty() && !std::isspace(static_cast<unsigned char>(part[0])) && stop == part.c_str() + part.size() &&
           std::isfinite(x);
  };
  if (!number(colon + 1, comma, p.uv.x()) || !number(comma + 1, text.size(), p.uv.y())) return bad();
  return p;
}

ParamOptions to_options(const ParamArgs& a, int num_vertices) {
  ParamOptions o;
  o.weights = a.weights->options();
  if (a.boundary == "circle") o.boundary = BoundaryShape::Circle;
  else if (a.boundary == "square") o.boundary = BoundaryShape::Square;
  else if (a.boundary == "natural") o.boundary = BoundaryShape::Natural;
  else {
    o.boundary = BoundaryShape::Given;
    o.given = read_boundary_file(a.boundary, num_vertices);
  }
  o.spacing = a.spacing == "uniform" ? Spacing::Uniform : Spacing::ArcLength;
  o.scale = a.scale == "surface" ? ScaleMode::Surface : ScaleMode::Unit;
  o.holes = a.holes == "free" ? HoleRule::Free : a.holes == "natural" ? HoleRule::Natural : HoleRule::Fill;
  for (const std::string& p : a.pins) o.pins.push_back(parse_pin(p));
  if (!o.pins.empty() && o.boundary != BoundaryShape::Natural) throw_usage("--pin applies to --boundary natural only");
  if (o.pins.size() == 1) throw_usage("--pin needs at least two pins (translation, rotation and scale)");
  o.solver = parse_solver(a.solver);
  o.max_residual = a.max_residual;
  return o;
}

void check_args(const ParamArgs& a) {
  parse_method(a.weights->method);
  parse_solver(a.solver);
  if (!(a.max_residual > 0)) throw_usage("--max-residual must be a positive number");
  for (const std::string& p : a.pins) parse_pin(p);  // syntax first: a usage error whatever the file
  if (a.has_constraints() && (!a.optimize_lambda.empty() || !a.optimize_boundary.empty()))
    throw_usage("--constraints cannot be combined with --optimize-lambda or --optimize-boundary");
  if (!a.optimize_lambda.empty() && !a.optimize_boundary.empty())
    throw_usage("--optimize-lambda and --optimize-boundary cannot be combined");
  if (!a.optimize_lambda.empty() && (a.weights->method != "conformal" || a.weights->lambda_set || a.weights->mu_set))
    throw_usage("--optimize-lambda chooses the blend itself; do not give --method, --lambda or --mu");
}

Mesh validated_mesh(const ParamArgs& a, const MeshData& data) {
  ValidateOptions vo;
  vo.allow_several_components = true;
  vo.allow_closed = a.largest_component;  // a closed small piece may be dropped; the kept one is checked later
  Mesh mesh = make_mesh(data, vo);
  if (a.largest_component && mesh.topology.num_components > 1) {
    const int reoriented = mesh.validation.reoriented_faces;
    mesh = make_mesh(component_data(mesh, largest_component(mesh)));
    mesh.validation.reoriented_faces = reoriented;
  }
  return mesh;
}

Constraints load_constraints(const ParamArgs& a, const MeshData& data, const Mesh& mesh) {
  Constraints c = a.given_constraints ? *a.given_constraints : read_constraints_file(a.constraints);
  match_face_corners(c, data.F, mesh);
  return c;
}

Solved solve(const ParamArgs& a, const Mesh& mesh, const MeshData& data, const ParamOptions& options) {
  if (mesh.topology.num_components > 1) {
    if (!a.optimize_lambda.empty() || !a.optimize_boundary.empty() || a.has_constraints())
      throw_usage("--optimize-lambda, --optimize-boundary and --constraints take a single component; "
                  "use --largest-component");
    return {parameterize_charts(mesh, options), nullptr, nullptr};
  }
  if (!a.optimize_lambda.empty()) return solve_optimal_lambda(a, mesh, options);
  if (!a.optimize_boundary.empty()) return solve_boundary_optimization(a, mesh, options);
  Parameterizer parameterizer(mesh, options);
  if (a.has_constraints()) parameterizer.set_constraints(load_constraints(a, data, mesh));
  return {parameterizer.solve(), nullptr, nullptr};
}

nlohmann::json build_report(const ParamArgs& a, const Mesh& mesh, const Solved& s, const DistortionSummary& d) {
  nlohmann::json report = mesh_json(mesh);
  report["output"] = a.output;
  add_solution(report, s.map, a.boundary);
  if (!s.optimal_lambda.is_null()) {
    report["method"] = "optimal-lambda";
    report["optimal_lambda"] = s.optimal_lambda;
  }
  if (!s.boundary_optimization.is_null()) report["boundary_optimization"] = s.boundary_optimization;
  if (!a.constraints.empty()) report["constraints_file"] = a.constraints;
  if (a.has_constraints()) report["constraints"] = constraints_json(s.map.constraints);
  // The scale the map came out at: parameter area over 3D area.
  report["area_ratio"] = std::abs(parameter_area(mesh.F, s.map.UV)) / surface_area(mesh.V, mesh.F);
  add_distortion(report, d);
  return report;
}

}  // namespace intrinsic::app
