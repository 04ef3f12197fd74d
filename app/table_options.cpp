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

// Every occurrence of a repeated option, one value each ("--pin 1:0,0 in.obj"
// leaves the input alone).
CLI::Option* add_repeated(CLI::App* cmd, const OptionSpec& s, const std::shared_ptr<GivenOptions>& given) {
  const std::string key = s.key;
  return cmd
      ->add_option_function<std::vector<std::string>>(
          s.flag,
          [given, key](const std::vector<std::string>& values) {
            for (const std::string& v : values) given->emplace_back(key, OptionValue(v));
          },
          s.help)
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

// Two numbers as LO,HI.
CLI::Option* add_pair(CLI::App* cmd, const OptionSpec& s, const std::shared_ptr<GivenOptions>& given) {
  const std::string key = s.key;
  return cmd
      ->add_option_function<std::vector<double>>(
          s.flag, [given, key](const std::vector<double>& v) { given->emplace_back(key, OptionValue(RealPair{v[0], v[1]})); },
          s.help)
      ->delimiter(',')
      ->expected(2);
}

CLI::Option* add_one(CLI::App* cmd, const OptionSpec& s, const std::shared_ptr<GivenOptions>& given) {
  CLI::Option* o = nullptr;
  if (s.type == OptionType::Bool) {
    const std::string key = s.key;
    const bool value = !s.flag_negates;
    return cmd->add_flag_callback(s.flag, [given, key, value] { given->emplace_back(key, OptionValue(value)); }, s.help);
  } else if (s.type == OptionType::Int) {
    o = add_value<std::int64_t>(cmd, s, given);
    add_range<std::int64_t>(o, s);
  } else if (s.type == OptionType::Real) {
    o = add_value<double>(cmd, s, given);
    add_range<double>(o, s);
  } else if (s.type == OptionType::RealPair) {
    o = add_pair(cmd, s, given);
  } else if (s.repeated) {
    o = add_repeated(cmd, s, given);
  } else {
    o = add_value<std::string>(cmd, s, given);
    if (s.type == OptionType::Choice) o->check(choices_check(s.choices));
  }
  if (!s.value_name.empty()) o->type_name(s.value_name);
  if (s.default_value) o->default_str(option_value_text(*s.default_value));
  return o;
}

}  // namespace

void add_table_options(CLI::App* cmd, const std::vector<OptionSpec>& table,
                       const std::shared_ptr<GivenOptions>& given) {
  for (const OptionSpec& s : table) {
    CLI::Option* o = add_one(cmd, s, given);
    o->group(s.group);
  }
}

}  // namespace intrinsic::app
