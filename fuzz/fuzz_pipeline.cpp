// Fuzzes the whole pipeline on small inputs: read, validate, parameterize,
// measure distortion. Input layout: one option byte, then the mesh file, then
// optionally "\n===\n" and a boundary file (positions for BoundaryShape::Given).
//   option bits 0-1: format (obj, off, ply, obj)
//   bits 2-4: method (conformal, authalic, mixed, tutte, floater)
//   bit 5: square boundary, bit 6: free holes, bit 7: uniform spacing
#include <cstring>

#include "fuzz_support.h"
#include "intrinsic/io.h"
#include "intrinsic/metrics.h"
#include "intrinsic/parameterize.h"
#include "intrinsic/mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace intrinsic;
  if (size < 1 || size > 4096) return 0;  // keep each execution fast
  const std::uint8_t opt = data[0];
  std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  std::string boundary;
  if (const std::size_t sep = text.find("\n===\n"); sep != std::string::npos) {
    boundary = text.substr(sep + 5);
    text.resize(sep + 1);
  }
  static const char* const kNames[] = {"fuzz.obj", "fuzz.off", "fuzz.ply", "fuzz.obj"};
  static const Method kMethods[] = {Method::Conformal, Method::Authalic, Method::Mixed, Method::Tutte,
                                    Method::Floater,   Method::Conformal, Method::Authalic, Method::Mixed};
  return fuzz::expect_only_error([&] {
    const MeshData m = read_mesh_from_memory(text, kNames[opt & 3], fuzz::small_limits());
    const Mesh mesh = make_mesh(m);
    ParamOptions o;
    o.weights.method = kMethods[(opt >> 2) & 7];
    if (o.weights.method == Method::Mixed) o.weights.lambda = 0.5, o.weights.mu = 0.5;
    o.boundary = (opt & 32) ? BoundaryShape::Square : BoundaryShape::Circle;
    o.holes = (opt & 64) ? HoleRule::Free : HoleRule::Fill;
    o.spacing = (opt & 128) ? Spacing::Uniform : Spacing::ArcLength;
    if (!boundary.empty()) {
      o.boundary = BoundaryShape::Given;
      o.given = parse_boundary_text(boundary, "fuzz-boundary.txt", static_cast<int>(mesh.V.rows()));
    }
    const ParamResult r = parameterize(mesh, o);
    summarize_distortion(mesh.V, mesh.F, r.UV);
  });
}
