// What `intrinsic atlas IN -o OUT --report REPORT` does, written against the
// installed package (find_package(intrinsic)) through the public pipeline
// (include/intrinsic/pipeline.h): read the mesh, build its atlas, write the
// mesh with its UVs (.obj or .glb) and the JSON report.
// Usage: atlas_file IN OUT [REPORT]. Exit codes as the command line's.
#include <chrono>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "intrinsic/pipeline.h"

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: atlas_file IN OUT [REPORT]\n");
    return 1;
  }
  const std::string input = argv[1], output = argv[2], report = argc == 4 ? argv[3] : "";
  try {
    const auto t0 = std::chrono::steady_clock::now();
    intrinsic::check_atlas_output(output);
    intrinsic::AtlasRequest request;  // the command line's defaults
    request.read.max_faces = intrinsic::faces_for_vertices(request.read.max_vertices);
    const intrinsic::AtlasOutcome atlas = intrinsic::atlas_file(input, request);
    intrinsic::write_atlas_file(output, atlas.input, atlas.result);
    if (!report.empty()) {
      nlohmann::json j = nlohmann::json::parse(intrinsic::atlas_report(atlas, output));
      j["timings_ms"]["total"] =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      intrinsic::write_file_atomically(report, j.dump(2) + "\n");
    }
    std::printf("%s: %d charts, utilization %.2f\n", output.c_str(), static_cast<int>(atlas.result.charts.size()),
                atlas.result.utilization);
    return 0;
  } catch (const intrinsic::Error& e) {
    std::fprintf(stderr, "atlas_file: error: %s\n", e.what());
    return e.exit_code();
  }
}
