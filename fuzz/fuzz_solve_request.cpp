// Fuzzes the browser editor's request path (`POST /api/solve`, README
// "intrinsic serve"): every body goes through parse_solve_request and, when
// accepted, through one EditSession (the server's per-tab engine), whose
// state carries over between inputs as a long-lived tab's does. The mesh is
// a bumped 5 x 5 vertex grid (vertex y * 5 + x; two faces per quad).
#include "fuzz_support.h"
#include "intrinsic/mesh.h"
#include "serve/edit_session.h"
#include "serve/solve_request.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace intrinsic;
  static const Mesh mesh = fuzz::bumped_grid(false);
  static app::EditSession session(mesh);
  return fuzz::expect_only_error([&] {
    const std::string body(reinterpret_cast<const char*>(data), size);
    const app::SolveRequest request = app::parse_solve_request(body, mesh, mesh.F);
    session.solve(request);
  });
}
