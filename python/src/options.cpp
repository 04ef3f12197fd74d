// Python keyword options -> the library's typed requests (pipeline.h):
// parameterize(V, F, **options) and Parameterizer(...) fill a ParamRequest;
// atlas()'s keywords are values for the library's option table
// (to_option_value, atlas_option_table.h). Choices go through the name tables
// (intrinsic/choice.h) with the keyword as the label, so a bad value reads
// "method: 'foo' is not one of conformal, ...", and the library's own checks
// name keywords (OptionSpelling::Keyword), never command-line flags.
#include <cmath>
#include <iostream>

#include "common.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "intrinsic/intrinsic.h"

namespace intrinsic::python {
namespace {

py::object pop(py::dict& o, const char* key) { return o.attr("pop")(key, py::none()); }

template <class T>
T pop_number(py::dict& o, const char* key, T fallback) {
  const py::object v = pop(o, key);
  if (v.is_none()) return fallback;
  try {
    return v.cast<T>();
  } catch (const py::cast_error&) {
    throw_usage(std::string(key) + ": expected a number, got " + py::str(py::type::of(v).attr("__name__")).cast<std::string>());
  }
}

// (vertex, u, v) triples, or "V:U,V" text as batch runs pass --pin.
std::vector<FixedVertex> to_pins(const py::handle& pins) {
  std::vector<FixedVertex> out;
  for (const py::handle p : pins) {
    if (py::isinstance<py::str>(p)) out.push_back(parse_pin(p.cast<std::string>(), OptionSpelling::Keyword));
    else out.push_back(to_fixed(py::make_tuple(p), "pins").front());
  }
  return out;
}

void set_constraints(ParamRequest& r, const py::handle& c) {
  if (c.is_none()) return;
  if (py::isinstance<py::dict>(c)) {
    const std::string text = py::str(py::module_::import("json").attr("dumps")(c)).cast<std::string>();
    r.constraints = parse_constraints_json(text, "constraints");
  } else {
    r.constraints_file = to_path(c);  // read by the pipeline, as --constraints FILE
  }
}

// Boundary optimization's progress lines on stderr when verbose=True (the
// library never prints).
void set_progress(BoundaryOptimizationOptions& bo) {
  bo.progress = [](int it, double e) {
    std::cerr << "boundary optimization: iteration " << it << ", energy " << e << "\n" << std::flush;
  };
}

void set_optimizers(ParamRequest& r, py::dict& o, bool verbose) {
  const py::object lambda = pop(o, "optimize_lambda"), boundary = pop(o, "optimize_boundary");
  if (!lambda.is_none() && !boundary.is_none()) throw_usage("optimize_lambda and optimize_boundary cannot be combined");
  if (!lambda.is_none()) {
    r.optimizer = ChartOptimizer::OptimalLambda;
    r.optimal_lambda.energy = to_choice<LambdaEnergy>(lambda, "optimize_lambda");
  } else if (!boundary.is_none()) {
    r.optimizer = ChartOptimizer::OptimizeBoundary;
    r.boundary_optimization.energy = to_choice<BoundaryEnergy>(boundary, "optimize_boundary");
  }
  const py::object range = pop(o, "lambda_range");
  if (!range.is_none()) {
    const auto lohi = range.cast<std::vector<double>>();
    if (lohi.size() != 2) throw_usage("lambda_range: expected (lo, hi)");
    r.optimal_lambda.lo = lohi[0];
    r.optimal_lambda.hi = lohi[1];
  }
  BoundaryOptimizationOptions& bo = r.boundary_optimization;
  bo.max_iterations = pop_number<int>(o, "iterations", 200);
  if (bo.max_iterations < 0) throw_usage("iterations: must be >= 0, got " + std::to_string(bo.max_iterations));
  bo.tolerance = pop_number<double>(o, "tolerance", 1e-6);
  if (!(bo.tolerance >= 0)) throw_usage("tolerance: must be >= 0, got " + short_number(bo.tolerance));
  const py::object route = pop(o, "gradient"), descent = pop(o, "descent");
  if (!route.is_none()) bo.route = to_choice<GradientRoute>(route, "gradient");
  if (!descent.is_none()) bo.descent = to_choice<Descent>(descent, "descent");
  if (verbose) set_progress(bo);
}

void set_boundary(ParamRequest& r, const py::object& b) {
  if (b.is_none()) return;
  if (!py::isinstance<py::str>(b) && !py::hasattr(b, "__fspath__")) {
    r.options.boundary = to_choice<BoundaryShape>(b, "boundary");
    return;
  }
  const std::string text = to_path(b);
  if (is_choice<BoundaryShape>(text)) {
    r.options.boundary = parse_choice<BoundaryShape>(text, "boundary");
  } else {
    r.options.boundary = BoundaryShape::Given;  // a file of positions
    r.boundary_file = text;
  }
}

}  // namespace

WeightOptions pop_weights(py::dict& o) {
  const py::object m = pop(o, "method");
  const Method method = m.is_none() ? Method::Conformal : to_choice<Method>(m, "method");
  std::optional<double> lambda, mu;
  for (const char* key : {"lambda", "lambda_", "lam"}) {
    const py::object v = pop(o, key);
    if (v.is_none()) continue;
    if (lambda) throw_usage("give lambda once (lam, lambda_ or 'lambda')");
    lambda = v.cast<double>();
  }
  const py::object u = pop(o, "mu");
  if (!u.is_none()) mu = u.cast<double>();
  return weight_options(method, lambda, mu, OptionSpelling::Keyword);
}

void check_no_options_left(const py::dict& o) {
  if (!o.empty()) throw_usage("unknown option '" + py::str(py::list(o.attr("keys")())[0]).cast<std::string>() + "'");
}

ParamRequest to_request(const py::dict& options, bool optimizers) {
  py::dict o = options.attr("copy")();
  ParamRequest r;
  r.spelling = OptionSpelling::Keyword;
  ParamOptions& p = r.options;
  p.weights = pop_weights(o);
  set_boundary(r, pop(o, "boundary"));
  if (const py::object v = pop(o, "spacing"); !v.is_none()) p.spacing = to_choice<Spacing>(v, "spacing");
  if (const py::object v = pop(o, "scale"); !v.is_none()) p.scale = to_choice<ScaleMode>(v, "scale");
  if (const py::object v = pop(o, "holes"); !v.is_none()) p.holes = to_choice<HoleRule>(v, "holes");
  if (const py::object v = pop(o, "solver"); !v.is_none()) {
    // A name is also checked against this build's solvers.
    p.solver = py::isinstance<py::str>(v) ? parse_solver(v.cast<std::string>(), "solver") : to_choice<SolverKind>(v, "solver");
  }
  const py::object pins = o.attr("pop")("pins", pop(o, "pin"));
  if (!pins.is_none()) p.pins = to_pins(pins);
  p.max_residual = pop_number<double>(o, "max_residual", p.max_residual);
  set_constraints(r, pop(o, "constraints"));
  r.largest_component = o.attr("pop")("largest_component", false).cast<bool>();
  r.read.max_vertices = pop_number<std::int64_t>(o, "max_vertices", r.read.max_vertices);
  if (r.read.max_vertices <= 0)
    throw_usage("max_vertices: must be > 0, got " + std::to_string(r.read.max_vertices));
  r.read.max_faces = faces_for_vertices(r.read.max_vertices);
  const bool verbose = o.attr("pop")("verbose", false).cast<bool>();
  if (optimizers) set_optimizers(r, o, verbose);
  check_no_options_left(o);
  check_param_request(r);
  return r;
}

}  // namespace intrinsic::python

