// The option tables of the atlas and param jobs (atlas_option_table.h,
// param_option_table.h) against mappings written here, separately: which request field each key sets, and that field's
// default in a default-constructed AtlasRequest or ParamRequest. Every option of the table
// must be in that mapping (a new option needs a line here), each default is
// the struct's, each value given lands in its field; ranges, choices,
// unknown and repeated keys, and the checks that span options give
// Error(Usage) naming the option as each shell spells it. The command line
// registers exactly the table's flags, and its messages name them.
#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <sstream>

#include "cli_support.h"
#include "intrinsic/atlas_option_table.h"
#include "intrinsic/param_option_table.h"
#include "test_support.h"

namespace intrinsic {
namespace {

using test::expect_error;

// key -> the request field it sets, read as an OptionValue.
using Reader = std::function<OptionValue(const AtlasRequest&)>;

std::map<std::string, Reader> fields() {
  const auto c = [](const AtlasRequest& r) -> const ChartOptions& { return r.options.charts; };
  return {
      {"scope", [](const AtlasRequest& r) { return OptionValue(choice_name(r.options.scope)); }},
      {"instances", [](const AtlasRequest& r) { return OptionValue(choice_name(r.read.instances)); }},
      {"allow_missing_images", [](const AtlasRequest& r) { return OptionValue(r.gltf.allow_missing_images); }},
      {"uv_set", [](const AtlasRequest& r) { return OptionValue(std::int64_t{r.gltf.texcoord_set}); }},
      {"replace_used_set", [](const AtlasRequest& r) { return OptionValue(r.gltf.replace_used_set); }},
      {"transfer_textures", [](const AtlasRequest& r) { return OptionValue(r.textures.enabled); }},
      {"texture_size", [](const AtlasRequest& r) { return OptionValue(std::int64_t{r.textures.size}); }},
      {"texture_padding", [](const AtlasRequest& r) { return OptionValue(std::int64_t{r.textures.padding}); }},
      {"boundary", [c](const AtlasRequest& r) { return OptionValue(choice_name(c(r).chart_map.boundary)); }},
      {"method", [c](const AtlasRequest& r) { return OptionValue(choice_name(c(r).chart_map.weights.method)); }},
      {"lambda", [c](const AtlasRequest& r) { return OptionValue(c(r).chart_map.weights.lambda); }},
      {"mu", [c](const AtlasRequest& r) { return OptionValue(c(r).chart_map.weights.mu); }},
      {"optimize_lambda", [c](const AtlasRequest& r) { return OptionValue(choice_name(c(r).chart_map.lambda_energy)); }},
      {"optimize_boundary",
       [c](const AtlasRequest& r) { return OptionValue(choice_name(c(r).chart_map.boundary_energy)); }},
      {"padding", [](const AtlasRequest& r) { return OptionValue(r.options.pack.padding); }},
      {"texels_per_unit", [](const AtlasRequest& r) { return OptionValue(r.options.pack.texels_per_unit); }},
      {"pack_only", [](const AtlasRequest& r) { return OptionValue(r.options.pack_only); }},
      {"keep_overlaps", [](const AtlasRequest& r) { return OptionValue(r.options.keep_overlaps); }},
      {"max_pages", [](const AtlasRequest& r) { return OptionValue(std::int64_t{r.options.pack.max_pages}); }},
      {"resolution", [](const AtlasRequest& r) { return OptionValue(std::int64_t{r.options.pack.resolution}); }},
      {"max_normal_deviation", [c](const AtlasRequest& r) { return OptionValue(c(r).max_normal_deviation_deg); }},
      {"hard_angle", [c](const AtlasRequest& r) { return OptionValue(c(r).hard_angle_deg); }},
      {"min_chart_faces", [c](const AtlasRequest& r) { return OptionValue(std::int64_t{c(r).min_chart_faces}); }},
      {"seams", [](const AtlasRequest& r) { return OptionValue(r.seams_file); }},
      {"max_stretch", [c](const AtlasRequest& r) { return OptionValue(c(r).max_stretch); }},
      {"max_face_stretch", [c](const AtlasRequest& r) { return OptionValue(c(r).max_face_stretch); }},
      {"isometric_iterations",
       [c](const AtlasRequest& r) { return OptionValue(std::int64_t{c(r).chart_map.isometric_iterations}); }},
      {"atlas_stretch_budget", [c](const AtlasRequest& r) { return OptionValue(c(r).atlas_stretch_budget); }},
      {"max_charts", [c](const AtlasRequest& r) { return OptionValue(std::int64_t{c(r).max_charts}); }},
      {"weld", [c](const AtlasRequest& r) { return OptionValue(c(r).weld); }},
      {"reorient", [c](const AtlasRequest& r) { return OptionValue(c(r).reorient); }},
      {"max_vertices", [](const AtlasRequest& r) { return OptionValue(r.read.max_vertices); }},
  };
}

// A value of the spec's type other than its default, inside its range.
OptionValue other_value(const OptionSpec& s) {
  switch (s.type) {
    case OptionType::Bool: return !std::get<bool>(*s.default_value);
    case OptionType::Int: return static_cast<std::int64_t>(std::isfinite(s.max) ? s.max : s.min + 7);
    case OptionType::Real: return std::isfinite(s.max) ? s.max : (std::isfinite(s.min) ? s.min : 0) + 0.5;
    case OptionType::Choice:
      for (const std::string& c : s.choices)
        if (!s.default_value || c != std::get<std::string>(*s.default_value)) return c;
      break;
    case OptionType::Path: return std::string("cuts.txt");
    case OptionType::Text: return std::string("2:0.5,0.25");
    case OptionType::ChoiceOrPath:
      for (const std::string& c : s.choices)
        if (c != std::get<std::string>(*s.default_value)) return c;
      break;
    case OptionType::RealPair: return RealPair{0.25, 0.75};
  }
  return {};
}

TEST(AtlasOptionTable, EveryOptionIsMappedAndDefaultsAreTheStructs) {
  const auto map = fields();
  const AtlasRequest defaults;
  EXPECT_EQ(atlas_option_table().size(), map.size());
  for (const OptionSpec& s : atlas_option_table()) {
    SCOPED_TRACE(s.key);
    ASSERT_TRUE(map.count(s.key)) << "an option without a line in fields()";
    if (s.default_value) EXPECT_EQ(map.at(s.key)(defaults), *s.default_value);
    if (s.default_value && (s.type == OptionType::Int || s.type == OptionType::Real)) {
      const double d = s.type == OptionType::Int ? static_cast<double>(std::get<std::int64_t>(*s.default_value))
                                                 : std::get<double>(*s.default_value);
      EXPECT_GE(d, s.min);
      EXPECT_LE(d, s.max);
    }
  }
}

// Each value given alone lands in its field (the chart map's options with
// the fixed boundary and the mixed method they need).
TEST(AtlasOptionTable, EachValueLandsInItsField) {
  const auto map = fields();
  for (const OptionSpec& s : atlas_option_table()) {
    SCOPED_TRACE(s.key);
    const OptionValue v = other_value(s);
    GivenOptions given = {{s.key, v}};
    if (s.key == "method" || s.key == "optimize_lambda" || s.key == "optimize_boundary" || s.key == "mu" ||
        s.key == "lambda")
      given.push_back({"boundary", std::string("circle")});
    if (s.key == "lambda" || s.key == "mu") given.push_back({"method", std::string("mixed")});
    if (s.key == "method" && std::get<std::string>(v) == "mixed") given.push_back({"lambda", 1.0});
    const AtlasRequest r = atlas_request(given, OptionSpelling::Keyword);
    EXPECT_EQ(map.at(s.key)(r), v);
  }
}

TEST(AtlasOptionTable, CombinedOptionsAsParamCombinesThem) {
  const AtlasRequest r = atlas_request({{"boundary", std::string("square")}, {"method", std::string("mixed")},
                                        {"lambda_", 0.25}, {"optimize_boundary", std::string("area")},
                                        {"max_vertices", std::int64_t{1000}}},
                                       OptionSpelling::Flag);
  const ChartMapOptions& m = r.options.charts.chart_map;
  EXPECT_EQ(m.weights.method, Method::Mixed);
  EXPECT_EQ(m.weights.lambda, 0.25);
  EXPECT_EQ(m.weights.mu, 0.0);
  EXPECT_EQ(m.optimizer, ChartOptimizer::OptimizeBoundary);
  EXPECT_EQ(m.boundary_energy, BoundaryEnergy::Area);
  EXPECT_EQ(r.read.max_faces, faces_for_vertices(1000));
  EXPECT_EQ(r.textures.spelling, OptionSpelling::Flag);
  EXPECT_EQ(r.gltf.spelling, OptionSpelling::Flag);
  EXPECT_EQ(atlas_request({}, OptionSpelling::Keyword).options.charts.chart_map.optimizer, ChartOptimizer::None);
}

TEST(AtlasOptionTable, ErrorsNameTheOptionAsEachShellSpellsIt) {
  const auto usage = [](GivenOptions g, OptionSpelling s, const std::string& fragment) {
    expect_error([&] { atlas_request(g, s); }, ErrorKind::Usage, fragment);
  };
  usage({{"max_stretch", 0.5}}, OptionSpelling::Flag, "--max-stretch: 0.5 is not in [1, 100]");
  usage({{"max_stretch", 0.5}}, OptionSpelling::Keyword, "max_stretch: 0.5 is not in [1, 100]");
  usage({{"max_charts", std::int64_t{-1}}}, OptionSpelling::Keyword, "max_charts: -1 is not at least 0");
  usage({{"scope", std::string("all")}}, OptionSpelling::Flag, "--atlas: 'all' is not one of whole, per-mesh");
  usage({{"max_stretch", std::string("big")}}, OptionSpelling::Keyword, "max_stretch: expected a number, got big");
  usage({{"reorient", std::int64_t{1}}}, OptionSpelling::Keyword, "reorient: expected true or false");
  usage({{"stretch", 1.0}}, OptionSpelling::Keyword, "unknown option 'stretch'");
  usage({{"boundary", std::string("circle")}, {"method", std::string("mixed")}, {"lambda", 1.0}, {"lam", 2.0}},
        OptionSpelling::Keyword, "lambda: given twice");
  usage({{"method", std::string("authalic")}}, OptionSpelling::Flag,
        "--method applies to fixed chart boundaries: add --boundary circle or square");
  usage({{"mu", 1.0}}, OptionSpelling::Keyword, "method applies to fixed chart boundaries: add boundary='circle'");
  usage({{"boundary", std::string("circle")}, {"method", std::string("mixed")}}, OptionSpelling::Flag,
        "--method mixed needs --lambda and/or --mu");
  usage({{"boundary", std::string("circle")}, {"optimize_lambda", std::string("edge")},
         {"optimize_boundary", std::string("edge")}},
        OptionSpelling::Flag, "--optimize-lambda and --optimize-boundary: choose one");
}

// The library's own messages (texture transfer, the glTF writer) name
// options through option_label: it must give the table's flags.
TEST(AtlasOptionTable, OptionLabelGivesTheTablesFlags) {
  for (const OptionSpec& s : atlas_option_table()) {
    if (s.flag_negates || s.key == "scope") continue;  // flags named after their effect, not their key
    EXPECT_EQ(option_label(s.key, OptionSpelling::Flag), s.flag) << s.key;
  }
}

TEST(AtlasOptionTable, CommandLineRegistersEveryFlag) {
  test::TempDir dir;
  const test::CliResult help = test::run_cli("atlas --help", dir);
  ASSERT_EQ(help.code, 0);
  for (const OptionSpec& s : atlas_option_table()) {
    EXPECT_NE(help.out.find("  " + s.flag + " "), std::string::npos) << s.flag;
    EXPECT_NE(help.out.find(s.help.substr(0, 40)), std::string::npos) << s.flag;
  }
}

}  // namespace
}  // namespace intrinsic

