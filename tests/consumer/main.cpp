// Consumer of the installed package: parameterizes a generated disk and
// checks the result (exit 0 on success).
#include <cstdio>

#include "intrinsic/intrinsic.h"  // the front door: the whole public API must compile outside the tree
#include "intrinsic/error.h"
#include "intrinsic/generate.h"
#include "intrinsic/metrics.h"
#include "intrinsic/parameterize.h"

int main() {
  try {
    const intrinsic::Mesh mesh = intrinsic::make_mesh(intrinsic::generate_flat_disk(intrinsic::GenerateOptions{}));
    const intrinsic::ParamResult r = intrinsic::parameterize(mesh, intrinsic::ParamOptions{});
    const intrinsic::DistortionSummary d = intrinsic::summarize_distortion(mesh.V, mesh.F, r.UV);
    std::printf("consumer: %d vertices, residual %g, %d flipped\n", static_cast<int>(mesh.V.rows()), r.residual,
                d.flipped_triangles);
    return r.UV.rows() == mesh.V.rows() && d.flipped_triangles == 0 && r.residual < 1e-8 ? 0 : 1;
  } catch (const intrinsic::Error& e) {
    std::fprintf(stderr, "consumer: error: %s\n", e.what());
    return 2;
  }
}
