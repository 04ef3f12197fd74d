// A job's option table (intrinsic/option_table.h) as command-line flags:
// the flag, help, range check, choices and shown default all come from the
// library's declaration, and what the user gave goes back to the library
// as keys and values (atlas_request), which makes the request.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <vector>

#include "intrinsic/option_table.h"

namespace intrinsic::app {

// Registers one flag per spec of `table` on `cmd`, each in its spec's group;
// every one the user gives is appended to `given` in the order given.
void add_table_options(CLI::App* cmd, const std::vector<OptionSpec>& table,
                       const std::shared_ptr<GivenOptions>& given);

}  // namespace intrinsic::app