namespace intrinsic {
namespace {

// The texture-transfer checks that need the input and the output, in each
// spelling; the command line refuses before any work and writes nothing.
TEST(AtlasOptionTable, TextureTransferInputChecksInEachSpelling) {
  for (const OptionSpelling s : {OptionSpelling::Keyword, OptionSpelling::Flag}) {
    TextureTransferOptions o;
    o.enabled = true;
    o.spelling = s;
    const bool flag = s == OptionSpelling::Flag;
    expect_error([&] { check_texture_transfer_input(o, true, "out.glb", -1); }, ErrorKind::Usage,
                 flag ? "--transfer-textures replaces the set the textures read: add --uv-set N (usually 0)"
                      : "transfer_textures replaces the set the textures read: add uv_set N (usually 0)");
    expect_error([&] { check_texture_transfer_input(o, true, "out.obj", 0); }, ErrorKind::Usage,
                 flag ? "--transfer-textures: a glTF input is written back as .glb or .gltf"
                      : "transfer_textures: a glTF input is written back as .glb or .gltf");
    EXPECT_NO_THROW(check_texture_transfer_input(o, true, "out.glb", 0));
    EXPECT_NO_THROW(check_texture_transfer_input(o, true, "", 0));  // output not known yet
    EXPECT_NO_THROW(check_texture_transfer_input(o, false, "out.obj", -1));  // an OBJ's mtllib maps
  }
}

TEST(AtlasOptionTable, CommandLineRefusesATransferItCannotWriteBeforeAnyWork) {
  test::TempDir dir;
  ASSERT_EQ(test::run_cli("generate textured -o " + dir / "in.glb", dir).code, 0);
  const test::CliResult no_set = test::run_cli("atlas " + dir / "in.glb" + " -o " + dir / "out.glb" +
                                                   " --transfer-textures --report " + dir / "r.json",
                                               dir);
  EXPECT_EQ(no_set.code, 1);
  EXPECT_NE(no_set.err.find("--transfer-textures replaces the set the textures read: add --uv-set N"),
            std::string::npos)
      << no_set.err;
  const test::CliResult to_obj = test::run_cli(
      "atlas " + dir / "in.glb" + " -o " + dir / "out.obj" + " --transfer-textures --uv-set 0", dir);
  EXPECT_EQ(to_obj.code, 1);
  EXPECT_NE(to_obj.err.find("--transfer-textures: a glTF input is written back as .glb or .gltf"),
            std::string::npos)
      << to_obj.err;
  const test::CliResult size = test::run_cli(
      "atlas " + dir / "in.glb" + " -o " + dir / "out.glb" + " --transfer-textures --uv-set 0 --texture-size 99999",
      dir);
  EXPECT_EQ(size.code, 1);
  EXPECT_NE(size.err.find("--texture-size"), std::string::npos) << size.err;
  for (const char* name : {"out.glb", "out.obj", "r.json"}) EXPECT_FALSE(std::filesystem::exists(dir / name)) << name;
}

}  // namespace
}  // namespace intrinsic

