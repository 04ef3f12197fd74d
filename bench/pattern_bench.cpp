// The weight matrix's pattern and the free block's pattern (the ordering
// thread's input) at one size: what building the free block from the faces
// (util/vertex_adjacency.h on the free vertices) costs against taking it
// from K's pattern (solve/ordering_ahead.h), the choice the Parameterizer's
// "pattern counted once" rests on (docs/performance.md#symbolic-analysis).
// Each piece on one thread and on all cores, alternately, medians of R runs of
// wall time and of process CPU time; plus the counts they handle.
//
//   pattern_bench [N] [R]    N vertices (generated wavy patch, 1000000), R runs (5)
#include <time.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench_timing.h"
#include "intrinsic/generate.h"
#include "intrinsic/mesh.h"
#include "solve/ordering_ahead.h"
#include "util/parallel_for.h"
#include "weights/assemble_stages.h"

using namespace intrinsic;

namespace {

double cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

template <class Fn>
void row(const char* what, int threads, int runs, Fn&& fn) {
  detail::thread_limit() = threads;
  std::vector<double> wall, cpu;
  long nnz = 0;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = cpu_ms();
    const SparseMatrix P = fn();
    cpu.push_back(cpu_ms() - c0);
    wall.push_back(bench::ms_since(t0));
    nnz = static_cast<long>(P.nonZeros());
  }
  detail::thread_limit() = 0;
  std::printf("| %s | %s | %.1f | %.1f | %ld |\n", what, threads == 1 ? "1" : "all", bench::median(wall),
              bench::median(cpu), nnz);
}

}  // namespace

int main(int argc, char** argv) {
#ifdef INTRINSIC_HAVE_SUITESPARSE
  const int n = argc > 1 ? std::atoi(argv[1]) : 1000000;
  const int runs = argc > 2 ? std::atoi(argv[2]) : 5;
  GenerateOptions g;
  g.rings = std::max(2, static_cast<int>(std::lround(std::sqrt(n / 3.0))));
  const Mesh mesh = make_mesh(generate_wavy_patch(g));
  const int nv = static_cast<int>(mesh.V.rows());
  std::vector<char> known(nv, 0), used(mesh.topology.is_used.begin(), mesh.topology.is_used.end());
  for (int v : mesh.topology.boundary_loops[0]) known[v] = 1;
  std::printf("%d vertices, %ld faces, %zu known\n\n", nv, static_cast<long>(mesh.F.rows()),
              mesh.topology.boundary_loops[0].size());
  std::printf("| piece | threads | wall ms | CPU ms | nnz |\n|---|---|---|---|---|\n");
  const SparseMatrix K = detail::weight_matrix_pattern(mesh.F, nv);
  for (int round = 0; round < 2; ++round)
    for (int threads : {1, 0}) {
      row("K's pattern from the faces", threads, runs, [&] { return detail::weight_matrix_pattern(mesh.F, nv); });
      row("free block from the faces", threads, runs,
          [&] { return detail::free_block_pattern(mesh.F, known, used); });
      row("free block from K's pattern", threads, runs,
          [&] { return detail::free_block_pattern(K, known, used); });
    }
  return 0;
#else
  (void)argc;
  (void)argv;
  std::fprintf(stderr, "pattern_bench needs SuiteSparse (the ordering ahead)\n");
  return 1;
#endif
}
