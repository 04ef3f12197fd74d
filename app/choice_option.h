// A CLI11 check for an option whose value is one of an enum's names: the
// allowed list and the message come from the name table (intrinsic/choice.h), so
// `--help` shows exactly the names the library parses.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "intrinsic/boundary_editor.h"
#include "intrinsic/intrinsic.h"
#include "intrinsic/pictures.h"

namespace intrinsic::app {

// Help shows "{a,b,c}"; a bad value fails parsing with
// "--option: 'foo' is not one of a, b, c".
template <class E>
CLI::Validator choice_check() {
  std::string set;
  for (const std::string& n : choice_names<E>()) set += (set.empty() ? "" : ",") + n;
  return CLI::Validator(
      [](std::string& value) -> std::string {
        return is_choice<E>(value) ? std::string() : "'" + value + "' is not one of " + choice_list<E>();
      },
      "{" + set + "}");
}

}  // namespace intrinsic::app
