// One name table per user-facing choice: how the command line, the Python
// module, the server and the JSON reports spell each enum value. Every
// enum's names are written once, in src/util/names.cpp; parsing, printing,
// the allowed lists of `--help` and the messages for a bad value all come
// from that table, so the spellings cannot drift apart between the shells.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "intrinsic/atlas.h"
#include "intrinsic/boundary.h"
#include "intrinsic/boundary_editor.h"
#include "intrinsic/boundary_optimization.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "intrinsic/linear_solver.h"
#include "intrinsic/optimal_lambda.h"
#include "intrinsic/parameterize.h"
#include "intrinsic/texture.h"
#include "intrinsic/weights.h"

namespace intrinsic {

// The five pictures of `intrinsic render` (render.h draws them).
enum class PictureMode { Checker, Layout, Angle, Area, Stretch };

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

// The table of E, in the order `--help` lists it. Specialised in names.cpp
// for every enum below; an enum without a table fails to link.
template <class E>
ChoiceTable<E> choice_table();

template <>
ChoiceTable<Method> choice_table<Method>();
template <>
ChoiceTable<BoundaryShape> choice_table<BoundaryShape>();
template <>
ChoiceTable<Spacing> choice_table<Spacing>();
template <>
ChoiceTable<ScaleMode> choice_table<ScaleMode>();
template <>
ChoiceTable<Placement> choice_table<Placement>();
template <>
ChoiceTable<HoleRule> choice_table<HoleRule>();
template <>
ChoiceTable<HolesApplied> choice_table<HolesApplied>();
template <>
ChoiceTable<SolverKind> choice_table<SolverKind>();
template <>
ChoiceTable<LambdaEnergy> choice_table<LambdaEnergy>();
template <>
ChoiceTable<BoundaryEnergy> choice_table<BoundaryEnergy>();
template <>
ChoiceTable<GradientRoute> choice_table<GradientRoute>();
template <>
ChoiceTable<Descent> choice_table<Descent>();
template <>
ChoiceTable<Segmentation> choice_table<Segmentation>();
template <>
ChoiceTable<ChartMethod> choice_table<ChartMethod>();
template <>
ChoiceTable<ChartOptimizer> choice_table<ChartOptimizer>();
template <>
ChoiceTable<BasisMode> choice_table<BasisMode>();
template <>
ChoiceTable<PictureMode> choice_table<PictureMode>();
template <>
ChoiceTable<TextureRole> choice_table<TextureRole>();
template <>
ChoiceTable<TextureWrap> choice_table<TextureWrap>();
template <>
ChoiceTable<AtlasScope> choice_table<AtlasScope>();
template <>
ChoiceTable<InstanceMode> choice_table<InstanceMode>();

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

// The value named `text`. Throws Error(Usage) "<label>: 'foo' is not one of
// a, b, c"; `label` is how the caller's user names the option ("--method"
// on the command line, "method" in Python).
template <class E>
E parse_choice(std::string_view text, std::string_view label) {
  for (const Choice<E>& c : choice_table<E>())
    if (c.listed && text == c.name) return c.value;
  throw_usage(std::string(label) + ": '" + std::string(text) + "' is not one of " + choice_list<E>());
}

// The solver named `text` (the table's parse) that this build has: Error(Usage)
// for one it lacks (SuiteSparse not found).
SolverKind parse_solver(const std::string& text, std::string_view label);

}  // namespace intrinsic
