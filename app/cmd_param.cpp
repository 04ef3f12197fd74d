// `intrinsic param`: parse -> read -> solve -> emit. The job's flags are the
// library's param option table (param_option_table.h), which makes the
// ParamRequest (pipeline.h); the pipeline reads and validates the mesh
// and parameterizes it (one chart per component when it has several;
// optionally optimal lambda, boundary optimization or constraints); this file
// adds the pictures, writes the mesh, the pictures and the report, and prints.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "choice_option.h"
#include "command.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "intrinsic/param_option_table.h"
#include "intrinsic/pictures.h"
#include "intrinsic/pipeline.h"
#include "intrinsic/report.h"
#include "table_options.h"

namespace intrinsic::app {
namespace {

struct ParamArgs {
  std::string input, output, report;
  std::string render, render_all, render_size = "1024,1024", view = "auto";
  std::shared_ptr<GivenOptions> given = std::make_shared<GivenOptions>();  // the job's options (param_option_table.h)
  bool binary = false, quiet = false;
};

// The flags as the library's request; usage errors before any file is read.
// Boundary optimization's progress goes to stderr (the library never prints).
ParamRequest to_request(const ParamArgs& a) {
  ParamRequest r = param_request(*a.given, OptionSpelling::Flag);
  const bool tty = isatty(fileno(stderr));
  if (!a.quiet)
    r.boundary_optimization.progress = [tty](int it, double e) {
      std::cerr << (tty ? "\r" : "") << "boundary optimization: iteration " << it << ", energy " << e
                << (tty ? "   " : "\n") << std::flush;
    };
  return r;
}

// Picture requests (mode, path), checked before any work is done.
std::vector<std::pair<PictureMode, std::string>> picture_requests(const ParamArgs& a, PictureSettings& ps) {
  std::vector<std::pair<PictureMode, std::string>> pictures;
  if (!a.render.empty()) {
    check_png_path(a.render, "--render");
    pictures.emplace_back(PictureMode::Checker, a.render);
  }
  if (!a.render_all.empty())
    for (PictureMode m : kAllPictureModes) pictures.emplace_back(m, a.render_all + "_" + mode_name(m) + ".png");
  parse_size(a.render_size, "--render-size", ps.render.width, ps.render.height);
  parse_view(a.view, ps.render);
  ps.render.fit_uv = true;
  return pictures;
}

// Pictures are made before anything is written, so a failure leaves no file.
std::vector<std::pair<std::string, std::string>> make_pictures(
    const std::vector<std::pair<PictureMode, std::string>>& pictures, const PictureSettings& ps,
    const ParamOutcome& o) {
  std::vector<std::pair<std::string, std::string>> files;
  if (pictures.empty()) return files;
  Distortion dist;
  dist.faces = face_distortion(o.mesh.V, o.mesh.F, o.map.UV);
  dist.summary = o.distortion;
  for (const auto& [mode, path] : pictures)
    files.emplace_back(path, encode_png(make_picture(mode, o.mesh.V, o.mesh.F, o.map.UV, ps, &dist).image));
  return files;
}

void print_summary(const ParamArgs& a, const ParamOutcome& o, const nlohmann::json& report, double total_ms) {
  const DistortionSummary& d = o.distortion;
  std::cout << a.output << ": " << o.mesh.V.rows() << " vertices, " << report["method"].get<std::string>();
  if (report.contains("optimal_lambda")) std::cout << " lambda=" << std::to_string(report["lambda"].get<double>());
  std::cout << ", " << report["boundary"].get<std::string>()
            << (o.map.charts.empty() ? "" : ", " + std::to_string(o.map.charts.size()) + " charts") << ", "
            << d.flipped_triangles << " flipped, angle distortion mean " << d.angle_distortion.mean << ", "
            << static_cast<long>(total_ms) << " ms\n";
}

int run_param(const ParamArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  check_output_mesh_path(a.output);
  // The job writes the mesh itself, while it measures the map.
  ParamRequest request = to_request(a);
  request.output = a.output;
  request.write.binary = a.binary;
  PictureSettings ps;
  const auto pictures = picture_requests(a, ps);
  const ParamOutcome o = parameterize_file(a.input, request);
  if (!a.quiet && request.optimizer == ChartOptimizer::OptimizeBoundary && isatty(fileno(stderr)) &&
      o.boundary_optimization && o.boundary_optimization->iterations > 0)
    std::cerr << "\n";
  const auto t_pic = std::chrono::steady_clock::now();
  std::vector<std::pair<std::string, std::string>> files;
  try {
    files = make_pictures(pictures, ps, o);
  } catch (...) {
    std::remove(a.output.c_str());  // no partial set of outputs
    throw;
  }
  const double render_ms = elapsed_ms(t_pic);
  nlohmann::json report = nlohmann::json::parse(param_report(request, o, a.output));
  report["timings_ms"]["render"] = render_ms;
  report["timings_ms"]["write"] = o.write_ms;
  report["timings_ms"]["total"] = elapsed_ms(t0);
  if (!a.report.empty()) files.insert(files.begin(), {a.report, report.dump(2) + "\n"});
  write_all(files, {a.output});  // on failure the mesh goes too: no partial set of outputs
  if (!a.quiet) print_summary(a, o, report, elapsed_ms(t0));
  return 0;
}

void add_output_options(CLI::App& cmd, const std::shared_ptr<ParamArgs>& a) {
  cmd.add_option("--report", a->report, "Write the JSON report to this file");
  cmd.add_flag("--binary", a->binary, "Binary PLY output");
  cmd.add_option("--render", a->render, "Also write the checker picture of the result (.png)");
  cmd.add_option("--render-all", a->render_all,
                 "Also write PREFIX_checker.png, PREFIX_layout.png, PREFIX_angle.png, PREFIX_area.png, "
                 "PREFIX_stretch.png");
  cmd.add_option("--render-size", a->render_size, "Size of those pictures in pixels, W,H")->capture_default_str();
  cmd.add_option("--view", a->view, "3D view of the pictures: auto | top | front | AZIMUTH,ELEVATION")
      ->capture_default_str();
  cmd.add_flag("-q,--quiet", a->quiet, "Print nothing on success");
}

}  // namespace

void register_param(CLI::App& app, Runner& run) {
  auto a = std::make_shared<ParamArgs>();
  CLI::App* cmd = app.add_subcommand(
      "param", "Parameterize a mesh with boundary: a fixed outer boundary or the natural conformal map; "
               "several components become charts laid out side by side");
  cmd->add_option("input", a->input, "Input mesh (.obj, .off, .ply, .stl, optionally .gz)")->required();
  cmd->add_option("-o,--output", a->output, "Output mesh with UVs (.obj or .ply)")->required();
  add_table_options(cmd, param_option_table(), a->given);
  add_output_options(*cmd, a);
  cmd->callback([&run, a] { run = [a] { return run_param(*a); }; });
}

}  // namespace intrinsic::app
