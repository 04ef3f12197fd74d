// `intrinsic metrics`: the distortion report for any mesh that has UVs.
#include <iostream>
#include <nlohmann/json.hpp>

#include "command.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "intrinsic/metrics.h"
#include "intrinsic/report.h"
#include "intrinsic/uv_mesh.h"

namespace intrinsic::app {

namespace {

// A chart covering fewer texels than this shows at most a blur of its texture.
constexpr int kSmallChartTexels = 16;

// The mesh's topology (boundary loops, components) when the UV-indexed mesh
// is a valid manifold mesh; otherwise (a triangle soup, a non-manifold or
// degenerate face) the reason, and the atlas figures still follow.
nlohmann::json uv_mesh_report(const UvMesh& uv, const MeshData& data) {
  MeshData by_tc;
  by_tc.V = uv.V;
  by_tc.F = uv.F;
  by_tc.path = data.path;
  ValidateOptions vo;
  vo.allow_several_components = true;
  vo.allow_closed = true;
  nlohmann::json report;
  try {
    // Orientation is kept as listed so flipped triangles are reported, not repaired.
    report = nlohmann::json::parse(mesh_report(make_mesh(by_tc, vo)));
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::Input) throw;
    report = {{"input", data.path}, {"faces", uv.F.rows()}, {"not_a_manifold_mesh", e.what()}};
  }
  report["vertices"] = data.V.rows();
  report["texture_coordinates"] = data.TC.rows();
  return report;
}

}  // namespace

void register_metrics(CLI::App& app, Runner& run) {
  struct Args {
    std::string input, report;
    std::int64_t max_vertices = ReadOptions().max_vertices;
    int resolution = 1024;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("metrics",
                                     "Distortion and atlas report (charts, flips per chart, overlaps, utilization) "
                                     "of a mesh with UVs (OBJ vt or PLY u,v)");
  cmd->add_option("input", args->input, "Mesh with texture coordinates (.obj, .off, .ply, optionally .gz)")->required();
  cmd->add_option("--report", args->report, "Write the report as JSON to this file (default: print it)");
  cmd->add_option("--max-vertices", args->max_vertices, "Refuse inputs with more vertices")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--resolution", args->resolution,
                  "Texture size for small_charts: charts covering fewer than 16 texels of it")
      ->check(CLI::Range(1, 1 << 20))
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
      nlohmann::json report = uv_mesh_report(uv, data);
      // Charts, flips per chart and overlaps work on any per-corner UVs,
      // soups and non-manifold meshes included.
      const UvAtlasMetrics atlas = uv_atlas_metrics(uv.V, uv.F, uv.UV);
      report["atlas"] = nlohmann::json::parse(atlas_metrics_report(atlas));
      report["atlas"]["seam_length"] = seam_length(uv);
      report["atlas"]["small_charts"] = small_charts(uv, atlas, args->resolution, kSmallChartTexels);
      report["atlas"]["small_chart_texels"] = kSmallChartTexels;
      report["atlas"]["resolution"] = args->resolution;
      const MatrixX2d unmirrored = unmirrored_uv(uv, atlas);
      report.update(nlohmann::json::parse(distortion_report(summarize_distortion(uv.V, uv.F, unmirrored))));
      report["stretch"] = nlohmann::json::parse(stretch_report(summarize_stretch(uv.V, uv.F, unmirrored)));
      report["timings_ms"] = {{"total", elapsed_ms(t0)}};
      if (args->report.empty()) std::cout << report.dump(2) << "\n";
      else write_file_atomically(args->report, report.dump(2) + "\n");
      return 0;
    };
  });
}

}  // namespace intrinsic::app
