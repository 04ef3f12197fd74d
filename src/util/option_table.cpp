// Checking a value a shell gave against its option's declaration
// (option_table.h).
#include "intrinsic/option_table.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "intrinsic/error.h"

namespace intrinsic {
namespace {

const char* type_name(OptionType t) {
  switch (t) {
    case OptionType::Bool: return "true or false";
    case OptionType::Int: return "an integer";
    case OptionType::Real: return "a number";
    case OptionType::Choice: return "a name";
    case OptionType::Path: return "a path";
  }
  return "?";
}

std::string range_text(const OptionSpec& s) {
  const bool low = std::isfinite(s.min), high = std::isfinite(s.max);
  if (low && high) return "in [" + option_value_text(s.min) + ", " + option_value_text(s.max) + "]";
  if (low) return "at least " + option_value_text(s.min);
  return "at most " + option_value_text(s.max);
}

std::string list_text(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

OptionValue checked_option_value(const OptionSpec& spec, const OptionValue& value, OptionSpelling spelling) {
  const std::string& name = option_name(spec, spelling);
  OptionValue v = value;
  if (spec.type == OptionType::Real && std::holds_alternative<std::int64_t>(v))
    v = static_cast<double>(std::get<std::int64_t>(v));
  const bool fits = (spec.type == OptionType::Bool && std::holds_alternative<bool>(v)) ||
                    (spec.type == OptionType::Int && std::holds_alternative<std::int64_t>(v)) ||
                    (spec.type == OptionType::Real && std::holds_alternative<double>(v)) ||
                    ((spec.type == OptionType::Choice || spec.type == OptionType::Path) &&
                     std::holds_alternative<std::string>(v));
  if (!fits) throw_usage(name + ": expected " + type_name(spec.type) + ", got " + option_value_text(value));
  if (spec.type == OptionType::Int || spec.type == OptionType::Real) {
    const double x = spec.type == OptionType::Int ? static_cast<double>(std::get<std::int64_t>(v)) : std::get<double>(v);
    if (!(x >= spec.min && x <= spec.max))
      throw_usage(name + ": " + option_value_text(v) + " is not " + range_text(spec));
  }
  if (spec.type == OptionType::Choice) {
    const std::string& text = std::get<std::string>(v);
    bool known = false;
    for (const std::string& c : spec.choices) known = known || c == text;
    if (!known) throw_usage(name + ": '" + text + "' is not one of " + list_text(spec.choices));
  }
  return v;
}

bool option_matches(const OptionSpec& spec, const std::string& key) {
  return spec.key == key || std::find(spec.aliases.begin(), spec.aliases.end(), key) != spec.aliases.end();
}

const OptionSpec* find_option(const std::vector<OptionSpec>& table, const std::string& key) {
  for (const OptionSpec& s : table)
    if (option_matches(s, key)) return &s;
  return nullptr;
}

std::string option_value_text(const OptionValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const std::int64_t* i = std::get_if<std::int64_t>(&value)) return std::to_string(*i);
  if (const std::string* s = std::get_if<std::string>(&value)) return *s;
  std::ostringstream out;
  out << std::get<double>(value);
  return out.str();
}

}  // namespace intrinsic
