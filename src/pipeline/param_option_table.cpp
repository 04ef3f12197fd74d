// The param job's options, each declared once with the request field it sets
// (param_option_table.h); docs/cli.md "intrinsic param" explains them.
#include "intrinsic/param_option_table.h"

#include "option_rows.h"

namespace intrinsic {
// Named, not anonymous: the unity build compiles both tables in one unit.
namespace param_rows {

using option_rows::spec;

// The request being built, with what is combined only once every option is
// in: the blend, the boundary (a shape or a file), the pins' text, the
// optimizer and its interval.
struct Draft {
  ParamRequest request;
  Method method = Method::Conformal;
  std::optional<double> lambda, mu;
  std::string boundary = choice_name(ParamOptions().boundary);
  std::vector<std::string> pins;
  std::optional<LambdaEnergy> optimize_lambda;
  std::optional<BoundaryEnergy> optimize_boundary;
  RealPair lambda_range{OptimalLambdaOptions().lo, OptimalLambdaOptions().hi};
};

using Rows = option_rows::RowsOf<Draft>;
using Row = Rows::R;

const char* const kMap = "Map";
const char* const kSolve = "Solve";
const char* const kOptimizers = "Optimizers";

ParamOptions& opt(Draft& d) { return d.request.options; }

// The weights, the boundary and how it is laid out.
void add_map_rows(std::vector<Row>& t) {
  Rows::add_blend_rows(t, kMap);
  Row boundary = Rows::choice_or_path<BoundaryShape>(
      spec("boundary", kMap,
           "circle | square | natural (natural conformal map, no fixed boundary; conformal only) | FILE with lines "
           "'vertex u v'"),
      [](Draft& d) -> std::string& { return d.boundary; });
  t.push_back(boundary);
  Row pins = Rows::repeated_text(spec("pins", kMap,
                                      "Natural boundary: keep vertex V exactly at (U,V); repeatable, at least two, "
                                      "any vertex, no rescaling. Default: the two outer-loop vertices farthest apart "
                                      "in 3D, at their 3D distance"),
                                 [](Draft& d) -> std::vector<std::string>& { return d.pins; });
  pins.spec.aliases = {"pin"};
  pins.spec.value_name = "V:U,V";
  t.push_back(pins);
  t.push_back(Rows::choice<Spacing>(spec("spacing", kMap, "Boundary spacing: arclength | uniform"),
                                    [](Draft& d) -> Spacing& { return opt(d).spacing; }));
  t.push_back(Rows::choice<ScaleMode>(
      spec("scale", kMap,
           "unit: fit [0,1]^2 | surface: parameter area = 3D area (natural: pins at their 3D distance)"),
      [](Draft& d) -> ScaleMode& { return opt(d).scale; }));
  t.push_back(Rows::choice<HoleRule>(
      spec("holes", kMap,
           "Holes without given positions, fixed-boundary modes: fill (temporary fan) | free | natural (natural "
           "conformal condition on hole loops; see docs/holes.md). Natural boundary: every loop is natural"),
      [](Draft& d) -> HoleRule& { return opt(d).holes; }));
}

// The solver, its bound, constraints and which part of the input.
void add_solve_rows(std::vector<Row>& t) {
  Row solver = Rows::choice<SolverKind>(spec("solver", kSolve, "The sparse solver (auto: the fastest this build has)"),
                                        [](Draft& d) -> SolverKind& { return opt(d).solver; });
  // A listed name this build lacks (SuiteSparse not found) is refused too.
  solver.set = [](Draft& d, const OptionValue& v) { opt(d).solver = parse_solver(std::get<std::string>(v), ""); };
  t.push_back(solver);
  t.push_back(Rows::real(spec("max_residual", kSolve, "Fail (exit 3) if the relative residual exceeds this"),
                         [](Draft& d) -> double& { return opt(d).max_residual; }));
  t.push_back(Rows::path(spec("constraints", kSolve,
                              "JSON file of point and line constraints; targets are in output coordinates (see "
                              "docs/formats.md)"),
                         [](Draft& d) -> std::string& { return d.request.constraints_file; }));
  t.push_back(Rows::boolean(spec("largest_component", kSolve,
                                 "Keep only the component with the most faces (vertex numbering unchanged); otherwise "
                                 "every component becomes its own chart"),
                            [](Draft& d) -> bool& { return d.request.largest_component; }));
  t.push_back(Rows::integer<std::int64_t>(spec("max_vertices", kSolve, "Refuse inputs with more vertices", 1),
                                          [](Draft& d) -> std::int64_t& { return d.request.read.max_vertices; }));
}

// Section 5: the optimal lambda and boundary optimization.
void add_optimizer_rows(std::vector<Row>& t) {
  t.push_back(Rows::optional_choice<LambdaEnergy>(
      spec("optimize_lambda", kOptimizers,
           "Blend lambda*conformal + (1-lambda)*authalic with the lambda minimising edge or area distortion"),
      [](Draft& d) -> std::optional<LambdaEnergy>& { return d.optimize_lambda; }));
  Row range = Rows::real_pair(spec("lambda_range", kOptimizers, "Interval searched by --optimize-lambda, as LO,HI"),
                              [](Draft& d) -> RealPair& { return d.lambda_range; });
  range.spec.value_name = "LO,HI";
  t.push_back(range);
  t.push_back(Rows::optional_choice<BoundaryEnergy>(
      spec("optimize_boundary", kOptimizers,
           "Move the boundary to minimise edge, area or (symmetric) dirichlet distortion"),
      [](Draft& d) -> std::optional<BoundaryEnergy>& { return d.optimize_boundary; }));
  t.push_back(Rows::integer<int>(spec("iterations", kOptimizers, "Boundary optimization: iteration limit", 0),
                                 [](Draft& d) -> int& { return d.request.boundary_optimization.max_iterations; }));
  t.push_back(Rows::real(spec("tolerance", kOptimizers, "Boundary optimization: stop below this relative decrease", 0.0),
                         [](Draft& d) -> double& { return d.request.boundary_optimization.tolerance; }));
  t.push_back(Rows::choice<GradientRoute>(spec("gradient", kOptimizers, "Boundary optimization gradient: adjoint | responses"),
                                          [](Draft& d) -> GradientRoute& { return d.request.boundary_optimization.route; }));
  t.push_back(Rows::choice<Descent>(spec("descent", kOptimizers, "Boundary optimization descent: lbfgs | gradient"),
                                    [](Draft& d) -> Descent& { return d.request.boundary_optimization.descent; }));
}

const std::vector<Row>& rows() {
  static const std::vector<Row> table = [] {
    std::vector<Row> t;
    add_map_rows(t);
    add_solve_rows(t);
    add_optimizer_rows(t);
    return t;
  }();
  return table;
}

// The optimizer, and the blend it would otherwise be given.
void finish_optimizer(Draft& d, const std::vector<std::string>& keys, OptionSpelling spelling) {
  const auto label = [&](const char* key) { return option_label(key, spelling); };
  ParamRequest& r = d.request;
  if (d.optimize_lambda && d.optimize_boundary)
    throw_usage(label("optimize_lambda") + " and " + label("optimize_boundary") + " cannot be combined");
  const bool blend_given = d.method != Method::Conformal || option_rows::was_given(keys, "lambda") ||
                           option_rows::was_given(keys, "mu");
  if (d.optimize_lambda && blend_given)
    throw_usage(label("optimize_lambda") + " chooses the blend itself; do not give " + label("method") + ", " +
                label("lambda") + " or " + label("mu"));
  if (d.optimize_lambda) {
    r.optimizer = ChartOptimizer::OptimalLambda;
    r.optimal_lambda.energy = *d.optimize_lambda;
  } else if (d.optimize_boundary) {
    r.optimizer = ChartOptimizer::OptimizeBoundary;
    r.boundary_optimization.energy = *d.optimize_boundary;
  }
  r.optimal_lambda.lo = d.lambda_range[0];
  r.optimal_lambda.hi = d.lambda_range[1];
}

}  // namespace param_rows

const std::vector<OptionSpec>& param_option_table() {
  static const std::vector<OptionSpec> specs = option_rows::specs_of(param_rows::rows());
  return specs;
}

ParamRequest param_request(const GivenOptions& given, OptionSpelling spelling) {
  param_rows::Draft d;
  const std::vector<std::string> keys = option_rows::apply_given(param_rows::rows(), given, spelling, d);
  ParamRequest& r = d.request;
  r.spelling = spelling;
  for (const std::string& p : d.pins) r.options.pins.push_back(parse_pin(p, spelling));
  param_rows::finish_optimizer(d, keys, spelling);
  r.options.weights = weight_options(d.method, d.lambda, d.mu, spelling);
  if (is_choice<BoundaryShape>(d.boundary)) {
    r.options.boundary = parse_choice<BoundaryShape>(d.boundary, "");
  } else {
    r.options.boundary = BoundaryShape::Given;  // a file of positions, read once the mesh is known
    r.boundary_file = d.boundary;
  }
  r.read.max_faces = faces_for_vertices(r.read.max_vertices);
  check_param_request(r);
  return r;
}

}  // namespace intrinsic
