// The parameterize job of pipeline.h (`intrinsic param` without its command
// line): request checks, reading and validating the mesh, the solve (charts
// for several components, optimal lambda (paper section 5.1), boundary
// optimization (section 5.2), constraints) and the distortion summary, with
// the output mesh written at the same time when the request names one.
#include <chrono>
#include <cstdio>
#include <future>

#include "intrinsic/charts.h"
#include "intrinsic/error.h"
#include "intrinsic/parameterizer.h"
#include "intrinsic/pipeline.h"
#include "mesh/topology_build.h"
#include "util/stopwatch.h"

namespace intrinsic {
using detail::ms_since;
namespace {

using Clock = std::chrono::steady_clock;

Mesh checked(const MeshData& data, const ValidateOptions& vo) { return make_mesh(data, vo); }
Mesh checked(MeshData&& data, const ValidateOptions& vo) { return detail::make_mesh_taking(std::move(data), vo); }

// Several components allowed (charts), or only the largest kept. `Data`:
// a MeshData to copy from, or one to take over.
template <class Data>
Mesh validate(Data&& data, const ParamRequest& r) {
  ValidateOptions vo;
  vo.allow_several_components = true;
  vo.allow_closed = r.largest_component;  // a closed small piece may be dropped; the kept one is checked later
  Mesh mesh = checked(std::forward<Data>(data), vo);
  if (r.largest_component && mesh.topology.num_components > 1) {
    const int reoriented = mesh.validation.reoriented_faces;
    mesh = make_mesh(component_data(mesh, largest_component(mesh)));
    mesh.validation.reoriented_faces = reoriented;
  }
  return mesh;
}

}  // namespace

Mesh validated_mesh(const MeshData& data, const ParamRequest& r) { return validate(data, r); }

ParamOptions resolved_options(const ParamRequest& r, const Mesh& mesh) {
  ParamOptions options = r.options;
  if (options.boundary == BoundaryShape::Given && !r.boundary_file.empty())
    options.given = read_boundary_file(r.boundary_file, static_cast<int>(mesh.V.rows()));
  return options;
}

Constraints resolved_constraints(const ParamRequest& r, const MatrixX3i& file_faces, const Mesh& mesh) {
  Constraints c = r.constraints ? *r.constraints : read_constraints_file(r.constraints_file);
  match_face_corners(c, file_faces, mesh);
  return c;
}

namespace {

void solve_optimal_lambda(const ParamRequest& r, const ParamOptions& options, ParamOutcome& out) {
  OptimalLambdaOptions lo = r.optimal_lambda;
  lo.base = options;
  OptimalLambdaResult best = optimal_lambda(out.mesh, lo);
  out.map = std::move(best.map);
  best.map = ParamResult();
  out.optimal_lambda = std::move(best);
}

void solve_boundary_optimization(const ParamRequest& r, const ParamOptions& options, ParamOutcome& out) {
  BoundaryOptimizationOptions bo = r.boundary_optimization;
  bo.base = options;
  BoundaryOptimizationResult best = optimize_boundary(out.mesh, bo);
  out.map = std::move(best.map);
  best.map = ParamResult();
  out.boundary_optimization = std::move(best);
}

void solve(const ParamRequest& r, const MeshData& data, const ParamOptions& options, ParamOutcome& out) {
  const auto label = [&](std::string_view key) { return option_label(key, r.spelling); };
  if (out.mesh.topology.num_components > 1) {
    if (r.optimizer != ChartOptimizer::None || r.has_constraints())
      throw_usage(label("optimize_lambda") + ", " + label("optimize_boundary") + " and " + label("constraints") +
                  " take a single component; use " + label("largest_component"));
    out.map = parameterize_charts(out.mesh, options);
    return;
  }
  if (r.optimizer == ChartOptimizer::OptimalLambda) return solve_optimal_lambda(r, options, out);
  if (r.optimizer == ChartOptimizer::OptimizeBoundary) return solve_boundary_optimization(r, options, out);
  Parameterizer parameterizer(out.mesh, options);
  if (r.has_constraints()) parameterizer.set_constraints(resolved_constraints(r, data.F, out.mesh));
  out.map = parameterizer.solve();
}

// The distortion summary, and the output mesh when asked, side by side:
// the writer's last steps and the summary's serial sums each leave a core
// idle that the other can use. The summary stays on this thread: its arrays
// (80 MB at 1M) then come from the main malloc arena, which gives them back,
// where a worker's arena would keep them resident.
void measure_and_write(const ParamRequest& r, ParamOutcome& out) {
  const auto t0 = Clock::now();
  if (r.output.empty()) {
    out.distortion = summarize_distortion(out.mesh.V, out.mesh.F, out.map.UV);
    out.metrics_ms = ms_since(t0);
    return;
  }
  // The future's destructor waits for the write, so an exception here
  // leaves no thread behind; a failed write is rethrown by get().
  std::future<double> written = std::async(std::launch::async, [&] {
    write_mesh(r.output, out.mesh.V, out.mesh.F, out.map.UV, r.write);
    return ms_since(t0);
  });
  try {
    out.distortion = summarize_distortion(out.mesh.V, out.mesh.F, out.map.UV);
  } catch (...) {
    written.wait();
    std::remove(r.output.c_str());  // no output without its outcome
    throw;
  }
  out.metrics_ms = ms_since(t0);
  out.write_ms = written.get();
}

// `owned`: the caller's copy of `data` (the file just read), emptied once the
// mesh is validated: at 1M vertices it is 56 MB that the factorization need
// not carry. Only the file's faces stay, for constraints (which name them).
ParamOutcome run(const MeshData& data, const ParamRequest& r, double read_ms, MeshData* owned = nullptr) {
  ParamOutcome out;
  out.read_ms = read_ms;
  const auto t0 = Clock::now();
  if (owned) {
    // The mesh takes the file's arrays over; validation may reorient its
    // faces, so constraints (which name the file's faces) keep a copy.
    MatrixX3i file_faces;
    if (r.has_constraints()) file_faces = owned->F;
    MeshData taken = std::move(*owned);
    *owned = MeshData();
    out.mesh = validate(std::move(taken), r);
    owned->F.swap(file_faces);
  } else {
    out.mesh = validate(data, r);
  }
  out.validate_ms = ms_since(t0);
  solve(r, data, resolved_options(r, out.mesh), out);
  measure_and_write(r, out);
  return out;
}

}  // namespace

void check_param_request(const ParamRequest& r) {
  const auto label = [&](std::string_view key) { return option_label(key, r.spelling); };
  if (!(r.options.max_residual > 0)) throw_usage(label("max_residual") + " must be a positive number");
  const bool lambda = r.optimizer == ChartOptimizer::OptimalLambda;
  const bool boundary = r.optimizer == ChartOptimizer::OptimizeBoundary;
  if (r.has_constraints() && (lambda || boundary))
    throw_usage(label("constraints") + " cannot be combined with " + label("optimize_lambda") + " or " +
                label("optimize_boundary"));
  if (lambda && r.options.weights.method != Method::Conformal)
    throw_usage(label("optimize_lambda") + " chooses the blend itself; do not give " + label("method") + ", " +
                label("lambda") + " or " + label("mu"));
  if (!r.options.pins.empty() && r.options.boundary != BoundaryShape::Natural)
    throw_usage(label("pins") + " applies to " + label("boundary") + " natural only");
  if (r.options.pins.size() == 1)
    throw_usage(label("pins") + " needs at least two pins (translation, rotation and scale)");
  if (boundary && r.boundary_optimization.max_iterations < 0)
    throw_usage(label("iterations") + ": must be >= 0, got " + std::to_string(r.boundary_optimization.max_iterations));
}

ParamOutcome parameterize_file(const std::string& path, const ParamRequest& request) {
  check_param_request(request);
  const auto t0 = Clock::now();
  MeshData data = read_mesh(path, request.read);
  return run(data, request, ms_since(t0), &data);
}

ParamOutcome parameterize_data(const MeshData& data, const ParamRequest& request) {
  check_param_request(request);
  return run(data, request, 0.0);
}

}  // namespace intrinsic
