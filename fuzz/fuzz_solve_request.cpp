// Fuzzes the browser editor's request path (docs/cli.md "intrinsic serve"): every
// body goes through parse_solve_request (`POST /api/solve`) and, when
// accepted, through one EditSession (the server's per-tab engine), whose
// state carries over between inputs as a long-lived tab's does; the same
// body also goes through the parsers of `POST /api/optimal_lambda` and
// `POST /api/optimize_boundary` and, when accepted, through the session's
// boundary_after (where those optimizations start). The mesh is a bumped
// 5 x 5 vertex grid (vertex y * 5 + x; two faces per quad).
#include "fuzz_support.h"
#include "intrinsic/mesh.h"
#include "intrinsic/edit_session.h"
#include "serve/optimize_request.h"
#include "serve/solve_request.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace intrinsic;
  static const Mesh mesh = fuzz::bumped_grid(false);
  static app::EditSession session(mesh);
  const std::string body(reinterpret_cast<const char*>(data), size);
  fuzz::expect_only_error([&] {
    const app::SolveRequest request = app::parse_solve_request(body, mesh, mesh.F);
    session.solve(request);
  });
  fuzz::expect_only_error([&] {
    const app::OptimalLambdaRequest request = app::parse_optimal_lambda_request(body, mesh, mesh.F);
    if (!request.solve.moves.empty()) session.boundary_after(request.solve);
  });
  return fuzz::expect_only_error([&] {
    const app::OptimizeBoundaryRequest request = app::parse_optimize_boundary_request(body, mesh, mesh.F);
    if (!request.solve.moves.empty()) session.boundary_after(request.solve);
  });
}
