// What `intrinsic param` does between reading a mesh and writing it, shared
// by the command line (cmd_param.cpp) and the Python module
// (python/src/): the options as the command line names them, their mapping
// to ParamOptions, validation, the solve (charts, optimal lambda, boundary
// optimization, constraints) and the JSON report. One mapping, so the
// module's results and reports equal the command line's.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "intrinsic/constraints.h"
#include "intrinsic/io.h"
#include "intrinsic/mesh.h"
#include "intrinsic/parameterize.h"
#include "weight_args.h"

namespace intrinsic::app {

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
  // Constraints already in memory (the Python module); otherwise they are
  // read from the file `constraints` names, if any.
  std::shared_ptr<const Constraints> given_constraints;
  bool has_constraints() const { return !constraints.empty() || given_constraints != nullptr; }
};

// "V:U,V" -> pin. Malformed text is a usage error; the vertex range is
// checked against the mesh later (an input error).
FixedVertex parse_pin(const std::string& text);
ParamOptions to_options(const ParamArgs& a, int num_vertices);
// Usage checks that need no file, so a bad command line fails before any work
// (the output path is checked by the caller).
void check_args(const ParamArgs& a);
// Validates `data`: several components allowed (charts), or only the largest kept.
Mesh validated_mesh(const ParamArgs& a, const MeshData& data);

// What a run solved: the map, and the optimizers' own results when used.
struct Solved {
  ParamResult map;
  nlohmann::json optimal_lambda, boundary_optimization;  // null unless used
};

// The constraints of `a` (file or given), face points in mesh.F's corner order.
Constraints load_constraints(const ParamArgs& a, const MeshData& data, const Mesh& mesh);
Solved solve(const ParamArgs& a, const Mesh& mesh, const MeshData& data, const ParamOptions& options);
// The report without timings_ms (docs/formats.md "Report").
nlohmann::json build_report(const ParamArgs& a, const Mesh& mesh, const Solved& s, const DistortionSummary& d);

}  // namespace intrinsic::app
