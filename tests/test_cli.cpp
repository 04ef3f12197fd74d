// The command-line tool end to end: outputs, reports, exit codes and
// messages, and that a refused run leaves no file behind.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "intrinsic/io.h"

namespace intrinsic {
namespace {

using test::run_cli;
using test::TempDir;

TEST(Cli, GenerateParamAndReport) {
  TempDir dir;
  ASSERT_EQ(run_cli("generate wave --rings 12 -o " + (dir / "wave.obj"), dir).code, 0);
  const auto r = run_cli("param " + (dir / "wave.obj") + " -o " + (dir / "out.obj") + " --report " +
                             (dir / "report.json"),
                         dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(test::slurp(dir / "report.json"));
  for (const char* key : {"vertices", "faces", "boundary_loops", "components", "method", "lambda", "mu", "boundary",
                          "solver", "residual", "flipped_triangles", "angle_distortion", "area_distortion",
                          "stretch_l2", "stretch_linf", "edge_length_distortion", "timings_ms", "scale"})
    EXPECT_TRUE(report.contains(key)) << key;
  for (const char* key : {"read", "validate", "assemble", "factor", "solve", "write", "total"})
    EXPECT_TRUE(report["timings_ms"].contains(key)) << key;
  EXPECT_EQ(report["flipped_triangles"], 0);
  EXPECT_EQ(report["scale"], "unit");
  const MeshData out = read_mesh(dir / "out.obj");
  ASSERT_TRUE(out.has_uv());
  EXPECT_GE(out.TC.minCoeff(), 0.0);
  EXPECT_LE(out.TC.maxCoeff(), 1.0);

  // metrics on our own output gives the same figures.
  const auto m = run_cli("metrics " + (dir / "out.obj") + " --report " + (dir / "m.json"), dir);
  ASSERT_EQ(m.code, 0) << m.err;
  const nlohmann::json mj = nlohmann::json::parse(test::slurp(dir / "m.json"));
  EXPECT_NEAR(mj["angle_distortion"]["mean"].get<double>(), report["angle_distortion"]["mean"].get<double>(), 1e-9);
  EXPECT_EQ(mj["flipped_triangles"], 0);
}

TEST(Cli, PlyBinaryOutputAndSurfaceScale) {
  TempDir dir;
  ASSERT_EQ(run_cli("generate cap --rings 8 -o " + (dir / "cap.ply"), dir).code, 0);
  const auto r = run_cli("param " + (dir / "cap.ply") + " -o " + (dir / "out.ply") +
                             " --binary --method mixed --lambda 0.5 --mu 0.5 --scale surface --boundary square -q",
                         dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_TRUE(read_mesh(dir / "out.ply").has_uv());
}

struct BadCommandLine {
  const char* name;
  const char* input;   // file contents (OBJ) or nullptr for no file
  const char* args;    // extra arguments
  int code;
  const char* message;
};

TEST(Cli, ErrorsGiveCodeMessageAndNoOutput) {
  const char* square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 0\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n";
  const BadCommandLine cases[] = {
      {"missing file", nullptr, "", 2, "cannot open"},
      {"bad index", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", "", 2, ":4:"},
      {"repeated vertex", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\n", "", 2, "repeats vertex"},
      {"degenerate", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", "", 2, "degenerate"},
      {"closed", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n", "", 2, "closed"},
      {"non-manifold edge",
       "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n", "", 2, "has 3 faces"},
      {"closed component among several",
       "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 5 0 0\nv 6 0 0\nv 5 1 0\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\nf 5 6 7\n",
       "", 2, "component 0 is closed"},
      {"pin syntax", square, "--boundary natural --pin 1:0 --pin 2:1,0", 1, "expected VERTEX:U,V"},
      {"pin letters", square, "--boundary natural --pin a:0,0 --pin 2:1,0", 1, "expected VERTEX:U,V"},
      {"one pin", square, "--boundary natural --pin 1:0,0", 1, "at least two"},
      {"pin out of range", square, "--boundary natural --pin 1:0,0 --pin 99:1,0", 2, "vertex 99, which does not exist"},
      {"pin without natural", square, "--pin 1:0,0 --pin 2:1,0", 1, "natural only"},
      {"natural authalic", square, "--boundary natural --method authalic", 1, "conformal method"},
      {"unknown holes rule", square, "--holes magic", 1, "holes"},
      {"unknown method", square, "--method foo", 1, "method"},
      {"lambda without mixed", square, "--lambda 0.5", 1, "--method mixed only"},
      {"mixed zero", square, "--method mixed --lambda 0 --mu 0", 1, "both be zero"},
      {"bad output format", square, "-o {dir}/out.xyz", 1, "unknown format"},
      {"cg on authalic", square, "--method authalic --solver cg", 1, "symmetric"},
      {"unknown solver", square, "--solver magic", 1, "--solver: 'magic' is not one of auto, cholmod"},
      {"missing boundary file", square, "--boundary {dir}/nothing.txt", 2, "cannot open boundary file"},
      {"residual too large", "GENERATE", "--solver bicgstab --max-residual 1e-300", 3, "residual"},
  };
  for (const BadCommandLine& c : cases) {
    SCOPED_TRACE(c.name);
    TempDir dir;
    const std::string in = dir / "in.obj";
    if (c.input && std::string(c.input) == "GENERATE")
      ASSERT_EQ(run_cli("generate wave --rings 10 -o " + in, dir).code, 0);
    else if (c.input)
      test::write_text(in, c.input);
    std::string args = c.args;
    std::string out = dir / "out.obj";
    if (args.find("-o ") == std::string::npos) args += " -o " + out;
    for (size_t p; (p = args.find("{dir}")) != std::string::npos;) args.replace(p, 5, dir.path().string());
    const auto r = run_cli("param " + in + " " + args + " --report " + (dir / "r.json"), dir);
    EXPECT_EQ(r.code, c.code) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    const std::vector<std::string> expected = c.input ? std::vector<std::string>{"in.obj"} : std::vector<std::string>{};
    EXPECT_EQ(dir.files(), expected) << "a refused run must leave no output";
  }
}

TEST(Cli, BoundaryFileMustListOuterLoop) {
  TempDir dir;
  const char* square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 0\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n";
  test::write_text(dir / "in.obj", square);
  test::write_text(dir / "b.txt", "# three of four corners\n0 0 0\n1 1 0\n2 1 1\n");
  auto r = run_cli("param " + (dir / "in.obj") + " -o " + (dir / "out.obj") + " --boundary " + (dir / "b.txt"), dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("vertex 3"), std::string::npos) << r.err;
  test::write_text(dir / "b.txt", "0 0 0\n1 1 0\n2 1 1\n3 0 x\n");
  r = run_cli("param " + (dir / "in.obj") + " -o " + (dir / "out.obj") + " --boundary " + (dir / "b.txt"), dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("b.txt:4:"), std::string::npos) << r.err;
  test::write_text(dir / "b.txt", "0 0 0\n1 2 0\n2 2 2\n3 0 2\n");
  r = run_cli("param " + (dir / "in.obj") + " -o " + (dir / "out.obj") + " --boundary " + (dir / "b.txt") +
                  " --report " + (dir / "r.json"),
              dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const MeshData out = read_mesh(dir / "out.obj");
  EXPECT_NEAR(out.TC(4, 0), 1.0, 1e-12);  // centre of the given square, not rescaled
  EXPECT_NEAR(out.TC(4, 1), 1.0, 1e-12);
  EXPECT_EQ(nlohmann::json::parse(test::slurp(dir / "r.json"))["scale"], "given");
}

TEST(Cli, OptimizeLambda) {
  TempDir dir;
  ASSERT_EQ(run_cli("generate cap --rings 10 -o " + (dir / "cap.obj"), dir).code, 0);
  for (const char* energy : {"edge", "area"}) {
    const auto r = run_cli("param " + (dir / "cap.obj") + " -o " + (dir / "out.obj") + " --optimize-lambda " + energy +
                               " --lambda-range -0.5,1.5 --report " + (dir / "r.json"),
                           dir);
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(test::slurp(dir / "r.json"));
    const auto& o = j["optimal_lambda"];
    EXPECT_GE(o["lambda"].get<double>(), -0.5);
    EXPECT_LE(o["lambda"].get<double>(), 1.5);
    EXPECT_LE(o["energy_at_lambda"].get<double>(), o["energy_at_0_authalic"].get<double>());
    EXPECT_LE(o["energy_at_lambda"].get<double>(), o["energy_at_1_conformal"].get<double>());
    EXPECT_EQ(j["method"], "optimal-lambda");
  }
  const auto bad = run_cli("param " + (dir / "cap.obj") + " -o " + (dir / "out2.obj") +
                               " --optimize-lambda edge --method authalic", dir);
  EXPECT_EQ(bad.code, 1);
}

TEST(Cli, OptimizeBoundary) {
  TempDir dir;
  ASSERT_EQ(run_cli("generate strip --rings 10 -o " + (dir / "strip.obj"), dir).code, 0);
  const auto r = run_cli("param " + (dir / "strip.obj") + " -o " + (dir / "out.obj") +
                             " --optimize-boundary dirichlet --iterations 50 --report " + (dir / "r.json"),
                         dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("boundary optimization: iteration 1,"), std::string::npos);  // progress lines
  const nlohmann::json j = nlohmann::json::parse(test::slurp(dir / "r.json"));
  const auto& b = j["boundary_optimization"];
  EXPECT_LT(b["energy_final"].get<double>(), b["energy_initial"].get<double>());
  EXPECT_LE(b["iterations"].get<int>(), 50);
  EXPECT_EQ(j["flipped_triangles"], 0);
  const auto quiet = run_cli("param " + (dir / "strip.obj") + " -o " + (dir / "out.obj") +
                                 " --optimize-boundary edge --gradient responses -q", dir);
  ASSERT_EQ(quiet.code, 0) << quiet.err;
  EXPECT_TRUE(quiet.err.empty());
}

TEST(Cli, HelpAndUsage) {
  TempDir dir;
  for (const char* cmd : {"--help", "param --help", "metrics --help", "generate --help"}) {
    const auto r = run_cli(cmd, dir);
    EXPECT_EQ(r.code, 0) << cmd;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << cmd;
  }
  EXPECT_EQ(run_cli("", dir).code, 1);
  EXPECT_EQ(run_cli("param", dir).code, 1);
  EXPECT_EQ(run_cli("frobnicate", dir).code, 1);
}

}  // namespace
}  // namespace intrinsic
