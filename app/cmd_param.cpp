// `intrinsic param`: read, validate, parameterize, write the mesh with UVs
// and the distortion report.
#include <filesystem>
#include <iostream>

#include "command.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "intrinsic/parameterize.h"
#include "report.h"

namespace intrinsic::app {
namespace {

struct ParamArgs {
  std::string input, output, report;
  std::string method = "conformal";
  double lambda = 1, mu = 0;
  bool lambda_set = false, mu_set = false;
  std::string boundary = "circle", spacing = "arclength", scale = "unit", holes = "fill", solver = "auto";
  bool binary = false, quiet = false;
  std::int64_t max_vertices = ReadOptions().max_vertices;
  double max_residual = 1e-8;
};

ParamOptions to_options(const ParamArgs& a, int num_vertices) {
  ParamOptions o;
  o.weights.method = parse_method(a.method);
  if ((a.lambda_set || a.mu_set) && o.weights.method != Method::Mixed)
    throw_usage("--lambda and --mu apply to --method mixed only");
  if (o.weights.method == Method::Mixed) {
    if (!a.lambda_set && !a.mu_set) throw_usage("--method mixed needs --lambda and/or --mu");
    o.weights.lambda = a.lambda_set ? a.lambda : 0.0;
    o.weights.mu = a.mu_set ? a.mu : 0.0;
    if (o.weights.lambda == 0 && o.weights.mu == 0) throw_usage("--lambda and --mu cannot both be zero");
  }
  if (a.boundary == "circle") o.boundary = BoundaryShape::Circle;
  else if (a.boundary == "square") o.boundary = BoundaryShape::Square;
  else {
    o.boundary = BoundaryShape::Given;
    o.given = read_boundary_file(a.boundary, num_vertices);
  }
  o.spacing = a.spacing == "uniform" ? Spacing::Uniform : Spacing::ArcLength;
  o.scale = a.scale == "surface" ? ScaleMode::Surface : ScaleMode::Unit;
  o.holes = a.holes == "free" ? HoleRule::Free : HoleRule::Fill;
  o.solver = parse_solver(a.solver);
  o.max_residual = a.max_residual;
  return o;
}

std::string boundary_label(const ParamArgs& a) {
  return a.boundary == "circle" || a.boundary == "square" ? a.boundary : "file:" + a.boundary;
}

}  // namespace

void register_param(CLI::App& app, Runner& run) {
  auto a = std::make_shared<ParamArgs>();
  CLI::App* cmd = app.add_subcommand("param", "Parameterize a disk-like mesh with a fixed boundary");
  cmd->add_option("input", a->input, "Input mesh (.obj, .off, .ply, optionally .gz)")->required();
  cmd->add_option("-o,--output", a->output, "Output mesh with UVs (.obj or .ply)")->required();
  cmd->add_option("--method", a->method, "conformal | authalic | mixed | tutte | floater")
      ->check(CLI::IsMember({"conformal", "authalic", "mixed", "tutte", "floater"}))
      ->capture_default_str();
  cmd->add_option_function<double>("--lambda", [a](double v) { a->lambda = v; a->lambda_set = true; },
                                   "Weight of the conformal energy (mixed)");
  cmd->add_option_function<double>("--mu", [a](double v) { a->mu = v; a->mu_set = true; },
                                   "Weight of the authalic energy (mixed)");
  cmd->add_option("--boundary", a->boundary, "circle | square | FILE with lines 'vertex u v'")->capture_default_str();
  cmd->add_option("--spacing", a->spacing, "Boundary spacing: arclength | uniform")
      ->check(CLI::IsMember({"arclength", "uniform"}))
      ->capture_default_str();
  cmd->add_option("--scale", a->scale, "unit: fit [0,1]^2 | surface: parameter area = 3D area")
      ->check(CLI::IsMember({"unit", "surface"}))
      ->capture_default_str();
  cmd->add_option("--holes", a->holes, "Holes without given positions: fill (temporary fan) | free")
      ->check(CLI::IsMember({"fill", "free"}))
      ->capture_default_str();
  cmd->add_option("--solver", a->solver, "auto | cholmod | umfpack | eigen-llt | eigen-lu | cg | bicgstab")
      ->capture_default_str();
  cmd->add_option("--max-residual", a->max_residual, "Fail (exit 3) if the relative residual exceeds this")
      ->capture_default_str();
  cmd->add_option("--report", a->report, "Write the JSON report to this file");
  cmd->add_flag("--binary", a->binary, "Binary PLY output");
  cmd->add_option("--max-vertices", a->max_vertices, "Refuse inputs with more vertices")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", a->quiet, "Print nothing on success");
  cmd->callback([&run, a] {
    run = [a] {
      const auto t0 = std::chrono::steady_clock::now();
      check_output_mesh_path(a->output);
      parse_method(a->method);
      parse_solver(a->solver);
      if (!(a->max_residual > 0)) throw_usage("--max-residual must be a positive number");
      ReadOptions ro;
      ro.max_vertices = a->max_vertices;
      ro.max_faces = faces_for_vertices(ro.max_vertices);
      const MeshData data = read_mesh(a->input, ro);
      const double t_read = elapsed_ms(t0);
      const auto t1 = std::chrono::steady_clock::now();
      const Mesh mesh = make_mesh(data);
      const double t_validate = elapsed_ms(t1);
      const ParamOptions options = to_options(*a, static_cast<int>(mesh.V.rows()));
      const ParamResult r = parameterize(mesh, options);
      const DistortionSummary d = summarize_distortion(mesh.V, mesh.F, r.UV);

      const auto t2 = std::chrono::steady_clock::now();
      WriteOptions wo;
      wo.binary = a->binary;
      write_mesh(a->output, mesh.V, mesh.F, r.UV, wo);
      const double t_write = elapsed_ms(t2);

      nlohmann::json report = mesh_json(mesh);
      report["output"] = a->output;
      report["method"] = a->method;
      report["lambda"] = options.weights.method == Method::Mixed ? options.weights.lambda
                         : options.weights.method == Method::Conformal ? 1.0 : 0.0;
      report["mu"] = options.weights.method == Method::Mixed ? options.weights.mu
                     : options.weights.method == Method::Authalic ? 1.0 : 0.0;
      report["boundary"] = boundary_label(*a);
      report["spacing"] = a->spacing;
      report["scale"] = r.scale;
      report["holes"] = a->holes;
      report["filled_holes"] = r.filled_holes;
      report["solver"] = r.solver;
      report["residual"] = r.residual;
      report["free_vertices"] = r.free_vertices;
      report["fixed_vertices"] = r.fixed_vertices;
      if (r.iterations > 0) report["iterations"] = r.iterations;
      add_distortion(report, d);
      report["timings_ms"] = {{"read", t_read},
                              {"validate", t_validate},
                              {"assemble", r.timings.assemble_ms},
                              {"factor", r.timings.factor_ms},
                              {"solve", r.timings.solve_ms},
                              {"write", t_write},
                              {"total", elapsed_ms(t0)}};
      if (!a->report.empty()) {
        try {
          write_report(a->report, report);
        } catch (...) {
          std::filesystem::remove(a->output);  // no partial set of outputs
          throw;
        }
      }
      if (!a->quiet)
        std::cout << a->output << ": " << mesh.V.rows() << " vertices, " << a->method << ", "
                  << boundary_label(*a) << ", " << d.flipped_triangles << " flipped, angle distortion mean "
                  << d.angle_distortion.mean << ", " << static_cast<long>(elapsed_ms(t0)) << " ms\n";
      return 0;
    };
  });
}

}  // namespace intrinsic::app
