// `intrinsic atlas`: read any triangle mesh (closed, higher genus,
// several components, non-manifold bits, zero-area faces), build its atlas
// (atlas.h), write the input's vertices in input order with one `vt` per atlas
// UV and faces `f v/vt` (seams only through the per-corner texture
// coordinates), and the report.
#include <iostream>

#include "choice_option.h"
#include "command.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/error.h"
#include "intrinsic/gltf.h"
#include "intrinsic/io.h"
#include "intrinsic/pictures.h"
#include "intrinsic/pipeline.h"
#include "intrinsic/texture_transfer.h"
#include "intrinsic/report.h"
#include "weight_args.h"

namespace intrinsic::app {
namespace {

struct AtlasArgs {
  std::string input, output, report, seams;
  std::string boundary = choice_name(BoundaryShape::Natural), optimize_lambda, optimize_boundary;
  std::shared_ptr<WeightArgs> weights = std::make_shared<WeightArgs>();
  AtlasOptions options;
  GltfWriteOptions gltf;
  std::string scope = choice_name(AtlasScope::Whole);
  std::string instances = choice_name(InstanceMode::Shared);
  TextureTransferOptions textures;
  bool quiet = false;
  std::int64_t max_vertices = ReadOptions().max_vertices;
};

// The chart map as `param` spells it: --boundary natural|circle|square,
// --method/--lambda/--mu (fixed boundaries only), --optimize-lambda or
// --optimize-boundary.
void set_chart_map(const AtlasArgs& a, ChartMapOptions& m) {
  m.boundary = parse_choice<BoundaryShape>(a.boundary, "--boundary");
  if (m.boundary == BoundaryShape::Natural && a.weights->given())
    throw_usage("--method applies to fixed chart boundaries: add --boundary circle or square");
  m.weights = a.weights->options();
  if (!a.optimize_lambda.empty() && !a.optimize_boundary.empty())
    throw_usage("--optimize-lambda and --optimize-boundary: choose one");
  if (!a.optimize_lambda.empty()) {
    m.optimizer = ChartOptimizer::OptimalLambda;
    m.lambda_energy = parse_choice<LambdaEnergy>(a.optimize_lambda, "--optimize-lambda");
  } else if (!a.optimize_boundary.empty()) {
    m.optimizer = ChartOptimizer::OptimizeBoundary;
    m.boundary_energy = parse_choice<BoundaryEnergy>(a.optimize_boundary, "--optimize-boundary");
  }
}

int run_atlas(const AtlasArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  AtlasRequest request;
  request.options = a.options;
  set_chart_map(a, request.options.charts.chart_map);
  request.options.scope = parse_choice<AtlasScope>(a.scope, "--atlas");
  check_atlas_output(a.output);
  request.read.max_vertices = a.max_vertices;
  request.read.max_faces = faces_for_vertices(a.max_vertices);
  request.read.instances = parse_choice<InstanceMode>(a.instances, "--instances");
  request.seams_file = a.seams;
  // The library's messages name the options as flags.
  request.textures = a.textures;
  request.textures.spelling = OptionSpelling::Flag;
  GltfWriteOptions gltf = a.gltf;
  gltf.spelling = OptionSpelling::Flag;
  request.texcoord_set = a.gltf.texcoord_set;
  request.output = a.output;
  const AtlasOutcome o = atlas_file(a.input, request);
  const auto t1 = std::chrono::steady_clock::now();
  const TextureTransferReport baked = write_atlas_with_textures(a.output, o.data, o.result, gltf, request.textures);
  nlohmann::json j = atlas_report_json(o, a.output);
  if (a.textures.enabled) j["textures"] = texture_transfer_json(baked);
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
    std::cout << a.output << ": " << o.data.V.rows() << " vertices, " << r.components << " components, "
              << r.charts.size() << " charts, "
              << (r.pages > 1 ? std::to_string(r.pages) + " pages, " : std::string())
              << "utilization " << static_cast<int>(100 * r.utilization + 0.5) << "%, "
              << r.flipped << " flipped, " << r.overlapping << " overlapping, " << static_cast<long>(elapsed_ms(t0))
              << " ms\n";
  return 0;
}

// What goes in and comes out: files, scene instances, the glTF set, texture transfer.
void add_file_options(CLI::App* cmd, const std::shared_ptr<AtlasArgs>& a) {
  cmd->add_option("input", a->input, "Input mesh (.obj, .off, .ply, .stl, optionally .gz; .gltf, .glb)")->required();
  cmd->add_option("-o,--output", a->output,
                  "Output mesh (.obj: input vertices, one vt per atlas UV, f v/vt; "
                  ".glb/.gltf: glTF 2.0, vertices split at seams; a glTF input comes back as the same "
                  "document with the atlas as a new TEXCOORD set)")
      ->required();
  cmd->add_option("--atlas", a->scope,
                  "whole: one atlas for the whole input (default, e.g. a lightmap); per-mesh: each glTF mesh "
                  "or OBJ object `o` gets its own atlas filling [0,1]^2")
      ->check(choice_check<AtlasScope>())
      ->capture_default_str();
  cmd->add_option("--instances", a->instances,
                  "A mesh several nodes draw (glTF, FBX, Collada...): shared (default: one chart layout, every node "
                  "keeps pointing at it) or unique (each instance its own charts, the mesh copied per node)")
      ->check(choice_check<InstanceMode>())
      ->capture_default_str();
  cmd->add_flag("--allow-missing-images", a->gltf.allow_missing_images,
                "Write the output even when an image or material file the input names cannot be found (its "
                "reference is kept as it was and listed in the report's missing_images)");
  cmd->add_option("--uv-set", a->gltf.texcoord_set,
                  "glTF input: the TEXCOORD_n set the atlas goes to (default: the next free set of each primitive)")
      ->check(CLI::Range(0, 31));
  cmd->add_flag("--replace-uv-set", a->gltf.replace_used_set,
                "glTF input: allow --uv-set to replace a set that the material's textures read (they will no longer "
                "match: see --transfer-textures)");
  cmd->add_flag("--transfer-textures", a->textures.enabled,
                "Bake every texture that reads the replaced set into the new layout (glTF: with --uv-set N, images "
                "embedded, TANGENT written for normal maps; OBJ: map_Kd/map_Ks/map_Bump of the mtllib, PNGs and a "
                "new .mtl beside the output)");
  cmd->add_option("--texture-size", a->textures.size,
                  "--transfer-textures: side of each baked texture in texels (0: each source's own texel density)")
      ->check(CLI::Range(0, 16384))
      ->capture_default_str();
  cmd->add_option("--texture-padding", a->textures.padding,
                  "--transfer-textures: texels of dilation around every chart (-1: fill the whole image)")
      ->check(CLI::Range(-1, 1024))
      ->capture_default_str();
}

// The report and each chart's map, as `param` spells it.
void add_map_options(CLI::App* cmd, const std::shared_ptr<AtlasArgs>& a) {
  cmd->add_option("--report", a->report, "Write the JSON report to this file");
  cmd->add_option("--boundary", a->boundary,
                  "Each chart's map: natural (the natural conformal map, default) or a fixed circle or square "
                  "boundary with --method's weights")
      ->check(choice_check<BoundaryShape>())
      ->capture_default_str();
  add_weight_options(*cmd, a->weights);
  cmd->add_option("--optimize-lambda", a->optimize_lambda,
                  "Per chart, the mixed map at the optimal lambda for this energy (edge | area); fixed boundaries");
  cmd->add_option("--optimize-boundary", a->optimize_boundary,
                  "Per chart, optimize the fixed boundary for this energy (edge | area | dirichlet)");
}

// Packing: padding, page size, lightmap density and pages, re-packing existing UVs.
void add_pack_options(CLI::App* cmd, const std::shared_ptr<AtlasArgs>& a) {
  cmd->add_option("--padding", a->options.pack.padding, "Texels between charts")->capture_default_str();
  cmd->add_option("--texels-per-unit", a->options.pack.texels_per_unit,
                  "Lightmaps: every chart at this many texels per unit of surface length, on pages of "
                  "--resolution texels (UDIM tiles 1001, 1002, ...: page k at u in [k, k+1]; 0: one page, "
                  "charts scaled to fill it)")
      ->check(CLI::Range(0.0, 1e12))
      ->capture_default_str();
  cmd->add_flag("--pack-only", a->options.pack_only,
                "Re-pack the input's own UVs (OBJ vt, PLY u v, glTF TEXCOORD_<--uv-set, default 0>): its charts "
                "keep their shape, turned only by quarter turns, one common scale, moved into a layout without "
                "overlaps");
  cmd->add_flag("--keep-overlaps", a->options.keep_overlaps,
                "--pack-only: input charts that overlap each other (mirrored halves sharing texels) stay on each "
                "other (default: separated)");
  cmd->add_option("--max-pages", a->options.pack.max_pages,
                  "--texels-per-unit: refuse (exit 2, nothing written) when more pages are needed (0: no limit)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--resolution", a->options.pack.resolution, "Texture (page) width the padding is measured in")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
}

// Where charts are cut and how far they may stretch.
void add_chart_options(CLI::App* cmd, const std::shared_ptr<AtlasArgs>& a) {
  cmd->add_option("--max-normal-deviation", a->options.charts.max_normal_deviation_deg,
                  "Degrees between a face normal and its chart's mean normal")
      ->check(CLI::Range(1.0, 180.0))
      ->capture_default_str();
  cmd->add_option("--hard-angle", a->options.charts.hard_angle_deg,
                  "Always cut edges whose faces' normals turn by more than this many degrees (0: none)")
      ->check(CLI::Range(0.0, 179.999))
      ->capture_default_str();
  cmd->add_option("--min-chart-faces", a->options.charts.min_chart_faces,
                  "Charts with fewer faces may merge into a neighbour up to its own stretch (0: no merging)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--seams", a->seams,
                  "Cut exactly these edges (one 'i j' per line, 0-based vertex indices); charts are the pieces "
                  "between them, split only where validity needs");
  cmd->add_option("--max-stretch", a->options.charts.max_stretch,
                  "Split charts above, and merge neighbouring charts while the union stays within, this stretch: "
                  "95% of each chart's surface stretched or shrunk by at most this factor (max(s1, 1/s2))")
      ->check(CLI::Range(1.0, 100.0))
      ->capture_default_str();
  cmd->add_option("--max-face-stretch", a->options.charts.max_face_stretch,
                  "No face of a chart stretched or shrunk more than this (max(s1, 1/s2) at the atlas's texel density)")
      ->check(CLI::Range(1.0, 1e6))
      ->capture_default_str();
  cmd->add_option("--isometric-iterations", a->options.charts.chart_map.isometric_iterations,
                  "Local/global steps refining each chart's natural conformal map toward an isometry (0: none)")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  cmd->add_flag_callback(
      "--per-chart-stretch", [a] { a->options.charts.atlas_stretch_budget = false; },
      "Keep every merged chart within --max-stretch (default: unions under 1% of the surface may merge "
      "past it while the whole atlas's 95th percentile stays within it)");
  cmd->add_option("--max-charts", a->options.charts.max_charts,
                  "Merge further (past both stretch bounds, never past validity) down to this many charts (0: no limit)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--weld", a->options.charts.weld,
                  "Weld vertices closer than EPS times the bounding box diagonal, for the computation only "
                  "(coincident corners of unwelded exports; 0: off); the output keeps the input's vertices")
      ->check(CLI::Range(0.0, 0.999999))
      ->capture_default_str();
  cmd->add_flag("!--keep-winding", a->options.charts.reorient,
                "Keep the winding of faces listed against their piece's orientation and cut there (default: "
                "write them reversed, so charts may span them)");
}
}  // namespace

void register_atlas(CLI::App& app, Runner& run) {
  auto a = std::make_shared<AtlasArgs>();
  CLI::App* cmd = app.add_subcommand(
      "atlas", "UV atlas of any mesh (closed, higher genus, several components, non-manifold): disk charts, "
               "each flattened by the natural conformal map refined toward an isometry, within a stretch bound, packed into "
               "[0,1]^2 without flips or overlaps");
  add_file_options(cmd, a);
  add_map_options(cmd, a);
  add_pack_options(cmd, a);
  add_chart_options(cmd, a);
  cmd->add_option("--max-vertices", a->max_vertices, "Refuse inputs with more vertices")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", a->quiet, "Print nothing on success");
  cmd->callback([&run, a] { run = [a] { return run_atlas(*a); }; });
}

}  // namespace intrinsic::app
