// What keeping an OBJ's normals, materials, groups and smoothing groups costs
// (src/io/obj_extras.h, docs/formats.md "OBJ"): reading a large generated OBJ
// of quads and writing its atlas OBJ, plain (v, f only) or carrying all of it
// (vn per corner, usemtl/g/s every few rows, two mtllib lines). The atlas is
// not computed (one UV per vertex stands in for it): only the reader and the
// writer are timed. One case per process, so that the peak resident memory
// (ru_maxrss) is the case's own.
//   obj_io_bench [--quads-per-side N] [--runs R] [--case plain|extras] [--workdir DIR]
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_timing.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/io.h"

using namespace intrinsic;
using Clock = std::chrono::steady_clock;

namespace {

using intrinsic::bench::median;
using intrinsic::bench::ms_since;

// An n x n grid of quads on a wavy sheet, with (extras) one normal per vertex
// and a material, group and smoothing group change every 64 rows.
void write_grid_obj(const std::string& path, int n, bool extras) {
  std::ofstream out(path, std::ios::binary);
  char line[160];
  if (extras) out << "mtllib a.mtl\nmtllib b.mtl\n";
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = double(i) / n, y = double(j) / n;
      std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", x, y, 0.05 * (x * x - y * y));
      out << line;
    }
  if (extras)
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        const double x = double(i) / n, y = double(j) / n;
        std::snprintf(line, sizeof line, "vn %.9g %.9g 1\n", -0.1 * x, 0.1 * y);
        out << line;
      }
  for (int i = 0; i < n; ++i) {
    if (extras && i % 64 == 0)
      out << "g rows_" << i << "\nusemtl m" << (i / 64) % 3 << "\ns " << (i / 64) % 2 << "\n";
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j + 1, b = a + n + 1;
      if (extras)
        std::snprintf(line, sizeof line, "f %d//%d %d//%d %d//%d %d//%d\n", a, a, b, b, b + 1, b + 1, a + 1, a + 1);
      else
        std::snprintf(line, sizeof line, "f %d %d %d %d\n", a, b, b + 1, a + 1);
      out << line;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  int n = 1000, runs = 3;
  std::string which = "plain", workdir = "/tmp";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--quads-per-side") n = std::stoi(next());
    else if (a == "--runs") runs = std::stoi(next());
    else if (a == "--case") which = next();
    else if (a == "--workdir") workdir = next();
    else {
      std::cerr << "usage: obj_io_bench [--quads-per-side N] [--runs R] [--case plain|extras] [--workdir DIR]\n";
      return 2;
    }
  }
  const bool extras = which == "extras";
  const std::string in = workdir + "/obj_io_bench_in.obj", out = workdir + "/obj_io_bench_out.obj";
  write_grid_obj(in, n, extras);
  std::vector<double> read_ms, write_ms;
  for (int run = 0; run < runs; ++run) {
    auto t = Clock::now();
    const MeshFile file = read_mesh_file(in);  // the extras are what the writer gives back
    const MeshData& m = file.mesh;
    read_ms.push_back(ms_since(t));
    AtlasResult r;  // one UV per vertex stands in for an atlas
    r.UV = m.V.leftCols(2);
    r.F = m.F;
    r.FUV = m.F;
    t = Clock::now();
    write_atlas_obj(out, file, r);
    write_ms.push_back(ms_since(t));
  }
  struct rusage ru {};
  getrusage(RUSAGE_SELF, &ru);
  std::printf("%s: %d x %d quads (%d triangles), read %.1f ms, write %.1f ms (medians of %d), peak RSS %.1f MB\n",
              which.c_str(), n, n, 2 * n * n, median(read_ms), median(write_ms), runs, ru.ru_maxrss / 1024.0);
  std::remove(in.c_str());
  std::remove(out.c_str());
  return 0;
}
