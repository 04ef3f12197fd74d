// Fuzzes the constraint file and what `param --constraints` does with it, on
// a fixed small mesh: parse_constraints_json, match_face_corners,
// resolve_constraints (the line walks), Parameterizer::set_constraints and
// solve. The mesh is a bumped 5 x 5 vertex grid without its quad at (1, 1),
// so paths can leave the surface through that hole as well as through the
// outer boundary (vertex y * 5 + x; two faces per quad, row by row, the hole
// skipped: 30 faces, as fuzz/make_corpus.py assumes for the seeds).
// The map is picked by the input size modulo 3 (circle conformal, natural
// boundary, square mixed), so every seed stays a plain JSON file.
#include "fuzz_support.h"
#include "intrinsic/constraints.h"
#include "intrinsic/parameterizer.h"
#include "intrinsic/mesh.h"

namespace {

intrinsic::Mesh grid_with_hole() {
  using namespace intrinsic;
  MatrixX3d V(25, 3);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x) V.row(y * 5 + x) << x, y, 0.3 * ((x * y) % 3);
  MatrixX3i F(30, 3);
  int f = 0;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      if (x == 1 && y == 1) continue;  // the hole
      const int a = y * 5 + x;
      F.row(f++) << a, a + 1, a + 6;
      F.row(f++) << a, a + 6, a + 5;
    }
  return make_mesh(V, F);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace intrinsic;
  static const Mesh mesh = grid_with_hole();
  return fuzz::expect_only_error([&] {
    Constraints c = parse_constraints_json(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
    match_face_corners(c, mesh.F, mesh);
    std::vector<LinearConstraint> rows = resolve_constraints(mesh, c);
    ParamOptions o;
    if (size % 3 == 1) o.boundary = BoundaryShape::Natural;
    if (size % 3 == 2) {
      o.boundary = BoundaryShape::Square;
      o.weights.method = Method::Mixed;
      o.weights.lambda = 0.5;
      o.weights.mu = 0.5;
    }
    Parameterizer p(mesh, o);
    p.set_constraints(std::move(rows));
    p.solve();
  });
}
