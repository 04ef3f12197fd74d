// `intrinsic metrics`: the distortion report for any mesh that has UVs.
#include <iostream>

#include "command.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "intrinsic/metrics.h"
#include "report.h"
#include "uv_mesh.h"

namespace intrinsic::app {

void register_metrics(CLI::App& app, Runner& run) {
  struct Args {
    std::string input, report;
    std::int64_t max_vertices = ReadOptions().max_vertices;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("metrics", "Distortion report of a mesh with UVs (OBJ vt or PLY u,v)");
  cmd->add_option("input", args->input, "Mesh with texture coordinates (.obj, .off, .ply, optionally .gz)")->required();
  cmd->add_option("--report", args->report, "Write the report as JSON to this file (default: print it)");
  cmd->add_option("--max-vertices", args->max_vertices, "Refuse inputs with more vertices")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->callback([&run, args] {
    run = [args] {
      const auto t0 = std::chrono::steady_clock::now();
      ReadOptions ro;
      ro.max_vertices = args->max_vertices;
      ro.max_faces = faces_for_vertices(ro.max_vertices);
      const MeshData data = read_mesh(args->input, ro);
      // Distortion is per face, so the UV of a corner is what matters.
      const UvMesh uv = split_by_texcoord(data);
      MeshData by_tc;
      by_tc.V = uv.V;
      by_tc.F = uv.F;
      by_tc.path = data.path;
      ValidateOptions vo;
      vo.allow_several_components = true;
      vo.allow_closed = true;
      // Validation catches degenerate faces; orientation is kept as listed so
      // flipped triangles are reported, not repaired.
      const Mesh mesh = make_mesh(by_tc, vo);
      nlohmann::json report = mesh_json(mesh);
      report["vertices"] = data.V.rows();
      const DistortionSummary d = summarize_distortion(uv.V, uv.F, uv.UV);
      add_distortion(report, d);
      report["timings_ms"] = {{"total", elapsed_ms(t0)}};
      if (args->report.empty()) std::cout << report.dump(2) << "\n";
      else write_report(args->report, report);
      return 0;
    };
  });
}

}  // namespace intrinsic::app
