// Python keyword options -> the library's typed requests (pipeline.h): the
// keywords of parameterize(V, F, **options), Parameterizer(...) and atlas()
// are values for the library's option tables (to_option_value;
// param_option_table.h, atlas_option_table.h). Choices go through the name tables
// (intrinsic/choice.h) with the keyword as the label, so a bad value reads
// "method: 'foo' is not one of conformal, ...", and the library's own checks
// name keywords (OptionSpelling::Keyword), never command-line flags.
#include <cmath>
#include <iostream>
#include <sstream>

#include "common.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "intrinsic/intrinsic.h"
#include "intrinsic/param_option_table.h"

namespace intrinsic::python {
namespace {

// A pin as the table takes it: "V:U,V" text as is; a (vertex, u, v) triple
// as that text, with every digit a double needs, so it parses back exactly.
std::string pin_text(const py::handle& pin) {
  if (py::isinstance<py::str>(pin)) return pin.cast<std::string>();
  const FixedVertex f = to_fixed(py::make_tuple(pin), "pins").front();
  std::ostringstream out;
  out.precision(17);
  out << f.vertex << ":" << f.uv.x() << "," << f.uv.y();
  return out.str();
}

// Boundary optimization's progress lines on stderr when verbose=True (the
// library never prints).
void set_progress(BoundaryOptimizationOptions& bo) {
  bo.progress = [](int it, double e) {
    std::cerr << "boundary optimization: iteration " << it << ", energy " << e << "\n" << std::flush;
  };
}

}  // namespace

// Every keyword but `verbose` and a dict of constraints (data) is an option
// of the library's param table, which checks it and makes the request; None
// leaves an option at its default.
ParamRequest to_request(const py::dict& options, bool optimizers) {
  const std::vector<OptionSpec>& table = param_option_table();
  GivenOptions given;
  bool verbose = false;
  py::object constraints = py::none();
  for (const auto& [key, value] : options) {
    const std::string k = py::str(key);
    const OptionSpec* spec = find_option(table, k);
    if (k == "verbose") verbose = value.cast<bool>();
    else if (k == "constraints" && py::isinstance<py::dict>(value)) constraints = py::reinterpret_borrow<py::object>(value);
    else if (!spec || (!optimizers && spec->group == "Optimizers")) throw_usage("unknown option '" + k + "'");
    else if (value.is_none()) continue;
    else if (spec->repeated) for (const py::handle item : value) given.emplace_back(k, pin_text(item));
    else given.emplace_back(k, to_option_value(table, k, value));
  }
  ParamRequest r = param_request(given, OptionSpelling::Keyword);
  if (!constraints.is_none()) {
    const std::string text = py::str(py::module_::import("json").attr("dumps")(constraints)).cast<std::string>();
    r.constraints = parse_constraints_json(text, "constraints");
    check_param_request(r);  // constraints and the optimizers exclude each other
  }
  if (verbose) set_progress(r.boundary_optimization);
  return r;
}

namespace {

py::object value_to_python(const OptionValue& v) {
  if (const bool* b = std::get_if<bool>(&v)) return py::bool_(*b);
  if (const std::int64_t* i = std::get_if<std::int64_t>(&v)) return py::int_(*i);
  if (const double* d = std::get_if<double>(&v)) return py::float_(*d);
  if (const RealPair* p = std::get_if<RealPair>(&v)) return py::make_tuple((*p)[0], (*p)[1]);
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
      case OptionType::ChoiceOrPath:
        // An enum value (intrinsic.AtlasScope.PER_MESH) gives its name.
        if (!py::isinstance<py::str>(value) && py::hasattr(value, "option")) return value.attr("option").cast<std::string>();
        return s->type == OptionType::Choice ? value.cast<std::string>() : to_path(value);
      case OptionType::Path: return to_path(value);
      case OptionType::Text: return value.cast<std::string>();
      case OptionType::RealPair: {
        if (py::isinstance<py::str>(value)) break;
        const auto pair = value.cast<std::vector<double>>();
        if (pair.size() == 2) return RealPair{pair[0], pair[1]};
        break;
      }
    }
  } catch (const py::cast_error&) {
  }
  throw_usage(key + ": expected " + (s->type == OptionType::Choice       ? "one of its names"
               : s->type == OptionType::RealPair ? "(lo, hi)"
                                                 : option_type_name(s->type)) +
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
    d["type"] = option_type_name(s.type);
    d["group"] = s.group;
    d["help"] = s.help;
    d["min"] = bound_to_python(s.min);
    d["max"] = bound_to_python(s.max);
    d["choices"] = s.choices;
    d["repeated"] = s.repeated;
    d["value_name"] = s.value_name;
    d["default"] = s.default_value ? value_to_python(*s.default_value) : py::object(py::none());
    out.append(d);
  }
  return out;
}

}  // namespace intrinsic::python
