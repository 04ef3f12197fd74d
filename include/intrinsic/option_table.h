// The declaration of a job's options as every shell spells them: the command
// line's flag, Python's keyword and the report's key, the type, the accepted
// range, the default and one help text. Each job declares its options once,
// in one table (atlas_option_table.h); the CLI registers its flags from it,
// the Python module its keywords, the .pyi and the batch runner their
// signatures and the Blender add-on its properties, so a new option is
// written once (docs/layout.md "Options").
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "intrinsic/choice.h"

namespace intrinsic {

// Text is free text the job parses itself (a pin's "V:U,V"); ChoiceOrPath
// is one of the choices or else a file's path (param's --boundary: circle,
// square, natural or a file of positions); RealPair is two numbers (an
// interval, "LO,HI" on the command line).
enum class OptionType { Bool, Int, Real, Choice, Path, Text, ChoiceOrPath, RealPair };

using RealPair = std::array<double, 2>;

// A value as a shell gives it: a Choice as its name, a Path or Text as text.
using OptionValue = std::variant<bool, std::int64_t, double, std::string, RealPair>;

struct OptionSpec {
  std::string key;                   // Python keyword and report key ("max_stretch")
  std::string flag;                  // the command line's flag ("--max-stretch")
  bool flag_negates = false;         // the flag sets the key false ("--keep-winding" for reorient)
  std::vector<std::string> aliases;  // other keywords Python takes ("lambda_" for "lambda")
  OptionType type = OptionType::Real;
  std::string group;                 // where --help lists it ("Packing", ...)
  std::string help;
  double min = -std::numeric_limits<double>::infinity();  // Int and Real: the accepted range
  double max = std::numeric_limits<double>::infinity();
  std::vector<std::string> choices;  // Choice, ChoiceOrPath: the names
  bool repeated = false;             // may be given many times, each value kept (--pin, once per pin)
  std::string value_name;            // how --help shows the value ("V:U,V"), when its type says too little
  std::optional<OptionValue> default_value;  // none: unset unless given
};

// The options a user gave, by key, in the order given.
using GivenOptions = std::vector<std::pair<std::string, OptionValue>>;

// How a spec's option is named in `spelling` (its flag, or its key).
inline const std::string& option_name(const OptionSpec& spec, OptionSpelling spelling) {
  return spelling == OptionSpelling::Flag ? spec.flag : spec.key;
}

// `value` as `spec`'s type: an Int where a Real is expected is taken as a
// number; anything else of the wrong type, a number outside [min, max] or a
// name outside the choices (of a Choice; a ChoiceOrPath takes any other
// text as a path) is Error(Usage) naming the option as `spelling`
// spells it.
OptionValue checked_option_value(const OptionSpec& spec, const OptionValue& value, OptionSpelling spelling);

// Whether `key` is the spec's key or one of its aliases.
bool option_matches(const OptionSpec& spec, const std::string& key);

// The spec whose key or alias is `key`, or null.
const OptionSpec* find_option(const std::vector<OptionSpec>& table, const std::string& key);

// The specs of `table` whose keys are in `keys`, in the table's order (a
// command that takes a few of a job's options: `edit` takes param's blend).
std::vector<OptionSpec> select_options(const std::vector<OptionSpec>& table, const std::vector<std::string>& keys);

// The type's short name, as the tables' readers (the Python module's dicts,
// the generated docs) show it: "bool", "int", "float", "choice", "path",
// "str", "choice or path", "pair".
const char* option_type_name(OptionType type);

// A value as text, as --help shows a default ("2", "1.08", "true", "whole",
// "0,1").
std::string option_value_text(const OptionValue& value);

}  // namespace intrinsic
