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
#include "intrinsic/io.h"
#include "intrinsic/constraints.h"
#include "intrinsic/parameterizer.h"
#include "intrinsic/mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace intrinsic;
  static const Mesh mesh = fuzz::bumped_grid(true);
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
