// The rows of a job's option table: each option's declaration (option_table.h)
// with the request field it sets, and the one loop that turns what a user
// gave into a request. A job's table (atlas_option_table.cpp,
// param_option_table.cpp) is a list of such rows over its own Draft: the
// request being built, plus the values combined only once every option is in.
#pragma once

#include <algorithm>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "intrinsic/error.h"
#include "intrinsic/option_table.h"
#include "intrinsic/weights.h"

namespace intrinsic::option_rows {

constexpr double kNoLimit = std::numeric_limits<double>::infinity();

template <class Draft>
struct Row {
  OptionSpec spec;
  std::function<void(Draft&, const OptionValue&)> set;
};

// The request field a row sets, reached from the draft.
template <class Draft, class T>
using Field = T& (*)(Draft&);

// A spec whose flag is the key with dashes (option_label).
inline OptionSpec spec(const char* key, const char* group, const char* help, double min = -kNoLimit,
                       double max = kNoLimit) {
  OptionSpec s;
  s.key = key;
  s.flag = option_label(key, OptionSpelling::Flag);
  s.group = group;
  s.help = help;
  s.min = min;
  s.max = max;
  return s;
}

// The row makers of one job's Draft: `using Rows = RowsOf<Draft>;` then
// `Rows::real(spec(...), [](Draft& d) -> double& { return ...; })`. Each
// default is read from a default-constructed draft, so it is written once.
template <class Draft>
struct RowsOf {
  using R = Row<Draft>;
  template <class T>
  using F = Field<Draft, T>;

  template <class T>
  static T default_of(F<T> f) {
    Draft d;
    return f(d);
  }

  static R with_flag(R row, const char* flag, bool negates = false) {
    row.spec.flag = flag;
    row.spec.flag_negates = negates;
    return row;
  }

  static R real(OptionSpec s, F<double> f) {
    s.type = OptionType::Real;
    s.default_value = default_of(f);
    return {s, [f](Draft& d, const OptionValue& v) { f(d) = std::get<double>(v); }};
  }

  static R optional_real(OptionSpec s, F<std::optional<double>> f) {
    s.type = OptionType::Real;
    return {s, [f](Draft& d, const OptionValue& v) { f(d) = std::get<double>(v); }};
  }

  template <class I>
  static R integer(OptionSpec s, F<I> f) {
    s.type = OptionType::Int;
    s.default_value = static_cast<std::int64_t>(default_of(f));
    return {s, [f](Draft& d, const OptionValue& v) { f(d) = static_cast<I>(std::get<std::int64_t>(v)); }};
  }

  // An Int that is unset (-1 in the request) unless given.
  static R optional_integer(OptionSpec s, F<int> f) {
    R r = integer<int>(s, f);
    r.spec.default_value.reset();
    return r;
  }

  static R boolean(OptionSpec s, F<bool> f) {
    s.type = OptionType::Bool;
    s.default_value = default_of(f);
    return {s, [f](Draft& d, const OptionValue& v) { f(d) = std::get<bool>(v); }};
  }

  static R path(OptionSpec s, F<std::string> f) {
    s.type = OptionType::Path;
    return {s, [f](Draft& d, const OptionValue& v) { f(d) = std::get<std::string>(v); }};
  }

  static R real_pair(OptionSpec s, F<RealPair> f) {
    s.type = OptionType::RealPair;
    s.default_value = default_of(f);
    return {s, [f](Draft& d, const OptionValue& v) { f(d) = std::get<RealPair>(v); }};
  }

  // Text given any number of times, each value kept in order.
  static R repeated_text(OptionSpec s, F<std::vector<std::string>> f) {
    s.type = OptionType::Text;
    s.repeated = true;
    return {s, [f](Draft& d, const OptionValue& v) { f(d).push_back(std::get<std::string>(v)); }};
  }

  template <class E>
  static R choice(OptionSpec s, F<E> f) {
    s.type = OptionType::Choice;
    s.choices = choice_names<E>();
    s.default_value = choice_name(default_of(f));
    return {s, [f](Draft& d, const OptionValue& v) { f(d) = parse_choice<E>(std::get<std::string>(v), ""); }};
  }

  // One of E's names, or any other text as a file's path; kept as text.
  template <class E>
  static R choice_or_path(OptionSpec s, F<std::string> f) {
    s.type = OptionType::ChoiceOrPath;
    s.choices = choice_names<E>();
    s.default_value = default_of(f);
    return {s, [f](Draft& d, const OptionValue& v) { f(d) = std::get<std::string>(v); }};
  }

  // The blend's rows (method, lambda, mu), which the jobs spell alike; the
  // Draft holds them as `method`, `lambda` and `mu` until every option is in.
  static void add_blend_rows(std::vector<R>& t, const char* group) {
    t.push_back(choice<Method>(spec("method", group, "conformal | authalic | mixed | tutte | floater"),
                               [](Draft& d) -> Method& { return d.method; }));
    R lambda = optional_real(spec("lambda", group, "Weight of the conformal energy (mixed)"),
                             [](Draft& d) -> std::optional<double>& { return d.lambda; });
    lambda.spec.aliases = {"lambda_", "lam"};
    t.push_back(lambda);
    t.push_back(optional_real(spec("mu", group, "Weight of the authalic energy (mixed)"),
                              [](Draft& d) -> std::optional<double>& { return d.mu; }));
  }

  template <class E>
  static R optional_choice(OptionSpec s, F<std::optional<E>> f) {
    s.type = OptionType::Choice;
    s.choices = choice_names<E>();
    return {s, [f](Draft& d, const OptionValue& v) { f(d) = parse_choice<E>(std::get<std::string>(v), ""); }};
  }
};

template <class Draft>
std::vector<OptionSpec> specs_of(const std::vector<Row<Draft>>& rows) {
  std::vector<OptionSpec> s;
  for (const Row<Draft>& r : rows) s.push_back(r.spec);
  return s;
}

// Sets every given value on `draft`, each checked against its spec; returns
// the keys given, in order. An unknown key, or one given twice (also through
// an alias) that is not repeated, is Error(Usage) naming it as `spelling`
// spells it.
template <class Draft>
std::vector<std::string> apply_given(const std::vector<Row<Draft>>& rows, const GivenOptions& given,
                                     OptionSpelling spelling, Draft& draft) {
  std::vector<std::string> keys;
  for (const auto& [key, value] : given) {
    const Row<Draft>* row = nullptr;
    for (const Row<Draft>& r : rows)
      if (option_matches(r.spec, key)) row = &r;
    if (!row) throw_usage("unknown option '" + key + "'");
    const bool seen = std::find(keys.begin(), keys.end(), row->spec.key) != keys.end();
    if (seen && !row->spec.repeated) throw_usage(option_name(row->spec, spelling) + ": given twice");
    if (!seen) keys.push_back(row->spec.key);
    row->set(draft, checked_option_value(row->spec, value, spelling));
  }
  return keys;
}

inline bool was_given(const std::vector<std::string>& keys, const char* key) {
  return std::find(keys.begin(), keys.end(), key) != keys.end();
}

}  // namespace intrinsic::option_rows
