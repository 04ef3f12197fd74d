// `intrinsic atlas` (issue 13): read any triangle mesh (closed, higher genus,
// several components, non-manifold bits, zero-area faces), build its atlas
// (atlas.h), write the input's vertices in input order with one `vt` per atlas
// UV and faces `f v/vt` (seams only through the per-corner texture
// coordinates), and the report.
#include <charconv>
#include <iostream>

#include "command.h"
#include "intrinsic/atlas.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "pictures.h"
#include <nlohmann/json.hpp>

namespace intrinsic::app {
namespace {

struct AtlasArgs {
  std::string input, output, report;
  AtlasOptions options;
  bool quiet = false;
  std::int64_t max_vertices = ReadOptions().max_vertices;
};

void put(std::string& s, double x) {
  char b[32];
  s.append(b, std::to_chars(b, b + sizeof b, x).ptr);
}

void put(std::string& s, long x) {
  char b[24];
  s.append(b, std::to_chars(b, b + sizeof b, x).ptr);
}

// The OBJ, streamed in blocks of lines.
void write_obj(const std::string& path, const MeshData& m, const AtlasResult& r) {
  write_file_atomically(path, [&](const ByteSink& sink) {
    std::string s = "# intrinsic atlas: " + std::to_string(r.charts.size()) + " charts\n";
    auto flush = [&](bool force) {
      if (force || s.size() > (1 << 20)) sink(s.data(), s.size()), s.clear();
    };
    for (int v = 0; v < m.V.rows(); ++v) {
      s += "v";
      for (int c = 0; c < 3; ++c) s += ' ', put(s, m.V(v, c));
      s += '\n';
      flush(false);
    }
    for (int t = 0; t < r.UV.rows(); ++t) {
      s += "vt ";
      put(s, r.UV(t, 0));
      s += ' ';
      put(s, r.UV(t, 1));
      s += '\n';
      flush(false);
    }
    for (int f = 0; f < m.F.rows(); ++f) {
      s += "f";
      for (int c = 0; c < 3; ++c) {
        s += ' ';
        put(s, static_cast<long>(m.F(f, c)) + 1);
        s += '/';
        put(s, static_cast<long>(r.FUV(f, c)) + 1);
      }
      s += '\n';
      flush(false);
    }
    flush(true);
  });
}

nlohmann::json report_json(const AtlasArgs& a, const MeshData& m, const AtlasResult& r) {
  nlohmann::json j;
  j["input"] = a.input;
  j["output"] = a.output;
  j["vertices"] = m.V.rows();
  j["faces"] = m.F.rows();
  j["components"] = r.components;
  j["charts"] = r.charts.size();
  j["splits"] = r.splits;
  const AtlasSplits& sr = r.split_reasons;
  j["split_reasons"] = {{"not_disk", sr.not_disk}, {"refused", sr.refused}, {"solve_failed", sr.solve_failed},
                        {"flipped", sr.flipped}, {"boundary_crossing", sr.boundary_crossing}, {"sparse", sr.sparse}};
  j["utilization"] = r.utilization;
  j["flipped"] = r.flipped;
  j["overlapping"] = r.overlapping;
  j["resolution"] = a.options.resolution;
  j["padding"] = a.options.padding;
  j["cleaning"] = {{"degenerate_faces", r.cleaning.degenerate_faces},
                   {"nonmanifold_edges", r.cleaning.nonmanifold_edges},
                   {"nonmanifold_vertices", r.cleaning.nonmanifold_vertices},
                   {"inconsistent_edges", r.cleaning.inconsistent_edges},
                   {"reversed_faces", r.cleaning.reversed_faces},
                   {"nonorientable_cuts", r.cleaning.nonorientable_cuts},
                   {"unreferenced_vertices", r.cleaning.unreferenced_vertices}};
  nlohmann::json charts = nlohmann::json::array();
  for (const AtlasChart& c : r.charts)
    charts.push_back({{"component", c.component}, {"faces", c.faces}, {"vertices", c.vertices},
                      {"method", chart_method_name(c.method)}, {"flipped", c.flipped},
                      {"angle_distortion_mean", c.angle_distortion_mean}, {"stretch_l2_mean", c.stretch_l2_mean},
                      {"area_3d", c.area_3d}, {"rotated", c.rotated}});
  j["chart_list"] = charts;
  return j;
}

int run_atlas(const AtlasArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  if (mesh_extension(a.output) != ".obj")
    throw_usage("output '" + a.output + "': the atlas is written as .obj (one texture coordinate per corner)");
  ReadOptions ro;
  ro.max_vertices = a.max_vertices;
  ro.max_faces = faces_for_vertices(ro.max_vertices);
  const MeshData data = read_mesh(a.input, ro);
  const double read_ms = elapsed_ms(t0);
  const AtlasResult r = atlas(data, a.options);
  const auto t1 = std::chrono::steady_clock::now();
  write_obj(a.output, data, r);
  const double write_ms = elapsed_ms(t1);
  nlohmann::json j = report_json(a, data, r);
  j["timings_ms"] = {{"read", read_ms},       {"clean", r.timings.clean_ms}, {"segment", r.timings.segment_ms},
                     {"flatten", r.timings.flatten_ms}, {"merge", r.timings.merge_ms}, {"pack", r.timings.pack_ms}, {"write", write_ms},
                     {"total", elapsed_ms(t0)}};
  if (!a.report.empty()) write_all({{a.report, j.dump(2) + "\n"}}, {a.output});
  if (!a.quiet)
    std::cout << a.output << ": " << data.V.rows() << " vertices, " << r.components << " components, "
              << r.charts.size() << " charts, utilization " << static_cast<int>(100 * r.utilization + 0.5) << "%, "
              << r.flipped << " flipped, " << r.overlapping << " overlapping, " << static_cast<long>(elapsed_ms(t0))
              << " ms\n";
  return 0;
}

}  // namespace

void register_atlas(CLI::App& app, Runner& run) {
  auto a = std::make_shared<AtlasArgs>();
  CLI::App* cmd = app.add_subcommand(
      "atlas", "UV atlas of any mesh (closed, higher genus, several components, non-manifold): disk charts, "
               "each flattened by the natural conformal map, packed into [0,1]^2 without flips or overlaps");
  cmd->add_option("input", a->input, "Input mesh (.obj, .off, .ply, optionally .gz)")->required();
  cmd->add_option("-o,--output", a->output, "Output mesh (.obj: input vertices, one vt per atlas UV, f v/vt)")
      ->required();
  cmd->add_option("--report", a->report, "Write the JSON report to this file");
  cmd->add_option("--padding", a->options.padding, "Texels between charts")->capture_default_str();
  cmd->add_option("--resolution", a->options.resolution, "Texture width the padding is measured in")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  cmd->add_option("--max-normal-deviation", a->options.max_normal_deviation_deg,
                  "Degrees between a face normal and its chart's mean normal")
      ->check(CLI::Range(1.0, 180.0))
      ->capture_default_str();
  cmd->add_option("--min-chart-faces", a->options.min_chart_faces,
                  "Merge smaller charts into a neighbour when the result stays valid (0: never)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--max-vertices", a->max_vertices, "Refuse inputs with more vertices")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", a->quiet, "Print nothing on success");
  cmd->callback([&run, a] { run = [a] { return run_atlas(*a); }; });
}

}  // namespace intrinsic::app
