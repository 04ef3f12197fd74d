// The atlas job's options, each declared once with the request field it sets
// (atlas_option_table.h); docs/cli.md "intrinsic atlas" explains them.
#include "intrinsic/atlas_option_table.h"

#include "option_rows.h"

namespace intrinsic {
// Named, not anonymous: the unity build compiles both tables in one unit.
namespace atlas_rows {

using option_rows::kNoLimit;
using option_rows::spec;

// The request being built, with the chart map's choices that are combined
// only once every option is in (weights, optimizer).
struct Draft {
  AtlasRequest request;
  Method method = Method::Conformal;
  std::optional<double> lambda, mu;
  std::optional<LambdaEnergy> optimize_lambda;
  std::optional<BoundaryEnergy> optimize_boundary;
};

using Rows = option_rows::RowsOf<Draft>;
using Row = Rows::R;

AtlasOptions& opt(Draft& d) { return d.request.options; }

const char* const kFiles = "Files";
const char* const kMap = "Chart map";
const char* const kPack = "Packing";
const char* const kCharts = "Charts";

// What goes in and comes out: scene instances, the glTF set, texture transfer.
void add_file_rows(std::vector<Row>& t) {
  t.push_back(Rows::with_flag(
      Rows::choice<AtlasScope>(spec("scope", kFiles,
                              "whole: one atlas for the whole input (default, e.g. a lightmap); per-mesh: each glTF "
                              "mesh or OBJ object `o` gets its own atlas filling [0,1]^2"),
                         [](Draft& d) -> AtlasScope& { return opt(d).scope; }),
      "--atlas"));
  t.push_back(Rows::choice<InstanceMode>(
      spec("instances", kFiles,
           "A mesh several nodes draw (glTF, FBX, Collada...): shared (default: one chart layout, every node keeps "
           "pointing at it) or unique (each instance its own charts, the mesh copied per node)"),
      [](Draft& d) -> InstanceMode& { return d.request.read.instances; }));
  t.push_back(Rows::boolean(spec("allow_missing_images", kFiles,
                           "Write the output even when an image or material file the input names cannot be found "
                           "(its reference is kept as it was and listed in the report's missing_images)"),
                      [](Draft& d) -> bool& { return d.request.gltf.allow_missing_images; }));
  t.push_back(Rows::optional_integer(
      spec("uv_set", kFiles,
           "glTF input: the TEXCOORD_n set the atlas goes to (default: the next free set of each primitive)", 0, 31),
      [](Draft& d) -> int& { return d.request.gltf.texcoord_set; }));
  t.push_back(Rows::boolean(spec("replace_used_set", kFiles,
                           "glTF input: allow --uv-set to replace a set that the material's textures read (they will "
                           "no longer match: see --transfer-textures)"),
                      [](Draft& d) -> bool& { return d.request.gltf.replace_used_set; }));
  t.push_back(Rows::boolean(
      spec("transfer_textures", kFiles,
           "Bake every texture that reads the replaced set into the new layout (glTF: with --uv-set N, images "
           "embedded, TANGENT written for normal maps; OBJ: map_Kd/map_Ks/map_Bump of the mtllib, PNGs and a new "
           ".mtl beside the output)"),
      [](Draft& d) -> bool& { return d.request.textures.enabled; }));
  t.push_back(Rows::integer<int>(
      spec("texture_size", kFiles,
           "--transfer-textures: side of each baked texture in texels (0: each source's own texel density)", 0, 16384),
      [](Draft& d) -> int& { return d.request.textures.size; }));
  t.push_back(Rows::integer<int>(spec("texture_padding", kFiles,
                                "--transfer-textures: texels of dilation around every chart (-1: fill the whole image)",
                                -1, 1024),
                           [](Draft& d) -> int& { return d.request.textures.padding; }));
  t.push_back(Rows::integer<std::int64_t>(spec("max_vertices", kFiles, "Refuse inputs with more vertices", 1),
                                    [](Draft& d) -> std::int64_t& { return d.request.read.max_vertices; }));
}

// Each chart's map, as `param` spells it.
void add_map_rows(std::vector<Row>& t) {
  t.push_back(Rows::choice<BoundaryShape>(
      spec("boundary", kMap,
           "Each chart's map: natural (the natural conformal map, default) or a fixed circle or square boundary "
           "with --method's weights"),
      [](Draft& d) -> BoundaryShape& { return opt(d).charts.chart_map.boundary; }));
  Rows::add_blend_rows(t, kMap);
  t.push_back(Rows::optional_choice<LambdaEnergy>(
      spec("optimize_lambda", kMap,
           "Per chart, the mixed map at the optimal lambda for this energy (edge | area); fixed boundaries"),
      [](Draft& d) -> std::optional<LambdaEnergy>& { return d.optimize_lambda; }));
  t.push_back(Rows::optional_choice<BoundaryEnergy>(
      spec("optimize_boundary", kMap, "Per chart, optimize the fixed boundary for this energy (edge | area | dirichlet)"),
      [](Draft& d) -> std::optional<BoundaryEnergy>& { return d.optimize_boundary; }));
}

// Padding, page size, lightmap density and pages, re-packing existing UVs.
void add_pack_rows(std::vector<Row>& t) {
  t.push_back(Rows::real(spec("padding", kPack, "Texels between charts", 0.0),
                   [](Draft& d) -> double& { return opt(d).pack.padding; }));
  t.push_back(Rows::real(spec("texels_per_unit", kPack,
                        "Lightmaps: every chart at this many texels per unit of surface length, on pages of "
                        "--resolution texels (UDIM tiles 1001, 1002, ...: page k at u in [k, k+1]; 0: one page, "
                        "charts scaled to fill it)",
                        0.0, 1e12),
                   [](Draft& d) -> double& { return opt(d).pack.texels_per_unit; }));
  t.push_back(Rows::boolean(spec("pack_only", kPack,
                           "Re-pack the input's own UVs (OBJ vt, PLY u v, glTF TEXCOORD_<--uv-set, default 0>): its "
                           "charts keep their shape, turned only by quarter turns, one common scale, moved into a "
                           "layout without overlaps"),
                      [](Draft& d) -> bool& { return opt(d).pack_only; }));
  t.push_back(Rows::boolean(spec("keep_overlaps", kPack,
                           "--pack-only: input charts that overlap each other (mirrored halves sharing texels) stay "
                           "on each other (default: separated)"),
                      [](Draft& d) -> bool& { return opt(d).keep_overlaps; }));
  t.push_back(Rows::integer<int>(spec("max_pages", kPack,
                                "--texels-per-unit: refuse (exit 2, nothing written) when more pages are needed (0: "
                                "no limit)",
                                0),
                           [](Draft& d) -> int& { return opt(d).pack.max_pages; }));
  t.push_back(Rows::integer<int>(spec("resolution", kPack, "Texture (page) width the padding is measured in", 1, 1 << 20),
                           [](Draft& d) -> int& { return opt(d).pack.resolution; }));
}

// Where charts are cut and how far they may stretch.
void add_chart_rows(std::vector<Row>& t) {
  t.push_back(Rows::real(spec("max_normal_deviation", kCharts, "Degrees between a face normal and its chart's mean normal",
                        1.0, 180.0),
                   [](Draft& d) -> double& { return opt(d).charts.max_normal_deviation_deg; }));
  t.push_back(Rows::real(spec("hard_angle", kCharts,
                        "Always cut edges whose faces' normals turn by more than this many degrees (0: none)", 0.0,
                        179.999),
                   [](Draft& d) -> double& { return opt(d).charts.hard_angle_deg; }));
  t.push_back(Rows::integer<int>(spec("min_chart_faces", kCharts,
                                "Charts with fewer faces may merge into a neighbour up to its own stretch (0: no "
                                "merging)",
                                0),
                           [](Draft& d) -> int& { return opt(d).charts.min_chart_faces; }));
  t.push_back(Rows::path(spec("seams", kCharts,
                        "Cut exactly these edges (one 'i j' per line, 0-based vertex indices); charts are the pieces "
                        "between them, split only where validity needs"),
                   [](Draft& d) -> std::string& { return d.request.seams_file; }));
  t.push_back(Rows::real(spec("max_stretch", kCharts,
                        "Split charts above, and merge neighbouring charts while the union stays within, this "
                        "stretch: 95% of each chart's surface stretched or shrunk by at most this factor (max(s1, "
                        "1/s2))",
                        1.0, 100.0),
                   [](Draft& d) -> double& { return opt(d).charts.max_stretch; }));
  t.push_back(Rows::real(spec("max_face_stretch", kCharts,
                        "No face of a chart stretched or shrunk more than this (max(s1, 1/s2) at the atlas's texel "
                        "density)",
                        1.0, 1e6),
                   [](Draft& d) -> double& { return opt(d).charts.max_face_stretch; }));
  t.push_back(Rows::integer<int>(spec("isometric_iterations", kCharts,
                                "Local/global steps refining each chart's natural conformal map toward an isometry "
                                "(0: none)",
                                0, 1000),
                           [](Draft& d) -> int& { return opt(d).charts.chart_map.isometric_iterations; }));
  t.push_back(Rows::with_flag(Rows::boolean(spec("atlas_stretch_budget", kCharts,
                                     "Keep every merged chart within --max-stretch (default: unions under 1% of the "
                                     "surface may merge past it while the whole atlas's 95th percentile stays "
                                     "within it)"),
                                [](Draft& d) -> bool& { return opt(d).charts.atlas_stretch_budget; }),
                        "--per-chart-stretch", true));
  t.push_back(Rows::integer<int>(spec("max_charts", kCharts,
                                "Merge further (past both stretch bounds, never past validity) down to this many "
                                "charts (0: no limit)",
                                0),
                           [](Draft& d) -> int& { return opt(d).charts.max_charts; }));
  t.push_back(Rows::real(spec("weld", kCharts,
                        "Weld vertices closer than EPS times the bounding box diagonal, for the computation only "
                        "(coincident corners of unwelded exports; 0: off); the output keeps the input's vertices",
                        0.0, 0.999999),
                   [](Draft& d) -> double& { return opt(d).charts.weld; }));
  t.push_back(Rows::with_flag(Rows::boolean(spec("reorient", kCharts,
                                     "Keep the winding of faces listed against their piece's orientation and cut "
                                     "there (default: write them reversed, so charts may span them)"),
                                [](Draft& d) -> bool& { return opt(d).charts.reorient; }),
                        "--keep-winding", true));
}

const std::vector<Row>& rows() {
  static const std::vector<Row> table = [] {
    std::vector<Row> t;
    add_file_rows(t);
    add_map_rows(t);
    add_pack_rows(t);
    add_chart_rows(t);
    return t;
  }();
  return table;
}

// The chart map's options, combined as `param` combines them.
void finish_chart_map(Draft& d, const std::vector<std::string>& keys, OptionSpelling spelling) {
  const auto given = [&](const char* key) { return option_rows::was_given(keys, key); };
  const auto label = [&](const char* key) { return option_label(key, spelling); };
  ChartMapOptions& m = d.request.options.charts.chart_map;
  if (m.boundary == BoundaryShape::Natural &&
      ((given("method") && d.method != Method::Conformal) || given("lambda") || given("mu")))
    throw_usage(label("method") + " applies to fixed chart boundaries: add " + label("boundary") +
                (spelling == OptionSpelling::Flag ? " circle or square" : "='circle' or 'square'"));
  m.weights = weight_options(d.method, d.lambda, d.mu, spelling);
  if (d.optimize_lambda && d.optimize_boundary)
    throw_usage(label("optimize_lambda") + " and " + label("optimize_boundary") + ": choose one");
  if (d.optimize_lambda) {
    m.optimizer = ChartOptimizer::OptimalLambda;
    m.lambda_energy = *d.optimize_lambda;
  } else if (d.optimize_boundary) {
    m.optimizer = ChartOptimizer::OptimizeBoundary;
    m.boundary_energy = *d.optimize_boundary;
  }
}

}  // namespace atlas_rows

const std::vector<OptionSpec>& atlas_option_table() {
  static const std::vector<OptionSpec> specs = option_rows::specs_of(atlas_rows::rows());
  return specs;
}

AtlasRequest atlas_request(const GivenOptions& given, OptionSpelling spelling) {
  atlas_rows::Draft d;
  const std::vector<std::string> keys = option_rows::apply_given(atlas_rows::rows(), given, spelling, d);
  atlas_rows::finish_chart_map(d, keys, spelling);
  d.request.read.max_faces = faces_for_vertices(d.request.read.max_vertices);
  d.request.textures.spelling = spelling;
  d.request.gltf.spelling = spelling;
  return d.request;
}

}  // namespace intrinsic
