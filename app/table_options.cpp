// Flags from a job's option table (table_options.h).
#include "table_options.h"

#include <cmath>

namespace intrinsic::app {
namespace {

// Help shows "{a,b,c}"; a bad value fails parsing with
// "--option: 'foo' is not one of a, b, c".
CLI::Validator choices_check(const std::vector<std::string>& names) {
  std::string set, list;
  for (const std::string& n : names) {
    set += (set.empty() ? "" : ",") + n;
    list += (list.empty() ? "" : ", ") + n;
  }
  return CLI::Validator(
      [names, list](std::string& value) -> std::string {
        for (const std::string& n : names)
          if (n == value) return {};
        return "'" + value + "' is not one of " + list;
      },
      "{" + set + "}");
}

// The spec's range as CLI11 checks and shows it.
template <class T>
void add_range(CLI::Option* o, const OptionSpec& s) {
  if (std::isfinite(s.min) && std::isfinite(s.max))
    o->check(CLI::Range(static_cast<T>(s.min), static_cast<T>(s.max)));
  else if (s.min == 0)
    o->check(CLI::NonNegativeNumber);
  else if (s.min > 0)
    o->check(CLI::PositiveNumber);
}

template <class T>
CLI::Option* add_value(CLI::App* cmd, const OptionSpec& s, const std::shared_ptr<GivenOptions>& given) {
  const std::string key = s.key;
  return cmd->add_option_function<T>(
      s.flag, [given, key](const T& v) { given->emplace_back(key, OptionValue(v)); }, s.help);
}

}  // namespace

void add_table_options(CLI::App* cmd, const std::vector<OptionSpec>& table,
                       const std::shared_ptr<GivenOptions>& given) {
  for (const OptionSpec& s : table) {
    CLI::Option* o = nullptr;
    if (s.type == OptionType::Bool) {
      const std::string key = s.key;
      const bool value = !s.flag_negates;
      o = cmd->add_flag_callback(s.flag, [given, key, value] { given->emplace_back(key, OptionValue(value)); }, s.help);
    } else if (s.type == OptionType::Int) {
      o = add_value<std::int64_t>(cmd, s, given);
      add_range<std::int64_t>(o, s);
    } else if (s.type == OptionType::Real) {
      o = add_value<double>(cmd, s, given);
      add_range<double>(o, s);
    } else {
      o = add_value<std::string>(cmd, s, given);
      if (s.type == OptionType::Choice) o->check(choices_check(s.choices));
    }
    if (s.type != OptionType::Bool && s.default_value) o->default_str(option_value_text(*s.default_value));
    o->group(s.group);
  }
}

}  // namespace intrinsic::app
