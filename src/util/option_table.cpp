// Checking a value a shell gave against its option's declaration
// (option_table.h).
#include "intrinsic/option_table.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "intrinsic/error.h"

namespace intrinsic {
namespace {

// The type in a message: "expected a number, got ...".
const char* type_words(OptionType t) {
  switch (t) {
    case OptionType::Bool: return "true or false";
    case OptionType::Int: return "an integer";
    case OptionType::Real: return "a number";
    case OptionType::Choice: return "a name";
    case OptionType::Path: return "a path";
    case OptionType::Text: return "text";
    case OptionType::ChoiceOrPath: return "a name or a path";
    case OptionType::RealPair: return "two numbers";
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

bool value_fits(OptionType type, const OptionValue& v) {
  switch (type) {
    case OptionType::Bool: return std::holds_alternative<bool>(v);
    case OptionType::Int: return std::holds_alternative<std::int64_t>(v);
    case OptionType::Real: return std::holds_alternative<double>(v);
    case OptionType::RealPair: return std::holds_alternative<RealPair>(v);
    case OptionType::Choice:
    case OptionType::Path:
    case OptionType::Text:
    case OptionType::ChoiceOrPath: return std::holds_alternative<std::string>(v);
  }
  return false;
}

}  // namespace

OptionValue checked_option_value(const OptionSpec& spec, const OptionValue& value, OptionSpelling spelling) {
  const std::string& name = option_name(spec, spelling);
  OptionValue v = value;
  if (spec.type == OptionType::Real && std::holds_alternative<std::int64_t>(v))
    v = static_cast<double>(std::get<std::int64_t>(v));
  if (!value_fits(spec.type, v))
    throw_usage(name + ": expected " + type_words(spec.type) + ", got " + option_value_text(value));
  if (spec.type == OptionType::Int || spec.type == OptionType::Real) {
    const double x = spec.type == OptionType::Int ? static_cast<double>(std::get<std::int64_t>(v)) : std::get<double>(v);
    if (!(x >= spec.min && x <= spec.max))
      throw_usage(name + ": " + option_value_text(v) + " is not " + range_text(spec));
  }
  if (spec.type == OptionType::RealPair)
    for (const double x : std::get<RealPair>(v))
      if (!(x >= spec.min && x <= spec.max))
        throw_usage(name + ": " + option_value_text(v) + " is not " + range_text(spec));
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

const char* option_type_name(OptionType type) {
  switch (type) {
    case OptionType::Bool: return "bool";
    case OptionType::Int: return "int";
    case OptionType::Real: return "float";
    case OptionType::Choice: return "choice";
    case OptionType::Path: return "path";
    case OptionType::Text: return "str";
    case OptionType::ChoiceOrPath: return "choice or path";
    case OptionType::RealPair: return "pair";
  }
  return "?";
}

std::vector<OptionSpec> select_options(const std::vector<OptionSpec>& table, const std::vector<std::string>& keys) {
  std::vector<OptionSpec> out;
  for (const OptionSpec& s : table)
    if (std::find(keys.begin(), keys.end(), s.key) != keys.end()) out.push_back(s);
  return out;
}

std::string option_value_text(const OptionValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const std::int64_t* i = std::get_if<std::int64_t>(&value)) return std::to_string(*i);
  if (const std::string* s = std::get_if<std::string>(&value)) return *s;
  std::ostringstream out;
  if (const RealPair* p = std::get_if<RealPair>(&value)) out << (*p)[0] << "," << (*p)[1];
  else out << std::get<double>(value);
  return out.str();
}

}  // namespace intrinsic
