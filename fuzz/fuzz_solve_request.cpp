// Fuzzes the browser editor's request path (`POST /api/solve`, README
// "intrinsic serve"): every body goes through parse_solve_request and, when
// accepted, through one EditSession (the server's per-tab engine), whose
// state carries over between inputs as a long-lived tab's does. The mesh is
// a bumped 5 x 5 vertex grid (vertex y * 5 + x; two faces per quad).
#include "fuzz_support.h"
#include "intrinsic/mesh.h"
#include "serve/edit_session.h"
#include "serve/solve_request.h"

namespace {

intrinsic::Mesh bumped_grid() {
  using namespace intrinsic;
  MatrixX3d V(25, 3);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x) V.row(y * 5 + x) << x, y, 0.3 * ((x * y) % 3);
  MatrixX3i F(32, 3);
  int f = 0;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const int a = y * 5 + x;
      F.row(f++) << a, a + 1, a + 6;
      F.row(f++) << a, a + 6, a + 5;
    }
  return make_mesh(V, F);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace intrinsic;
  static const Mesh mesh = bumped_grid();
  static app::EditSession session(mesh);
  return fuzz::expect_only_error([&] {
    const std::string body(reinterpret_cast<const char*>(data), size);
    const app::SolveRequest request = app::parse_solve_request(body, mesh, mesh.F);
    session.solve(request);
  });
}
