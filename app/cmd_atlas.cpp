// `intrinsic atlas`: read any triangle mesh (closed, higher genus,
// several components, non-manifold bits, zero-area faces), build its atlas
// (atlas.h), write the input's vertices in input order with one `vt` per atlas
// UV and faces `f v/vt` (seams only through the per-corner texture
// coordinates), and the report.
#include <iostream>
#include <nlohmann/json.hpp>

#include "command.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/atlas_option_table.h"
#include "intrinsic/error.h"
#include "intrinsic/gltf.h"
#include "intrinsic/io.h"
#include "intrinsic/pictures.h"
#include "intrinsic/pipeline.h"
#include "intrinsic/texture_transfer.h"
#include "intrinsic/report.h"
#include "table_options.h"

namespace intrinsic::app {
namespace {

struct AtlasArgs {
  std::string input, output, report;
  std::shared_ptr<GivenOptions> given = std::make_shared<GivenOptions>();
  bool quiet = false;
};

int run_atlas(const AtlasArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  // The library's table makes the request; its messages name the flags.
  AtlasRequest request = atlas_request(*a.given, OptionSpelling::Flag);
  check_atlas_output(a.output);
  request.output = a.output;
  const AtlasOutcome o = atlas_file(a.input, request);
  const auto t1 = std::chrono::steady_clock::now();
  const TextureTransferReport baked =
      write_atlas_with_textures(a.output, o.input, o.result, request.gltf, request.textures);
  nlohmann::json j = nlohmann::json::parse(atlas_report(o, a.output));
  if (request.textures.enabled) j["textures"] = nlohmann::json::parse(texture_transfer_report(baked));
  // What writing added beside the output, or could not find (only when
  // there is any: the report is otherwise the library's, as Python gives it).
  if (!baked.files.empty()) j["files_beside"] = baked.files;
  if (!baked.missing_images.empty()) j["missing_images"] = baked.missing_images;
  j["timings_ms"]["write"] = elapsed_ms(t1);
  j["timings_ms"]["total"] = elapsed_ms(t0);
  std::vector<std::string> written = baked.files;
  written.push_back(a.output);
  if (!a.report.empty()) write_all({{a.report, j.dump(2) + "\n"}}, written);
  const AtlasResult& r = o.result;
  for (const std::string& m : baked.missing_images)
    std::cerr << "intrinsic: warning: " << a.output << " names '" << m << "', which was not found (--allow-missing-images)\n";
  if (!a.quiet)
    std::cout << a.output << ": " << o.input.mesh.V.rows() << " vertices, " << r.components << " components, "
              << r.charts.size() << " charts, "
              << (r.pages > 1 ? std::to_string(r.pages) + " pages, " : std::string())
              << "utilization " << static_cast<int>(100 * r.utilization + 0.5) << "%, "
              << r.flipped << " flipped, " << r.overlapping << " overlapping, " << static_cast<long>(elapsed_ms(t0))
              << " ms\n";
  return 0;
}

}  // namespace

void register_atlas(CLI::App& app, Runner& run) {
  auto a = std::make_shared<AtlasArgs>();
  CLI::App* cmd = app.add_subcommand(
      "atlas", "UV atlas of any mesh (closed, higher genus, several components, non-manifold): disk charts, "
               "each flattened by the natural conformal map refined toward an isometry, within a stretch bound, packed into "
               "[0,1]^2 without flips or overlaps");
  cmd->add_option("input", a->input, "Input mesh (.obj, .off, .ply, .stl, optionally .gz; .gltf, .glb)")->required();
  cmd->add_option("-o,--output", a->output,
                  "Output mesh (.obj: input vertices, one vt per atlas UV, f v/vt; "
                  ".glb/.gltf: glTF 2.0, vertices split at seams; a glTF input comes back as the same "
                  "document with the atlas as a new TEXCOORD set)")
      ->required();
  cmd->add_option("--report", a->report, "Write the JSON report to this file");
  cmd->add_flag("-q,--quiet", a->quiet, "Print nothing on success");
  // Every atlas option, as the library declares it (atlas_option_table.h).
  add_table_options(cmd, atlas_option_table(), a->given);
  cmd->callback([&run, a] { run = [a] { return run_atlas(*a); }; });
}

}  // namespace intrinsic::app