namespace intrinsic {
namespace {

using test::expect_error;

using ParamReader = std::function<OptionValue(const ParamRequest&)>;

std::string pin_text(const FixedVertex& p) {
  std::ostringstream out;
  out << p.vertex << ":" << p.uv.x() << "," << p.uv.y();
  return out.str();
}

// key -> the ParamRequest field it sets, read as an OptionValue.
std::map<std::string, ParamReader> param_fields() {
  const auto o = [](const ParamRequest& r) -> const ParamOptions& { return r.options; };
  const auto bo = [](const ParamRequest& r) -> const BoundaryOptimizationOptions& { return r.boundary_optimization; };
  return {
      {"method", [o](const ParamRequest& r) { return OptionValue(choice_name(o(r).weights.method)); }},
      {"lambda", [o](const ParamRequest& r) { return OptionValue(o(r).weights.lambda); }},
      {"mu", [o](const ParamRequest& r) { return OptionValue(o(r).weights.mu); }},
      {"boundary",
       [o](const ParamRequest& r) {
         return OptionValue(o(r).boundary == BoundaryShape::Given ? r.boundary_file : choice_name(o(r).boundary));
       }},
      {"pins", [o](const ParamRequest& r) { return OptionValue(pin_text(o(r).pins.at(0))); }},
      {"spacing", [o](const ParamRequest& r) { return OptionValue(choice_name(o(r).spacing)); }},
      {"scale", [o](const ParamRequest& r) { return OptionValue(choice_name(o(r).scale)); }},
      {"holes", [o](const ParamRequest& r) { return OptionValue(choice_name(o(r).holes)); }},
      {"solver", [o](const ParamRequest& r) { return OptionValue(choice_name(o(r).solver)); }},
      {"max_residual", [o](const ParamRequest& r) { return OptionValue(o(r).max_residual); }},
      {"constraints", [](const ParamRequest& r) { return OptionValue(r.constraints_file); }},
      {"largest_component", [](const ParamRequest& r) { return OptionValue(r.largest_component); }},
      {"max_vertices", [](const ParamRequest& r) { return OptionValue(r.read.max_vertices); }},
      {"optimize_lambda", [](const ParamRequest& r) { return OptionValue(choice_name(r.optimal_lambda.energy)); }},
      {"lambda_range", [](const ParamRequest& r) { return OptionValue(RealPair{r.optimal_lambda.lo, r.optimal_lambda.hi}); }},
      {"optimize_boundary", [bo](const ParamRequest& r) { return OptionValue(choice_name(bo(r).energy)); }},
      {"iterations", [bo](const ParamRequest& r) { return OptionValue(std::int64_t{bo(r).max_iterations}); }},
      {"tolerance", [bo](const ParamRequest& r) { return OptionValue(bo(r).tolerance); }},
      {"gradient", [bo](const ParamRequest& r) { return OptionValue(choice_name(bo(r).route)); }},
      {"descent", [bo](const ParamRequest& r) { return OptionValue(choice_name(bo(r).descent)); }},
  };
}

TEST(ParamOptionTable, EveryOptionIsMappedAndDefaultsAreTheStructs) {
  const auto map = param_fields();
  const ParamRequest defaults;
  EXPECT_EQ(param_option_table().size(), map.size());
  for (const OptionSpec& s : param_option_table()) {
    SCOPED_TRACE(s.key);
    ASSERT_TRUE(map.count(s.key)) << "an option without a line in param_fields()";
    if (s.default_value) EXPECT_EQ(map.at(s.key)(defaults), *s.default_value);
  }
  // The request the table makes from nothing is the struct's own.
  const ParamRequest none = param_request({}, OptionSpelling::Keyword);
  for (const auto& [key, read] : map)
    if (key != "pins") EXPECT_EQ(read(none), read(defaults)) << key;
  EXPECT_EQ(none.optimizer, ChartOptimizer::None);
  EXPECT_EQ(none.read.max_faces, faces_for_vertices(defaults.read.max_vertices));
}

// Each value given alone lands in its field (with what it needs beside it:
// the mixed method for lambda and mu, the natural boundary and a second pin
// for a pin).
TEST(ParamOptionTable, EachValueLandsInItsField) {
  const auto map = param_fields();
  for (const OptionSpec& s : param_option_table()) {
    SCOPED_TRACE(s.key);
    const OptionValue v = other_value(s);
    GivenOptions given = {{s.key, v}};
    if (s.key == "lambda" || s.key == "mu") given.push_back({"method", std::string("mixed")});
    if (s.key == "method" && std::get<std::string>(v) == "mixed") given.push_back({"lambda", 1.0});
    if (s.key == "pins") given.insert(given.end(), {{"pins", std::string("0:0,0")}, {"boundary", std::string("natural")}});
    const ParamRequest r = param_request(given, OptionSpelling::Keyword);
    EXPECT_EQ(map.at(s.key)(r), v);
  }
}

TEST(ParamOptionTable, PinsInOrderBoundaryFileAndOptimizer) {
  const ParamRequest r = param_request({{"boundary", std::string("natural")},
                                        {"pin", std::string("7:0.125,-2")},
                                        {"pins", std::string("3:1e-3,4")},
                                        {"pins", std::string("9:0,0")}},
                                       OptionSpelling::Flag);
  ASSERT_EQ(r.options.pins.size(), 3u);
  EXPECT_EQ(r.options.pins[0].vertex, 7);
  EXPECT_EQ(r.options.pins[0].uv, Eigen::Vector2d(0.125, -2));
  EXPECT_EQ(r.options.pins[1].uv, Eigen::Vector2d(1e-3, 4));
  EXPECT_EQ(r.options.pins[2].vertex, 9);
  EXPECT_EQ(r.spelling, OptionSpelling::Flag);
  const ParamRequest file = param_request({{"boundary", std::string("positions.txt")}}, OptionSpelling::Keyword);
  EXPECT_EQ(file.options.boundary, BoundaryShape::Given);
  EXPECT_EQ(file.boundary_file, "positions.txt");
  const ParamRequest lambda = param_request(
      {{"optimize_lambda", std::string("area")}, {"lambda_range", RealPair{0.2, 0.6}}}, OptionSpelling::Keyword);
  EXPECT_EQ(lambda.optimizer, ChartOptimizer::OptimalLambda);
  EXPECT_EQ(lambda.optimal_lambda.energy, LambdaEnergy::Area);
  EXPECT_EQ(lambda.optimal_lambda.lo, 0.2);
  EXPECT_EQ(lambda.optimal_lambda.hi, 0.6);
  const ParamRequest boundary = param_request(
      {{"optimize_boundary", std::string("dirichlet")}, {"iterations", std::int64_t{5}}}, OptionSpelling::Keyword);
  EXPECT_EQ(boundary.optimizer, ChartOptimizer::OptimizeBoundary);
  EXPECT_EQ(boundary.boundary_optimization.energy, BoundaryEnergy::SymmetricDirichlet);
  EXPECT_EQ(boundary.boundary_optimization.max_iterations, 5);
}

TEST(ParamOptionTable, ErrorsNameTheOptionAsEachShellSpellsIt) {
  const auto usage = [](GivenOptions g, OptionSpelling s, const std::string& fragment) {
    expect_error([&] { param_request(g, s); }, ErrorKind::Usage, fragment);
  };
  const auto both = [&](GivenOptions g, const std::string& flag, const std::string& keyword) {
    usage(g, OptionSpelling::Flag, flag);
    usage(g, OptionSpelling::Keyword, keyword);
  };
  both({{"max_vertices", std::int64_t{0}}}, "--max-vertices: 0 is not at least 1", "max_vertices: 0 is not at least 1");
  both({{"spacing", std::string("even")}}, "--spacing: 'even' is not one of arclength, uniform",
       "spacing: 'even' is not one of arclength, uniform");
  both({{"lambda_range", 0.5}}, "--lambda-range: expected two numbers", "lambda_range: expected two numbers");
  both({{"method", std::string("mixed")}, {"method", std::string("mixed")}}, "--method: given twice",
       "method: given twice");
  both({{"optimize_lambda", std::string("edge")}, {"optimize_boundary", std::string("edge")}},
       "--optimize-lambda and --optimize-boundary cannot be combined",
       "optimize_lambda and optimize_boundary cannot be combined");
  both({{"optimize_lambda", std::string("edge")}, {"method", std::string("authalic")}},
       "--optimize-lambda chooses the blend itself; do not give --method, --lambda or --mu",
       "optimize_lambda chooses the blend itself; do not give method, lambda or mu");
  both({{"method", std::string("mixed")}}, "--method mixed needs --lambda and/or --mu",
       "method mixed needs lambda and/or mu");
  both({{"pins", std::string("0:0,0")}, {"pins", std::string("1:1,0")}}, "--pin applies to --boundary natural only",
       "pins applies to boundary natural only");
  both({{"boundary", std::string("natural")}, {"pins", std::string("0:0,0")}},
       "--pin needs at least two pins", "pins needs at least two pins");
  both({{"boundary", std::string("natural")}, {"pins", std::string("0:0;0")}, {"pins", std::string("1:1,0")}},
       "--pin", "pins");
  both({{"solver", std::string("gauss")}}, "--solver: 'gauss' is not one of auto, cholmod",
       "solver: 'gauss' is not one of auto, cholmod");
  usage({{"lambda", 1.0}, {"lam", 2.0}}, OptionSpelling::Keyword, "lambda: given twice");
  usage({{"boundary_shape", std::string("circle")}}, OptionSpelling::Keyword, "unknown option 'boundary_shape'");
}

// The command line registers exactly the table's flags; `edit` takes the
// blend and the solver from the same rows.
TEST(ParamOptionTable, CommandLineRegistersEveryFlag) {
  test::TempDir dir;
  const test::CliResult help = test::run_cli("param --help", dir);
  ASSERT_EQ(help.code, 0);
  for (const OptionSpec& s : param_option_table()) {
    EXPECT_NE(help.out.find("  " + s.flag + " "), std::string::npos) << s.flag;
    EXPECT_NE(help.out.find(s.help.substr(0, 40)), std::string::npos) << s.flag;
  }
  const test::CliResult edit = test::run_cli("edit --help", dir);
  ASSERT_EQ(edit.code, 0);
  for (const OptionSpec& s : select_options(param_option_table(), {"method", "lambda", "mu", "solver"}))
    EXPECT_NE(edit.out.find("  " + s.flag + " "), std::string::npos) << s.flag;
}

// `intrinsic param` with flags equals the library's job with the same keys:
// the map written to the OBJ is the one parameterize_file gives.
TEST(ParamOptionTable, CommandLineMapEqualsTheLibrarysForTheSameOptions) {
  test::TempDir dir;
  ASSERT_EQ(test::run_cli("generate wave -o " + dir / "in.obj", dir).code, 0);
  const test::CliResult r = test::run_cli("param " + dir / "in.obj" + " -o " + dir / "out.obj" +
                                              " --boundary natural --pin 0:0,0 --pin 5:2,0.5 --scale surface -q",
                                          dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const ParamOutcome lib = parameterize_file(
      dir / "in.obj", param_request({{"boundary", std::string("natural")},
                                     {"pins", std::string("0:0,0")},
                                     {"pins", std::string("5:2,0.5")},
                                     {"scale", std::string("surface")}},
                                    OptionSpelling::Keyword));
  const MeshData out = read_mesh(dir / "out.obj");
  ASSERT_TRUE(out.has_uv());
  ASSERT_EQ(out.F.rows(), lib.mesh.F.rows());
  double worst = 0;
  for (int f = 0; f < out.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, (out.TC.row(out.FTC(f, k)) - lib.map.UV.row(lib.mesh.F(f, k))).norm());
  EXPECT_LT(worst, 1e-12);  // the OBJ's text round-trips the UVs to this
  EXPECT_NEAR(lib.map.UV(5, 0), 2.0, 1e-12);
  EXPECT_NEAR(lib.map.UV(5, 1), 0.5, 1e-12);
}

}  // namespace
}  // namespace intrinsic
