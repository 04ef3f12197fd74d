// How a user-facing enum is spelled: each enum's header declares its table
// (`choice_table<E>()`) beside the enum, and the source of that layer
// defines it. Parsing, printing, the allowed lists of `--help` and the
// messages for a bad value all come from the table, so the command line, the
// Python module, the server and the JSON reports cannot spell a value
// differently.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "intrinsic/error.h"

namespace intrinsic {

// One row of a table. `listed` false: a name the library prints (reports)
// but a user does not choose, e.g. BoundaryShape::Given, which the command
// line spells as a file path.
template <class E>
struct Choice {
  E value;
  const char* name;
  bool listed = true;
};

template <class E>
struct ChoiceTable {
  const Choice<E>* rows;
  size_t size;
  const Choice<E>* begin() const { return rows; }
  const Choice<E>* end() const { return rows + size; }
};

// The table of E, in the order `--help` lists it. Specialised beside each
// enum (its header declares it, its layer's source defines it); an enum
// without a table fails to link.
template <class E>
ChoiceTable<E> choice_table();

// A table over a static array of rows (what each definition returns).
template <class E, std::size_t N>
ChoiceTable<E> make_choice_table(const Choice<E> (&rows)[N]) {
  return {rows, N};
}

// The names a user may give, in table order.
template <class E>
std::vector<std::string> choice_names() {
  std::vector<std::string> out;
  for (const Choice<E>& c : choice_table<E>())
    if (c.listed) out.emplace_back(c.name);
  return out;
}

// "conformal, authalic, mixed, tutte, floater": the list messages show.
template <class E>
std::string choice_list() {
  std::string out;
  for (const std::string& n : choice_names<E>()) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// The name of `value` ("?" for a value outside the table, which is a bug).
template <class E>
std::string choice_name(E value) {
  for (const Choice<E>& c : choice_table<E>())
    if (c.value == value) return c.name;
  return "?";
}

// Whether `text` is a listed name of E.
template <class E>
bool is_choice(std::string_view text) {
  for (const Choice<E>& c : choice_table<E>())
    if (c.listed && text == c.name) return true;
  return false;
}

// How messages about a request name its options: "optimize_lambda" (the
// Python keyword, the default) or "--optimize-lambda" (the command line).
// Every options struct a shell fills carries one, so the library's messages
// are right for each shell as they are.
enum class OptionSpelling { Keyword, Flag };
// `key` in keyword spelling ("optimize_lambda") as `spelling` writes it: the
// flag is the keyword with dashes, except where the command line's flag
// says more than the keyword (pins: --pin, once per pin; replace_used_set:
// --replace-uv-set).
inline std::string option_label(std::string_view key, OptionSpelling spelling) {
  if (spelling == OptionSpelling::Keyword) return std::string(key);
  if (key == "pins") return "--pin";
  if (key == "replace_used_set") return "--replace-uv-set";
  std::string flag = "--" + std::string(key);
  for (char& c : flag)
    if (c == '_') c = '-';
  return flag;
}

// The value named `text`. Throws Error(Usage) "<label>: 'foo' is not one of
// a, b, c"; `label` is how the caller's user names the option ("--method"
// on the command line, "method" in Python).
template <class E>
E parse_choice(std::string_view text, std::string_view label) {
  for (const Choice<E>& c : choice_table<E>())
    if (c.listed && text == c.name) return c.value;
  throw_usage(std::string(label) + ": '" + std::string(text) + "' is not one of " + choice_list<E>());
}

}  // namespace intrinsic
