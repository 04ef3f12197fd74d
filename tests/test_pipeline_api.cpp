// The public pipeline (pipeline.h) and the name tables (names.h): the job
// from arrays equals the job from a file; its report equals the command
// line's apart from timings; every table round-trips and its allowed list
// is what `--help` prints; a bad choice names the label and the list.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/generate.h"
#include "intrinsic/io.h"
#include "intrinsic/boundary_editor.h"
#include "intrinsic/intrinsic.h"
#include "intrinsic/pictures.h"
#include "intrinsic/texture.h"
#include "intrinsic/pipeline.h"

namespace intrinsic {
namespace {

using test::run_cli;
using test::slurp;
using test::TempDir;

nlohmann::json without_timings(nlohmann::json j) {
  j.erase("timings_ms");
  if (j.contains("optimal_lambda")) j["optimal_lambda"].erase("timings_ms");
  if (j.contains("boundary_optimization")) j["boundary_optimization"].erase("timings_ms");
  return j;
}

std::string generated(const TempDir& dir, const std::string& surface) {
  const std::string path = dir / (surface + ".obj");
  EXPECT_EQ(run_cli("generate " + surface + " --rings 10 -o " + path, dir).code, 0);
  return path;
}

TEST(PipelineApi, ParamFromArraysEqualsFromFile) {
  TempDir dir;
  const std::string path = generated(dir, "wave");
  ParamRequest request;
  request.options.boundary = BoundaryShape::Natural;
  const ParamOutcome from_file = parameterize_file(path, request);
  MeshData data = read_mesh(path);
  const ParamOutcome from_data = parameterize_data(data, request);
  EXPECT_EQ(from_file.map.UV, from_data.map.UV);
  nlohmann::json a = without_timings(nlohmann::json::parse(param_report(request, from_file, "")));
  nlohmann::json b = without_timings(nlohmann::json::parse(param_report(request, from_data, "")));
  EXPECT_EQ(a["input"], path);  // read_mesh names the data by its path
  EXPECT_EQ(a, b);
}

// The command line's report, written by a separate process, against the
// library's report of the same request built here.
void expect_report_equals_cli(const std::string& flags, const ParamRequest& request) {
  TempDir dir;
  const std::string in = generated(dir, "cap"), out = dir / "out.obj", report = dir / "r.json";
  ASSERT_EQ(run_cli("param " + in + " -o " + out + " --report " + report + " -q " + flags, dir).code, 0);
  const nlohmann::json cli = nlohmann::json::parse(slurp(report));
  const nlohmann::json lib = nlohmann::json::parse(param_report(request, parameterize_file(in, request), out));
  EXPECT_EQ(without_timings(cli), without_timings(lib)) << flags;
  // The command line adds its own stages to the library's.
  for (const char* k : {"read", "validate", "assemble", "factor", "solve", "render", "write", "total"})
    EXPECT_TRUE(cli["timings_ms"].contains(k)) << k;
}

TEST(PipelineApi, ParamReportEqualsCli) {
  expect_report_equals_cli("", ParamRequest());
  ParamRequest natural;
  natural.options.boundary = BoundaryShape::Natural;
  expect_report_equals_cli("--boundary natural", natural);
  ParamRequest lambda;
  lambda.optimizer = ChartOptimizer::OptimalLambda;
  lambda.optimal_lambda.energy = LambdaEnergy::Area;
  expect_report_equals_cli("--optimize-lambda area", lambda);
}

TEST(PipelineApi, AtlasReportEqualsCli) {
  TempDir dir;
  const std::string in = generated(dir, "torus"), out = dir / "out.obj", report = dir / "r.json";
  ASSERT_EQ(run_cli("atlas " + in + " -o " + out + " --report " + report + " -q", dir).code, 0);
  const AtlasOutcome o = atlas_file(in, AtlasRequest());
  EXPECT_EQ(without_timings(nlohmann::json::parse(slurp(report))), without_timings(nlohmann::json::parse(atlas_report(o, out))));
  // Same bytes as the command line's file.
  write_atlas_file(dir / "lib.obj", o.input, o.result);
  EXPECT_EQ(slurp(dir / "lib.obj"), slurp(out));
}

template <class E>
void expect_round_trip(const char* what) {
  SCOPED_TRACE(what);
  std::vector<std::string> names;
  for (const Choice<E>& c : choice_table<E>()) {
    EXPECT_EQ(choice_name(c.value), c.name);
    if (!c.listed) continue;
    EXPECT_EQ(parse_choice<E>(c.name, "x"), c.value);
    names.push_back(c.name);
  }
  EXPECT_EQ(choice_names<E>(), names);
  // Values are listed once each.
  for (const Choice<E>& a : choice_table<E>()) {
    int same = 0;
    for (const Choice<E>& b : choice_table<E>()) same += a.value == b.value;
    EXPECT_EQ(same, 1) << a.name;
  }
}

TEST(PipelineApi, NameTablesRoundTrip) {
  expect_round_trip<Method>("Method");
  expect_round_trip<BoundaryShape>("BoundaryShape");
  expect_round_trip<Spacing>("Spacing");
  expect_round_trip<ScaleMode>("ScaleMode");
  expect_round_trip<Placement>("Placement");
  expect_round_trip<HoleRule>("HoleRule");
  expect_round_trip<HolesApplied>("HolesApplied");
  expect_round_trip<SolverKind>("SolverKind");
  expect_round_trip<LambdaEnergy>("LambdaEnergy");
  expect_round_trip<BoundaryEnergy>("BoundaryEnergy");
  expect_round_trip<GradientRoute>("GradientRoute");
  expect_round_trip<Descent>("Descent");
  expect_round_trip<Segmentation>("Segmentation");
  expect_round_trip<ChartMethod>("ChartMethod");
  expect_round_trip<ChartOptimizer>("ChartOptimizer");
  expect_round_trip<BasisMode>("BasisMode");
  expect_round_trip<PictureMode>("PictureMode");
  expect_round_trip<TextureRole>("TextureRole");
  expect_round_trip<TextureWrap>("TextureWrap");
}

TEST(PipelineApi, BadChoiceNamesLabelAndList) {
  try {
    parse_choice<Method>("foo", "method");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_EQ(std::string(e.what()), "method: 'foo' is not one of conformal, authalic, mixed, tutte, floater");
  }
  TempDir dir;
  const std::string in = generated(dir, "wave");
  const auto r = run_cli("param " + in + " -o " + (dir / "o.obj") + " --spacing foo", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--spacing: 'foo' is not one of arclength, uniform"), std::string::npos) << r.err;
}

// `--help` lists exactly the table's names.
TEST(PipelineApi, HelpListsTheTables) {
  TempDir dir;
  const auto r = run_cli("param --help", dir);
  EXPECT_EQ(r.code, 0);
  const auto braces = [](std::vector<std::string> names) {
    std::string s;
    for (const std::string& n : names) s += (s.empty() ? "" : ",") + n;
    return "{" + s + "}";
  };
  for (const std::string& list : {braces(choice_names<Method>()), braces(choice_names<Spacing>()),
                                  braces(choice_names<ScaleMode>()), braces(choice_names<HoleRule>()),
                                  braces(choice_names<LambdaEnergy>()), braces(choice_names<BoundaryEnergy>()),
                                  braces(choice_names<GradientRoute>()), braces(choice_names<Descent>())})
    EXPECT_NE(r.out.find(list), std::string::npos) << list;
}

TEST(PipelineApi, RequestChecksNameTheSpelling) {
  ParamRequest r;
  r.optimizer = ChartOptimizer::OptimalLambda;
  r.constraints_file = "c.json";
  try {
    check_param_request(r);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "constraints cannot be combined with optimize_lambda or optimize_boundary");
  }
  r.spelling = OptionSpelling::Flag;
  try {
    check_param_request(r);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "--constraints cannot be combined with --optimize-lambda or --optimize-boundary");
  }
}

}  // namespace
}  // namespace intrinsic
