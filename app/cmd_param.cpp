// `intrinsic param`: parse -> read -> solve -> emit. Read and validate the
// mesh, parameterize it (one chart per component when it has several;
// optionally optimal lambda, boundary optimization or constraints), then
// write the mesh with UVs, the pictures and the report built from the
// result.
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "command.h"
#include "intrinsic/boundary_optimization.h"
#include "intrinsic/charts.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "intrinsic/optimal_lambda.h"
#include "intrinsic/parameterize.h"
#include "intrinsic/parameterizer.h"
#include "pictures.h"
#include "report.h"
#include "weight_args.h"

namespace intrinsic::app {
namespace {

struct ParamArgs {
  std::string input, output, report, constraints;
  std::string render, render_all, render_size = "1024,1024", view = "auto";
  std::shared_ptr<WeightArgs> weights = std::make_shared<WeightArgs>();
  std::string boundary = "circle", spacing = "arclength", scale = "unit", holes = "fill", solver = "auto";
  std::vector<std::string> pins;  // "V:U,V"
  bool binary = false, quiet = false, largest_component = false;
  std::int64_t max_vertices = ReadOptions().max_vertices;
  double max_residual = 1e-8;
  std::string optimize_lambda;            // "", "edge" or "area"
  std::vector<double> lambda_range{0, 1};
  std::string optimize_boundary;  // "", "edge", "area", "dirichlet"
  int iterations = 200;
  double tolerance = 1e-6;
  std::string gradient = "adjoint", descent = "lbfgs";
};

// "V:U,V" -> pin. Malformed text is a usage error; the vertex range is
// checked against the mesh later (an input error).
FixedVertex parse_pin(const std::string& text) {
  const auto bad = [&]() -> FixedVertex {
    throw_usage("--pin '" + text + "': expected VERTEX:U,V, e.g. --pin 12:0.5,0");
  };
  const size_t colon = text.find(':'), comma = text.find(',', colon == std::string::npos ? 0 : colon);
  if (colon == std::string::npos || comma == std::string::npos) return bad();
  FixedVertex p{};
  const char* b = text.data();
  auto [end, ec] = std::from_chars(b, b + colon, p.vertex);
  if (ec != std::errc() || end != b + colon || colon == 0) return bad();
  auto number = [&](size_t from, size_t to, double& x) {
    // strtod, not from_chars<double>: the latter is missing from older libstdc++
    const std::string part = text.substr(from, to - from);
    char* stop = nullptr;
    x = std::strtod(part.c_str(), &stop);
    return !part.empty() && !std::isspace(static_cast<unsigned char>(part[0])) && stop == part.c_str() + part.size() &&
           std::isfinite(x);
  };
  if (!number(colon + 1, comma, p.uv.x()) || !number(comma + 1, text.size(), p.uv.y())) return bad();
  return p;
}

ParamOptions to_options(const ParamArgs& a, int num_vertices) {
  ParamOptions o;
  o.weights = a.weights->options();
  if (a.boundary == "circle") o.boundary = BoundaryShape::Circle;
  else if (a.boundary == "square") o.boundary = BoundaryShape::Square;
  else if (a.boundary == "natural") o.boundary = BoundaryShape::Natural;
  else {
    o.boundary = BoundaryShape::Given;
    o.given = read_boundary_file(a.boundary, num_vertices);
  }
  o.spacing = a.spacing == "uniform" ? Spacing::Uniform : Spacing::ArcLength;
  o.scale = a.scale == "surface" ? ScaleMode::Surface : ScaleMode::Unit;
  o.holes = a.holes == "free" ? HoleRule::Free : a.holes == "natural" ? HoleRule::Natural : HoleRule::Fill;
  for (const std::string& p : a.pins) o.pins.push_back(parse_pin(p));
  if (!o.pins.empty() && o.boundary != BoundaryShape::Natural) throw_usage("--pin applies to --boundary natural only");
  if (o.pins.size() == 1) throw_usage("--pin needs at least two pins (translation, rotation and scale)");
  o.solver = parse_solver(a.solver);
  o.max_residual = a.max_residual;
  return o;
}

// What a run solved: the map, and the optimizers' own results when used.
struct Solved {
  ParamResult map;
  nlohmann::json optimal_lambda, boundary_optimization;  // null unless used
};

// Usage checks that need no file, so a bad command line fails before any work.
void check_args(const ParamArgs& a) {
  check_output_mesh_path(a.output);
  parse_method(a.weights->method);
  parse_solver(a.solver);
  if (!(a.max_residual > 0)) throw_usage("--max-residual must be a positive number");
  for (const std::string& p : a.pins) parse_pin(p);  // syntax first: a usage error whatever the file
  if (!a.constraints.empty() && (!a.optimize_lambda.empty() || !a.optimize_boundary.empty()))
    throw_usage("--constraints cannot be combined with --optimize-lambda or --optimize-boundary");
  if (!a.optimize_lambda.empty() && !a.optimize_boundary.empty())
    throw_usage("--optimize-lambda and --optimize-boundary cannot be combined");
  if (!a.optimize_lambda.empty() && (a.weights->method != "conformal" || a.weights->lambda_set || a.weights->mu_set))
    throw_usage("--optimize-lambda chooses the blend itself; do not give --method, --lambda or --mu");
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

Mesh validated_mesh(const ParamArgs& a, const MeshData& data) {
  ValidateOptions vo;
  vo.allow_several_components = true;
  vo.allow_closed = a.largest_component;  // a closed small piece may be dropped; the kept one is checked later
  Mesh mesh = make_mesh(data, vo);
  if (a.largest_component && mesh.topology.num_components > 1) {
    const int reoriented = mesh.validation.reoriented_faces;
    mesh = make_mesh(component_data(mesh, largest_component(mesh)));
    mesh.validation.reoriented_faces = reoriented;
  }
  return mesh;
}

Solved solve_optimal_lambda(const ParamArgs& a, const Mesh& mesh, const ParamOptions& options) {
  OptimalLambdaOptions lo;
  lo.base = options;
  lo.energy = parse_lambda_energy(a.optimize_lambda);
  lo.lo = a.lambda_range.at(0);
  lo.hi = a.lambda_range.at(1);
  const OptimalLambdaResult best = optimal_lambda(mesh, lo);
  return {best.map, optimal_lambda_json(best, lo), nullptr};
}

Solved solve_boundary_optimization(const ParamArgs& a, const Mesh& mesh, const ParamOptions& options) {
  BoundaryOptimizationOptions bo;
  bo.base = options;
  bo.energy = parse_boundary_energy(a.optimize_boundary);
  bo.route = parse_gradient_route(a.gradient);
  bo.descent = parse_descent(a.descent);
  bo.max_iterations = a.iterations;
  bo.tolerance = a.tolerance;
  const bool tty = isatty(fileno(stderr));
  if (!a.quiet)
    bo.progress = [tty](int it, double e) {
      std::cerr << (tty ? "\r" : "") << "boundary optimization: iteration " << it << ", energy " << e
                << (tty ? "   " : "\n") << std::flush;
    };
  const BoundaryOptimizationResult best = optimize_boundary(mesh, bo);
  if (!a.quiet && tty && best.iterations > 0) std::cerr << "\n";
  return {best.map, nullptr, boundary_optimization_json(best, bo)};
}

Solved solve(const ParamArgs& a, const Mesh& mesh, const MeshData& data, const ParamOptions& options) {
  if (mesh.topology.num_components > 1) {
    if (!a.optimize_lambda.empty() || !a.optimize_boundary.empty() || !a.constraints.empty())
      throw_usage("--optimize-lambda, --optimize-boundary and --constraints take a single component; "
                  "use --largest-component");
    return {parameterize_charts(mesh, options), nullptr, nullptr};
  }
  if (!a.optimize_lambda.empty()) return solve_optimal_lambda(a, mesh, options);
  if (!a.optimize_boundary.empty()) return solve_boundary_optimization(a, mesh, options);
  Parameterizer parameterizer(mesh, options);
  if (!a.constraints.empty()) {
    Constraints c = read_constraints_file(a.constraints);
    match_face_corners(c, data.F, mesh);
    parameterizer.set_constraints(c);
  }
  return {parameterizer.solve(), nullptr, nullptr};
}

struct StageMs {
  double read = 0, validate = 0, render = 0, write = 0;
};

nlohmann::json build_report(const ParamArgs& a, const Mesh& mesh, const Solved& s, const DistortionSummary& d) {
  nlohmann::json report = mesh_json(mesh);
  report["output"] = a.output;
  add_solution(report, s.map, a.boundary);
  if (!s.optimal_lambda.is_null()) {
    report["method"] = "optimal-lambda";
    report["optimal_lambda"] = s.optimal_lambda;
  }
  if (!s.boundary_optimization.is_null()) report["boundary_optimization"] = s.boundary_optimization;
  if (!a.constraints.empty()) {
    report["constraints_file"] = a.constraints;
    report["constraints"] = constraints_json(s.map.constraints);
  }
  // The scale the map came out at: parameter area over 3D area.
  report["area_ratio"] = std::abs(parameter_area(mesh.F, s.map.UV)) / surface_area(mesh.V, mesh.F);
  add_distortion(report, d);
  return report;
}

// Pictures are made before anything is written, so a failure leaves no file.
std::vector<std::pair<std::string, std::string>> make_pictures(
    const std::vector<std::pair<PictureMode, std::string>>& pictures, const PictureSettings& ps, const Mesh& mesh,
    const ParamResult& r, const DistortionSummary& d) {
  std::vector<std::pair<std::string, std::string>> files;
  if (pictures.empty()) return files;
  Distortion dist;
  dist.faces = face_distortion(mesh.V, mesh.F, r.UV);
  dist.summary = d;
  for (const auto& [mode, path] : pictures)
    files.emplace_back(path, encode_png(make_picture(mode, mesh.V, mesh.F, r.UV, ps, &dist).image));
  return files;
}

void print_summary(const ParamArgs& a, const Mesh& mesh, const nlohmann::json& report, const ParamResult& r,
                   const DistortionSummary& d, double total_ms) {
  std::cout << a.output << ": " << mesh.V.rows() << " vertices, " << report["method"].get<std::string>();
  if (report.contains("optimal_lambda")) std::cout << " lambda=" << std::to_string(report["lambda"].get<double>());
  std::cout << ", " << report["boundary"].get<std::string>()
            << (r.charts.empty() ? "" : ", " + std::to_string(r.charts.size()) + " charts") << ", "
            << d.flipped_triangles << " flipped, angle distortion mean " << d.angle_distortion.mean << ", "
            << static_cast<long>(total_ms) << " ms\n";
}

int run_param(const ParamArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  check_args(a);
  PictureSettings ps;
  const auto pictures = picture_requests(a, ps);
  StageMs ms;
  ReadOptions ro;
  ro.max_vertices = a.max_vertices;
  ro.max_faces = faces_for_vertices(ro.max_vertices);
  const MeshData data = read_mesh(a.input, ro);
  ms.read = elapsed_ms(t0);
  const auto t1 = std::chrono::steady_clock::now();
  const Mesh mesh = validated_mesh(a, data);
  ms.validate = elapsed_ms(t1);
  const Solved solved = solve(a, mesh, data, to_options(a, static_cast<int>(mesh.V.rows())));
  const ParamResult& r = solved.map;
  const DistortionSummary d = summarize_distortion(mesh.V, mesh.F, r.UV);
  const auto t_pic = std::chrono::steady_clock::now();
  std::vector<std::pair<std::string, std::string>> files = make_pictures(pictures, ps, mesh, r, d);
  ms.render = elapsed_ms(t_pic);
  const auto t2 = std::chrono::steady_clock::now();
  WriteOptions wo;
  wo.binary = a.binary;
  write_mesh(a.output, mesh.V, mesh.F, r.UV, wo);
  ms.write = elapsed_ms(t2);
  nlohmann::json report = build_report(a, mesh, solved, d);
  report["timings_ms"] = {{"read", ms.read},         {"validate", ms.validate}, {"assemble", r.timings.assemble_ms},
                          {"factor", r.timings.factor_ms}, {"solve", r.timings.solve_ms}, {"render", ms.render},
                          {"write", ms.write},       {"total", elapsed_ms(t0)}};
  if (!a.report.empty()) files.insert(files.begin(), {a.report, report.dump(2) + "\n"});
  write_all(files, {a.output});  // on failure the mesh goes too: no partial set of outputs
  if (!a.quiet) print_summary(a, mesh, report, r, d, elapsed_ms(t0));
  return 0;
}

void add_solve_options(CLI::App& cmd, const std::shared_ptr<ParamArgs>& a) {
  cmd.add_option("input", a->input, "Input mesh (.obj, .off, .ply, optionally .gz)")->required();
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
      ->check(CLI::IsMember({"arclength", "uniform"}))
      ->capture_default_str();
  cmd.add_option("--scale", a->scale,
                 "unit: fit [0,1]^2 | surface: parameter area = 3D area (natural: pins at their 3D distance)")
      ->check(CLI::IsMember({"unit", "surface"}))
      ->capture_default_str();
  cmd.add_option("--holes", a->holes,
                 "Holes without given positions, fixed-boundary modes: fill (temporary fan) | free | natural "
                 "(natural conformal condition on hole loops; see docs/holes.md). Natural boundary: every loop is natural")
      ->check(CLI::IsMember({"fill", "free", "natural"}))
      ->capture_default_str();
  cmd.add_option("--solver", a->solver, "auto | cholmod | umfpack | eigen-llt | eigen-lu | cg | bicgstab")
      ->capture_default_str();
  cmd.add_option("--max-residual", a->max_residual, "Fail (exit 3) if the relative residual exceeds this")
      ->capture_default_str();
  cmd.add_option("--constraints", a->constraints,
                 "JSON file of point and line constraints; targets are in output coordinates (see README)");
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
      ->check(CLI::IsMember({"edge", "area"}));
  cmd.add_option("--lambda-range", a->lambda_range, "Interval searched by --optimize-lambda, as LO,HI")
      ->delimiter(',')
      ->expected(2)
      ->capture_default_str();
  cmd.add_option("--optimize-boundary", a->optimize_boundary,
                 "Move the boundary to minimise edge, area or (symmetric) dirichlet distortion")
      ->check(CLI::IsMember({"edge", "area", "dirichlet"}));
  cmd.add_option("--iterations", a->iterations, "Boundary optimization: iteration limit")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd.add_option("--tolerance", a->tolerance, "Boundary optimization: stop below this relative decrease")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd.add_option("--gradient", a->gradient, "Boundary optimization gradient: adjoint | responses")
      ->check(CLI::IsMember({"adjoint", "responses"}))
      ->capture_default_str();
  cmd.add_option("--descent", a->descent, "Boundary optimization descent: lbfgs | gradient")
      ->check(CLI::IsMember({"lbfgs", "gradient"}))
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
