// `intrinsic param`: parse -> read -> solve -> emit. Read and validate the
// mesh, parameterize it (one chart per component when it has several;
// optionally optimal lambda, boundary optimization or constraints: the
// pipeline of param_job.h, shared with the Python module), then write the
// mesh with UVs, the pictures and the report built from the result.
#include <chrono>
#include <iostream>

#include "command.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "param_job.h"
#include "pictures.h"
#include "report.h"

namespace intrinsic::app {
namespace {

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

struct StageMs {
  double read = 0, validate = 0, render = 0, write = 0;
};

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
  check_output_mesh_path(a.output);
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
