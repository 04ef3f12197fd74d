// The atlas's stages on small assets, in one process: compute_charts and
// pack_charts (atlas.h) run `--runs` times each on every mesh given, with
// the medians of their wall time per stage and of the process CPU time they
// used (all threads: the figure a loaded machine disturbs least). For the
// fixed costs of small assets (docs/performance.md#the-atlas); the whole
// comparison with xatlas is bench/atlas_compare.py.
#include <ctime>
#include <iostream>
#include <string>
#include <vector>

#include "bench_timing.h"
#include "intrinsic/atlas.h"
#include "intrinsic/io.h"

namespace {

double cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace intrinsic;
  int runs = 5;
  std::vector<std::string> paths;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--runs" && i + 1 < argc) runs = std::max(1, std::stoi(argv[++i]));
    else paths.push_back(a);
  }
  if (paths.empty()) {
    std::cerr << "usage: atlas_stage_bench [--runs N] MESH...\n";
    return 2;
  }
  const AtlasOptions options;
  std::cout << "mesh, faces, charts, flatten ms, merge ms, charts cpu ms, pack ms, pack cpu ms (medians of " << runs
            << ")\n";
  for (const std::string& path : paths) {
    const MeshData mesh = read_mesh(path);
    std::vector<double> flatten, merge, charts_cpu, pack, pack_cpu;
    AtlasCharts c;
    for (int r = 0; r < runs; ++r) {
      const double c0 = cpu_ms();
      c = compute_charts(mesh, options.charts);
      charts_cpu.push_back(cpu_ms() - c0);
      flatten.push_back(c.timings.flatten_ms);
      merge.push_back(c.timings.merge_ms);
    }
    for (int r = 0; r < runs; ++r) {
      const double c0 = cpu_ms();
      const auto t0 = std::chrono::steady_clock::now();
      const AtlasResult a = pack_charts(c, pack_options(options));
      pack.push_back(bench::ms_since(t0));
      pack_cpu.push_back(cpu_ms() - c0);
    }
    std::cout << path << ", " << mesh.F.rows() << ", " << c.charts.size() << ", " << bench::median(flatten) << ", "
              << bench::median(merge) << ", " << bench::median(charts_cpu) << ", " << bench::median(pack) << ", "
              << bench::median(pack_cpu) << "\n";
  }
  return 0;
}
