// How subcommands plug into the `intrinsic` tool: each app/cmd_*.cpp defines a
// register function that adds its CLI11 subcommand and sets `run` when that
// subcommand is chosen; main.cpp calls it after parsing. Errors propagate as
// intrinsic::Error and become a message and exit code in main.cpp.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <string>

#include "intrinsic/io.h"

namespace intrinsic::app {

using Runner = std::function<int()>;

void register_param(CLI::App& app, Runner& run);
void register_metrics(CLI::App& app, Runner& run);
void register_generate(CLI::App& app, Runner& run);
void register_edit(CLI::App& app, Runner& run);

void register_render(CLI::App& app, Runner& run);
void register_compare(CLI::App& app, Runner& run);
void register_atlas(CLI::App& app, Runner& run);
void register_formats(CLI::App& app, Runner& run);
void register_serve(CLI::App& app, Runner& run);  // built when cpp-httplib is found

// Milliseconds since t0.
double elapsed_ms(std::chrono::steady_clock::time_point t0);
// Throws Error(Usage) unless `path` ends in .obj or .ply.
void check_output_mesh_path(const std::string& path);

}  // namespace intrinsic::app