namespace intrinsic::python {
namespace {

const char* type_word(OptionType t) {
  switch (t) {
    case OptionType::Bool: return "bool";
    case OptionType::Int: return "int";
    case OptionType::Real: return "float";
    case OptionType::Choice: return "choice";
    case OptionType::Path: return "path";
  }
  return "?";
}

py::object value_to_python(const OptionValue& v) {
  if (const bool* b = std::get_if<bool>(&v)) return py::bool_(*b);
  if (const std::int64_t* i = std::get_if<std::int64_t>(&v)) return py::int_(*i);
  if (const double* d = std::get_if<double>(&v)) return py::float_(*d);
  return py::str(std::get<std::string>(v));
}

py::object bound_to_python(double x) { return std::isfinite(x) ? py::object(py::float_(x)) : py::object(py::none()); }

}  // namespace

OptionValue to_option_value(const std::vector<OptionSpec>& table, const std::string& key, const py::handle& value) {
  const OptionSpec* s = find_option(table, key);
  if (!s) throw_usage("unknown option '" + key + "'");
  try {
    switch (s->type) {
      case OptionType::Bool: return value.cast<bool>();
      case OptionType::Int:
        if (py::isinstance<py::bool_>(value)) break;
        return value.cast<std::int64_t>();
      case OptionType::Real:
        if (py::isinstance<py::bool_>(value)) break;
        return value.cast<double>();
      case OptionType::Choice:
        // An enum value (intrinsic.AtlasScope.PER_MESH) gives its name.
        if (!py::isinstance<py::str>(value) && py::hasattr(value, "option")) return value.attr("option").cast<std::string>();
        return value.cast<std::string>();
      case OptionType::Path: return to_path(value);
    }
  } catch (const py::cast_error&) {
  }
  throw_usage(key + ": expected " + (s->type == OptionType::Choice ? "one of its names" : type_word(s->type)) +
              ", got " + py::str(py::type::of(value).attr("__name__")).cast<std::string>());
}

py::list table_to_python(const std::vector<OptionSpec>& table) {
  py::list out;
  for (const OptionSpec& s : table) {
    py::dict d;
    d["key"] = s.key;
    d["flag"] = s.flag;
    d["flag_negates"] = s.flag_negates;
    d["aliases"] = s.aliases;
    d["type"] = type_word(s.type);
    d["group"] = s.group;
    d["help"] = s.help;
    d["min"] = bound_to_python(s.min);
    d["max"] = bound_to_python(s.max);
    d["choices"] = s.choices;
    d["default"] = s.default_value ? value_to_python(*s.default_value) : py::object(py::none());
    out.append(d);
  }
  return out;
}

}  // namespace intrinsic::python
