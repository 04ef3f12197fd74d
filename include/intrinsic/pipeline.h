// The product as one typed pipeline: what `intrinsic param` and `intrinsic
// atlas` do between their command lines and their output files, callable
// from C++ (and under the command line, the Python module and the server).
// A request says what to solve (the library's option structs, enums, pins
// and constraints as values); a job reads or takes the mesh, validates it,
// solves (charts, optimal lambda, boundary optimization or constraints) and
// measures the result; the report functions give the JSON report of
// docs/formats.md "Report" and docs/cli.md, built from the outcome only.
// The param job may write its mesh itself (ParamRequest::output), while it
// measures the map on the other core; otherwise writing stays with the
// caller: write_mesh (io.h) / write_atlas_file (atlas_files.h).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "intrinsic/atlas.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/boundary_optimization.h"
#include "intrinsic/constraints.h"
#include "intrinsic/io.h"
#include "intrinsic/mesh.h"
#include "intrinsic/metrics.h"
#include "intrinsic/optimal_lambda.h"
#include "intrinsic/parameterize.h"
#include "intrinsic/texture_transfer.h"

namespace intrinsic {


// A pin written as text, "VERTEX:U,V" (e.g. "12:0.5,0"). Malformed text is
// Error(Usage) naming the option as `spelling` writes it; the vertex range is
// checked against the mesh by the solve (an input error).
FixedVertex parse_pin(const std::string& text, OptionSpelling spelling = OptionSpelling::Keyword);

// The blend of `method` with the lambda and mu a user gave (nullopt: not
// given): mixed needs at least one, other methods none, not both zero.
// Throws Error(Usage) naming the options as `spelling` writes them.
WeightOptions weight_options(Method method, std::optional<double> lambda, std::optional<double> mu,
                             OptionSpelling spelling = OptionSpelling::Keyword);

// --- parameterize (`intrinsic param`) ----------------------------------

struct ParamRequest {
  // Weights, boundary shape, spacing, scale, holes, pins, solver, residual
  // bound. BoundaryShape::Given with `boundary_file` set: the positions are
  // read from that file once the mesh is validated.
  ParamOptions options;
  std::string boundary_file;
  // At most one optimizer; it needs a single component and no constraints.
  // Its options' `base` is ignored (`options` is used).
  ChartOptimizer optimizer = ChartOptimizer::None;
  OptimalLambdaOptions optimal_lambda;                // energy, lo, hi
  BoundaryOptimizationOptions boundary_optimization;  // energy, route, descent, iterations, tolerance, progress
  // Point and line constraints: in memory, or read from `constraints_file`.
  std::optional<Constraints> constraints;
  std::string constraints_file;
  // Keep only the component with the most faces; otherwise every component
  // becomes a chart.
  bool largest_component = false;
  ReadOptions read;  // limits when reading a file
  OptionSpelling spelling = OptionSpelling::Keyword;
  // When set, the job writes the map there (write_mesh with `write`) while
  // the distortion summary is computed on another thread; a failed write
  // throws Error(Output) and leaves no file.
  std::string output;
  WriteOptions write;

  bool has_constraints() const { return constraints.has_value() || !constraints_file.empty(); }
};

// Usage checks that need no mesh (combinations, ranges); the jobs call it
// first, so a bad request fails before any work.
void check_param_request(const ParamRequest& request);

struct ParamOutcome {
  Mesh mesh;       // validated (and reduced to the largest component when asked)
  ParamResult map;  // UV per row of mesh.V, plus how it was solved
  std::optional<OptimalLambdaResult> optimal_lambda;                // when used (its map is `map`)
  std::optional<BoundaryOptimizationResult> boundary_optimization;  // when used (its map is `map`)
  DistortionSummary distortion;                                     // of `map` on `mesh`
  double read_ms = 0, validate_ms = 0;  // the solve's own stages are in map.timings
  // Both start when the solve ends and run at the same time (write_ms is 0
  // without request.output): the job's wall time after the solve is the
  // larger of the two, not their sum.
  double write_ms = 0, metrics_ms = 0;
};

// From a file (read with request.read) or from arrays.
ParamOutcome parameterize_file(const std::string& path, const ParamRequest& request);
ParamOutcome parameterize_data(const MeshData& data, const ParamRequest& request);

// The job's steps, for callers that keep a Parameterizer between solves
// (the Python module's Parameterizer): the validated mesh (largest
// component when asked), the options with the boundary file read, and the
// constraints (given or read) with face points in mesh.F's corner order
// (`file_faces`: the faces as given, which the barycentrics refer to).
Mesh validated_mesh(const MeshData& data, const ParamRequest& request);
ParamOptions resolved_options(const ParamRequest& request, const Mesh& mesh);
Constraints resolved_constraints(const ParamRequest& request, const MatrixX3i& file_faces, const Mesh& mesh);

// The report of `intrinsic param --report` (docs/formats.md "Report"):
// "output" is `output` (null when empty), "input" the mesh's path (null
// when empty); timings_ms holds read, validate, assemble, factor and solve,
// to which a caller adds its own stages (render, write, total).
// As JSON text (the shells add their keys with their own JSON reader).
std::string param_report(const ParamRequest& request, const ParamOutcome& outcome, const std::string& output);

// --- atlas (`intrinsic atlas`) -------------------------------------------

struct AtlasRequest {
  AtlasOptions options;
  std::string seams_file;  // read against the mesh into options.seams when set
  ReadOptions read;        // limits when reading a file
  // Bake the textures that read the replaced UV set into the new layout
  // when the atlas is written (write_atlas_with_textures, texture_transfer.h);
  // checked with the request, before any work.
  TextureTransferOptions textures;
  // How the atlas is written into a glTF input (write_atlas_with_textures):
  // gltf.texcoord_set is also, with options.pack_only, the TEXCOORD_n set
  // re-packed (-1: 0), and with textures.enabled the set the atlas replaces.
  GltfWriteOptions gltf;
  // Where the atlas will be written, when known: a request that cannot be
  // written there is refused before any work.
  std::string output;
};

struct AtlasOutcome {
  // The input as read (with its document, which the atlas writers give
  // back) or given (no document).
  MeshFile input;
  AtlasOptions options;  // as run (seams included)
  AtlasResult result;
  double read_ms = 0;  // reading the mesh and the seams file
};

AtlasOutcome atlas_file(const std::string& path, const AtlasRequest& request);
AtlasOutcome atlas_data(MeshData data, const AtlasRequest& request);

// The report of `intrinsic atlas --report` (docs/cli.md "intrinsic atlas"):
// "input" is the input's path and "output" `output` (null when empty);
// timings_ms holds read, clean, segment, flatten, merge and pack, to which a
// caller adds its own (write, total).
// As JSON text.
std::string atlas_report(const AtlasOutcome& outcome, const std::string& output);

}  // namespace intrinsic
