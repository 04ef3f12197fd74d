// `intrinsic param`: parse -> read -> solve -> emit. The flags map onto the
// library's ParamRequest (pipeline.h), which reads and validates the mesh
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
#include "intrinsic/pictures.h"
#include "intrinsic/pipeline.h"
#include "intrinsic/report.h"
#include "weight_args.h"

namespace intrinsic::app {
namespace {

struct ParamArgs {
  std::string input, output, report, constraints;
  std::string render, render_all, render_size = "1024,1024", view = "auto";
  std::shared_ptr<WeightArgs> weights = std::make_shared<WeightArgs>();
  std::string boundary = choice_name(BoundaryShape::Circle), spacing = choice_name(Spacing::ArcLength),
              scale = choice_name(ScaleMode::Unit), holes = choice_name(HoleRule::Fill),
              solver = choice_name(SolverKind::Auto);
  std::vector<std::string> pins;  // "V:U,V"
  bool binary = false, quiet = false, largest_component = false;
  std::int64_t max_vertices = ReadOptions().max_vertices;
  double max_residual = 1e-8;
  std::string optimize_lambda, optimize_boundary;  // "" when not given
  std::vector<double> lambda_range{0, 1};
  int iterations = 200;
  double tolerance = 1e-6;
  std::string gradient = choice_name(GradientRoute::Adjoint), descent = choice_name(Descent::LBFGS);
};

// Boundary optimization's progress, on stderr (the library never prints).
void add_progress(const ParamArgs& a, BoundaryOptimizationOptions& bo) {
  const bool tty = isatty(fileno(stderr));
  if (!a.quiet)
    bo.progress = [tty](int it, double e) {
      std::cerr << (tty ? "\r" : "") << "boundary optimization: iteration " << it << ", energy " << e
                << (tty ? "   " : "\n") << std::flush;
    };
}

void set_optimizer(const ParamArgs& a, ParamRequest& r) {
  if (!a.optimize_lambda.empty() && !a.optimize_boundary.empty())
    throw_usage("--optimize-lambda and --optimize-boundary cannot be combined");
  if (!a.optimize_lambda.empty()) {
    r.optimizer = ChartOptimizer::OptimalLambda;
    r.optimal_lambda.energy = parse_choice<LambdaEnergy>(a.optimize_lambda, "--optimize-lambda");
  } else if (!a.optimize_boundary.empty()) {
    r.optimizer = ChartOptimizer::OptimizeBoundary;
    r.boundary_optimization.energy = parse_choice<BoundaryEnergy>(a.optimize_boundary, "--optimize-boundary");
  }
  r.optimal_lambda.lo = a.lambda_range.at(0);
  r.optimal_lambda.hi = a.lambda_range.at(1);
  BoundaryOptimizationOptions& bo = r.boundary_optimization;
  bo.route = parse_choice<GradientRoute>(a.gradient, "--gradient");
  bo.descent = parse_choice<Descent>(a.descent, "--descent");
  bo.max_iterations = a.iterations;
  bo.tolerance = a.tolerance;
  add_progress(a, bo);
}

// The flags as the library's request; usage errors before any file is read.
ParamRequest to_request(const ParamArgs& a) {
  ParamRequest r;
  r.spelling = OptionSpelling::Flag;
  ParamOptions& o = r.options;
  o.solver = parse_solver(a.solver, "--solver");
  for (const std::string& p : a.pins) o.pins.push_back(parse_pin(p, OptionSpelling::Flag));  // syntax first: a usage error whatever the file
  if (!a.optimize_lambda.empty() && a.optimize_boundary.empty() && a.weights->given())
    throw_usage("--optimize-lambda chooses the blend itself; do not give --method, --lambda or --mu");
  o.weights = a.weights->options();
  if (is_choice<BoundaryShape>(a.boundary)) {
    o.boundary = parse_choice<BoundaryShape>(a.boundary, "--boundary");
  } else {
    o.boundary = BoundaryShape::Given;  // a file of positions, read once the mesh is known
    r.boundary_file = a.boundary;
  }
  o.spacing = parse_choice<Spacing>(a.spacing, "--spacing");
  o.scale = parse_choice<ScaleMode>(a.scale, "--scale");
  o.holes = parse_choice<HoleRule>(a.holes, "--holes");
  o.max_residual = a.max_residual;
  r.constraints_file = a.constraints;
  set_optimizer(a, r);
  r.largest_component = a.largest_component;
  r.read.max_vertices = a.max_vertices;
  r.read.max_faces = faces_for_vertices(a.max_vertices);
  check_param_request(r);
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

void add_solve_options(CLI::App& cmd, const std::shared_ptr<ParamArgs>& a) {
  cmd.add_option("input", a->input, "Input mesh (.obj, .off, .ply, .stl, optionally .gz)")->required();
  cmd.add_option("-o,--output", a->output, "Output mesh with UVs (.obj or .ply)")->required();
  add_weight_options(cmd, a->weights);
  cmd.add_option("--boundary", a->boundary,
                 "circle | square | natural (natural conformal map, no fixed boundary; conformal only) | "
                 "FILE with lines 'vertex u v'")
      ->capture_default_str();
  cmd.add_option("--pin", a->pins,
                 "Natural boundary: keep vertex V exactly at (U,V); repeatable, at least two, any vertex, "
                 "no rescaling. Default: the two outer-loop vertices farthest apart in 3D, at their 3D distance")
      ->type_name("V:U,V")
      ->allow_extra_args(false)  // one value per --pin, so "--pin 1:0,0 in.obj" leaves the input alone
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd.add_option("--spacing", a->spacing, "Boundary spacing: arclength | uniform")
      ->check(choice_check<Spacing>())
      ->capture_default_str();
  cmd.add_option("--scale", a->scale,
                 "unit: fit [0,1]^2 | surface: parameter area = 3D area (natural: pins at their 3D distance)")
      ->check(choice_check<ScaleMode>())
      ->capture_default_str();
  cmd.add_option("--holes", a->holes,
                 "Holes without given positions, fixed-boundary modes: fill (temporary fan) | free | natural "
                 "(natural conformal condition on hole loops; see docs/holes.md). Natural boundary: every loop is natural")
      ->check(choice_check<HoleRule>())
      ->capture_default_str();
  cmd.add_option("--solver", a->solver, "auto | cholmod | umfpack | eigen-llt | eigen-lu | cg | bicgstab")
      ->capture_default_str();
  cmd.add_option("--max-residual", a->max_residual, "Fail (exit 3) if the relative residual exceeds this")
      ->capture_default_str();
  cmd.add_option("--constraints", a->constraints,
                 "JSON file of point and line constraints; targets are in output coordinates (see docs/formats.md)");
  cmd.add_flag("--largest-component", a->largest_component,
               "Keep only the component with the most faces (vertex numbering unchanged); "
               "otherwise every component becomes its own chart");
  cmd.add_option("--max-vertices", a->max_vertices, "Refuse inputs with more vertices")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
}

void add_optimizer_options(CLI::App& cmd, const std::shared_ptr<ParamArgs>& a) {
  cmd.add_option("--optimize-lambda", a->optimize_lambda,
                 "Blend lambda*conformal + (1-lambda)*authalic with the lambda minimising edge or area distortion")
      ->check(choice_check<LambdaEnergy>());
  cmd.add_option("--lambda-range", a->lambda_range, "Interval searched by --optimize-lambda, as LO,HI")
      ->delimiter(',')
      ->expected(2)
      ->capture_default_str();
  cmd.add_option("--optimize-boundary", a->optimize_boundary,
                 "Move the boundary to minimise edge, area or (symmetric) dirichlet distortion")
      ->check(choice_check<BoundaryEnergy>());
  cmd.add_option("--iterations", a->iterations, "Boundary optimization: iteration limit")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd.add_option("--tolerance", a->tolerance, "Boundary optimization: stop below this relative decrease")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd.add_option("--gradient", a->gradient, "Boundary optimization gradient: adjoint | responses")
      ->check(choice_check<GradientRoute>())
      ->capture_default_str();
  cmd.add_option("--descent", a->descent, "Boundary optimization descent: lbfgs | gradient")
      ->check(choice_check<Descent>())
      ->capture_default_str();
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
  add_solve_options(*cmd, a);
  add_optimizer_options(*cmd, a);
  add_output_options(*cmd, a);
  cmd->callback([&run, a] { run = [a] { return run_param(*a); }; });
}

}  // namespace intrinsic::app
