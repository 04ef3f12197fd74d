// Python keyword options -> the command line's ParamArgs (app/param_job.h),
// so that parameterize(V, F, **options) maps options exactly as
// `intrinsic param` does. Values the command line checks with CLI11 before
// running (IsMember) are checked here with CLI11's message.
#include <cmath>
#include <cstdio>
#include <set>

#include "common.h"
#include "intrinsic/io.h"
#include "intrinsic/constraints.h"
#include "intrinsic/error.h"

namespace intrinsic::python {
namespace {

// CLI11's IsMember message: "--spacing: foo not in {arclength,uniform}".
void check_member(const std::string& option, const std::string& value, const std::vector<std::string>& allowed) {
  for (const std::string& a : allowed)
    if (a == value) return;
  std::string set;
  for (const std::string& a : allowed) set += (set.empty() ? "" : ",") + a;
  throw_usage("--" + option + ": " + value + " not in {" + set + "}");
}

std::string pin_text(const py::handle& pin) {
  if (py::isinstance<py::str>(pin)) return pin.cast<std::string>();
  const std::vector<FixedVertex> one = to_fixed(py::make_tuple(pin), "pins");
  char buf[96];
  std::snprintf(buf, sizeof buf, "%d:%.17g,%.17g", one[0].vertex, one[0].uv.x(), one[0].uv.y());
  return buf;
}

void set_constraints(app::ParamArgs& a, const py::handle& c) {
  if (c.is_none()) return;
  if (py::isinstance<py::dict>(c)) {
    const std::string text = py::str(py::module_::import("json").attr("dumps")(c)).cast<std::string>();
    a.given_constraints = std::make_shared<const Constraints>(parse_constraints_json(text, "constraints"));
  } else {
    a.constraints = to_path(c);  // read by the pipeline, as --constraints FILE
  }
}

}  // namespace

void set_weights(app::WeightArgs& w, py::dict& o) {
  if (o.contains("method")) w.method = py::str(o.attr("pop")("method")).cast<std::string>();
  check_member("method", w.method, {"conformal", "authalic", "mixed", "tutte", "floater"});
  int lambdas = 0;
  for (const char* key : {"lambda", "lambda_", "lam"}) {
    const py::object v = o.attr("pop")(key, py::none());
    if (v.is_none()) continue;
    if (++lambdas > 1) throw_usage("give lambda once (lam, lambda_ or 'lambda')");
    w.lambda = v.cast<double>();
    w.lambda_set = true;
  }
  const py::object mu = o.attr("pop")("mu", py::none());
  if (!mu.is_none()) {
    w.mu = mu.cast<double>();
    w.mu_set = true;
  }
}

namespace {

std::string pop_str(py::dict& o, const char* key, const std::string& fallback) {
  const py::object v = o.attr("pop")(key, py::none());
  return v.is_none() ? fallback : py::str(v).cast<std::string>();
}

void set_optimizers(app::ParamArgs& a, py::dict& o) {
  a.optimize_lambda = pop_str(o, "optimize_lambda", "");
  if (!a.optimize_lambda.empty()) check_member("optimize-lambda", a.optimize_lambda, {"edge", "area"});
  const py::object range = o.attr("pop")("lambda_range", py::none());
  if (!range.is_none()) a.lambda_range = range.cast<std::vector<double>>();
  if (a.lambda_range.size() != 2) throw_usage("--lambda-range: expected LO,HI");
  a.optimize_boundary = pop_str(o, "optimize_boundary", "");
  if (!a.optimize_boundary.empty())
    check_member("optimize-boundary", a.optimize_boundary, {"edge", "area", "dirichlet"});
  a.iterations = o.attr("pop")("iterations", a.iterations).cast<int>();
  if (a.iterations < 0) throw_usage("--iterations: Value " + std::to_string(a.iterations) + " should not be negative");
  a.tolerance = o.attr("pop")("tolerance", a.tolerance).cast<double>();
  a.gradient = pop_str(o, "gradient", a.gradient);
  check_member("gradient", a.gradient, {"adjoint", "responses"});
  a.descent = pop_str(o, "descent", a.descent);
  check_member("descent", a.descent, {"lbfgs", "gradient"});
}

}  // namespace

app::ParamArgs to_args(const py::dict& options, bool optimizers) {
  py::dict o = options.attr("copy")();
  app::ParamArgs a;
  a.quiet = true;  // the library never prints; boundary optimization's progress lines are the CLI's
  set_weights(*a.weights, o);
  const py::object boundary = o.attr("pop")("boundary", py::none());
  if (!boundary.is_none()) a.boundary = to_path(boundary);
  a.spacing = pop_str(o, "spacing", a.spacing);
  check_member("spacing", a.spacing, {"arclength", "uniform"});
  a.scale = pop_str(o, "scale", a.scale);
  check_member("scale", a.scale, {"unit", "surface"});
  a.holes = pop_str(o, "holes", a.holes);
  check_member("holes", a.holes, {"fill", "free", "natural"});
  a.solver = pop_str(o, "solver", a.solver);
  const py::object pins = o.attr("pop")("pins", o.attr("pop")("pin", py::none()));
  if (!pins.is_none())
    for (const py::handle p : pins) a.pins.push_back(pin_text(p));
  a.max_residual = o.attr("pop")("max_residual", a.max_residual).cast<double>();
  set_constraints(a, o.attr("pop")("constraints", py::none()));
  a.largest_component = o.attr("pop")("largest_component", false).cast<bool>();
  a.max_vertices = o.attr("pop")("max_vertices", a.max_vertices).cast<std::int64_t>();
  if (a.max_vertices <= 0) throw_usage("--max-vertices: Value " + std::to_string(a.max_vertices) + " should be positive");
  a.quiet = !o.attr("pop")("verbose", false).cast<bool>();
  if (optimizers) set_optimizers(a, o);
  if (!o.empty()) {
    const std::string key = py::str(py::list(o.attr("keys")())[0]).cast<std::string>();
    throw_usage("unknown option '" + key + "'");
  }
  app::check_args(a);
  return a;
}

}  // namespace intrinsic::python
