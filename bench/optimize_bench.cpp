// Timings of the paper's section 5 optimizers (not a test): near-optimal
// lambda (two solves + O(edges)) and boundary optimization by L-BFGS with
// adjoint or response gradients. Prints one markdown row per case, medians
// of `runs` repetitions.
//   optimize_bench [runs] [mesh files...]
// Always runs the generated sphere strip of the paper's Figure 7.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_timing.h"
#include "intrinsic/boundary_optimization.h"
#include "intrinsic/generate.h"
#include "intrinsic/io.h"
#include "intrinsic/metrics.h"
#include "intrinsic/optimal_lambda.h"

using namespace intrinsic;

namespace {

using intrinsic::bench::median;
using intrinsic::bench::ms_since;

void run_mesh(const std::string& name, const Mesh& mesh, int runs) {
  for (LambdaEnergy e : {LambdaEnergy::EdgeLength, LambdaEnergy::Area}) {
    std::vector<double> t;
    OptimalLambdaResult r;
    for (int k = 0; k < runs; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      OptimalLambdaOptions o;
      o.energy = e;
      r = optimal_lambda(mesh, o);
      t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    std::printf("| %s | lambda* (%s) | lambda*=%.4f | E(0)=%.6g E(1)=%.6g E*=%.6g | %.0f ms |\n", name.c_str(),
                e == LambdaEnergy::EdgeLength ? "edge" : "area", r.lambda, r.energy_at_0, r.energy_at_1, r.energy,
                median(t));
  }
  for (BoundaryEnergy e : {BoundaryEnergy::EdgeLength, BoundaryEnergy::Area, BoundaryEnergy::SymmetricDirichlet})
    for (GradientRoute g : {GradientRoute::Adjoint, GradientRoute::Responses}) {
      std::vector<double> t;
      BoundaryOptimizationResult r;
      for (int k = 0; k < runs; ++k) {
        BoundaryOptimizationOptions o;
        o.energy = e;
        o.route = g;
        const auto t0 = std::chrono::steady_clock::now();
        r = optimize_boundary(mesh, o);
        t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      }
      const char* en = e == BoundaryEnergy::EdgeLength ? "edge" : e == BoundaryEnergy::Area ? "area" : "dirichlet";
      std::printf("| %s | boundary (%s, %s) | %d iterations, %d solves, %d flips | E %.6g -> %.6g | %.0f ms |\n",
                  name.c_str(), en, g == GradientRoute::Adjoint ? "adjoint" : "responses", r.iterations, r.solves,
                  r.flipped_final, r.energy_history.front(), r.energy_history.back(), median(t));
    }
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  std::printf("| mesh | optimizer | result | energy | time (median of %d) |\n|---|---|---|---|---|\n", runs);
  GenerateOptions g;
  g.rings = 20;
  g.jitter = 0.5;
  const Mesh strip = make_mesh(generate_sphere_strip(g));
  run_mesh("sphere strip (" + std::to_string(strip.V.rows()) + " V, Fig. 7)", strip, runs);
  for (int i = 2; i < argc; ++i) {
    const Mesh mesh = make_mesh(read_mesh(argv[i]));
    const std::string path = argv[i];
    run_mesh(path.substr(path.find_last_of('/') + 1), mesh, runs);
  }
  return 0;
}
