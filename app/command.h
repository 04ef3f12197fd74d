// How subcommands plug into the `intrinsic` tool: each app/cmd_*.cpp defines a
// register function that adds its CLI11 subcommand and sets `run`, which the
// main function calls after parsing. Errors propagate as intrinsic::Error and
// are turned into a message and exit code in main.cpp.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace intrinsic::app {

using Runner = std::function<int()>;

void register_param(CLI::App& app, Runner& run);
void register_metrics(CLI::App& app, Runner& run);
void register_render(CLI::App& app, Runner& run);

}  // namespace intrinsic::app
