// One solve pipeline: regression tests for the answers the earlier
// five-way split got wrong (each case names the bug it guards). The expected
// values come from the mesh itself (vertex counts, loop lengths) or from a
// second route through the library (the same map asked for another way),
// never from numbers the code wrote.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "intrinsic/boundary_editor.h"
#include "intrinsic/boundary_optimization.h"
#include "intrinsic/charts.h"
#include "intrinsic/error.h"
#include "intrinsic/generate.h"
#include "intrinsic/io.h"
#include "intrinsic/optimal_lambda.h"
#include "intrinsic/parameterizer.h"
#include "test_support.h"

namespace intrinsic {
namespace {

using test::run_cli;
using test::TempDir;

// Used vertices that lie on no boundary loop.
int interior_vertices(const Mesh& mesh) {
  std::vector<char> on_loop(mesh.V.rows(), 0);
  for (const auto& loop : mesh.topology.boundary_loops)
    for (int v : loop) on_loop[v] = 1;
  int n = 0;
  for (int v = 0; v < mesh.V.rows(); ++v) n += mesh.topology.is_used[v] && !on_loop[v];
  return n;
}

nlohmann::json run_param(const TempDir& dir, const std::string& input, const std::string& args) {
  const auto r = run_cli("param " + input + " -o " + (dir / "out.obj") + " --report " + (dir / "r.json") + " " + args, dir);
  EXPECT_EQ(r.code, 0) << r.err;
  return nlohmann::json::parse(test::slurp(dir / "r.json"));
}

// Bug: --optimize-boundary reported residual 0 and free_vertices 0.
TEST(Pipeline, OptimizeBoundaryReportsTheFinalSolve) {
  TempDir dir;
  ASSERT_EQ(run_cli("generate cap --rings 6 -o " + (dir / "cap.obj"), dir).code, 0);
  const Mesh mesh = make_mesh(read_mesh(dir / "cap.obj"));
  const nlohmann::json r = run_param(dir, dir / "cap.obj", "--optimize-boundary edge");
  EXPECT_EQ(r["free_vertices"], interior_vertices(mesh));  // every loop vertex moves with the optimizer
  EXPECT_EQ(r["fixed_vertices"], mesh.topology.boundary_loops[0].size());
  EXPECT_GT(r["residual"].get<double>(), 0.0);  // a real solve has rounding
  EXPECT_LE(r["residual"].get<double>(), 1e-8);
  EXPECT_NE(r["solver"], "none (every vertex is fixed)");
}

// Bug: charts runs reported residual 0 and free_vertices 0.
TEST(Pipeline, ChartsReportSummedFreeVerticesAndWorstResidual) {
  const Mesh mesh = make_mesh(generate_two_disks(GenerateOptions{}), [] {
    ValidateOptions v;
    v.allow_several_components = true;
    return v;
  }());
  const ParamResult r = parameterize_charts(mesh, ParamOptions{});
  EXPECT_EQ(r.free_vertices, interior_vertices(mesh));
  ASSERT_EQ(r.charts.size(), 2u);
  double worst = 0;
  for (const ChartSummary& c : r.charts) {
    EXPECT_GT(c.free_vertices, 0);
    EXPECT_GT(c.residual, 0.0);
    worst = std::max(worst, c.residual);
  }
  EXPECT_EQ(r.residual, worst);
  EXPECT_EQ(r.free_vertices, r.charts[0].free_vertices + r.charts[1].free_vertices);
}

std::string exact(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

// Bug: lambda/mu in the report were rebuilt from the command line.
TEST(Pipeline, ReportedLambdaIsTheSolvedOne) {
  TempDir dir;
  ASSERT_EQ(run_cli("generate cap --rings 6 -o " + (dir / "cap.obj"), dir).code, 0);
  const nlohmann::json r = run_param(dir, dir / "cap.obj", "--optimize-lambda edge");
  const double best = r["optimal_lambda"]["lambda"];
  EXPECT_EQ(r["lambda"].get<double>(), best);
  EXPECT_DOUBLE_EQ(r["mu"].get<double>(), 1 - best);
  // The solved map is the mixed map at lambda*: asking for it directly gives the same UVs.
  const MeshData first = read_mesh(dir / "out.obj");
  const nlohmann::json direct = run_param(dir, dir / "cap.obj",
                                          "--method mixed --lambda " + exact(best) + " --mu " + exact(1 - best));
  EXPECT_EQ(direct["lambda"].get<double>(), best);
  EXPECT_LT((read_mesh(dir / "out.obj").TC - first.TC).cwiseAbs().maxCoeff(), 1e-9);  // as written to the file
}

// Bug: the hole rule's label depended on whether constraints were given.
TEST(Pipeline, HoleLabelIsTheSameWithAndWithoutConstraints) {
  TempDir dir;
  const std::string holed = dir / "holed.obj";  // 4 boundary loops
  const MeshData data = test::holed_wavy(3);
  write_mesh(holed, data.V, data.F, MatrixX2d());
  const Mesh mesh = make_mesh(read_mesh(holed));
  ASSERT_GT(mesh.topology.boundary_loops.size(), 1u);
  const int inner = mesh.F(mesh.F.rows() / 2, 0);
  test::write_text(dir / "c.json", R"({"points": [{"vertex": )" + std::to_string(inner) + R"(, "uv": [0.5, 0.5]}]})");
  for (const std::string method : {"authalic", "conformal"}) {
    SCOPED_TRACE(method);
    const nlohmann::json plain = run_param(dir, holed, "--method " + method + " --holes natural");
    const nlohmann::json constrained =
        run_param(dir, holed, "--method " + method + " --holes natural --constraints " + (dir / "c.json"));
    EXPECT_EQ(plain["holes"], constrained["holes"]);
    EXPECT_EQ(plain["holes"], method == "authalic" ? "free (method has no conformal term)" : "natural");
  }
}

// Bug: the likely-cause diagnosis existed only without constraints.
TEST(Pipeline, FailedConstrainedSolveNamesTheLikelyCause) {
  TempDir dir;
  test::write_text(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1e-9 0\n"
                                    "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n");
  test::write_text(dir / "c.json", R"({"points": [{"face": 2, "bary": [0.2, 0.3, 0.5], "uv": [0.5, 0.6]}]})");
  for (const std::string& extra : {std::string(), "--constraints " + (dir / "c.json")}) {
    SCOPED_TRACE(extra);
    const auto r = run_cli("param " + (dir / "bad.obj") + " -o " + (dir / "out.obj") + " --max-residual 1e-300 " + extra,
                           dir);
    EXPECT_EQ(r.code, 3) << r.err;
    EXPECT_NE(r.err.find("likely cause: face 0 (line 6) is nearly degenerate"), std::string::npos) << r.err;
  }
}

// Bug: a chart whose boundary was unusable silently got another method.
TEST(Pipeline, ChartFallbackIsReportedPerChart) {
  ValidateOptions v;
  v.allow_several_components = true;
  const Mesh mesh = make_mesh(generate_two_disks(GenerateOptions{}), v);
  // Given positions for chart 0's outer loop only.
  const int c0 = mesh.topology.face_component[0];
  const std::vector<int>& loop = mesh.topology.boundary_loops[mesh.topology.component_loops[c0][0]];
  ParamOptions o;
  o.weights.method = Method::Authalic;
  o.boundary = BoundaryShape::Given;
  for (size_t k = 0; k < loop.size(); ++k) {
    const double t = 2 * M_PI * k / loop.size();
    o.given.push_back({loop[k], Eigen::Vector2d(std::cos(t), std::sin(t))});
  }
  const ParamResult r = parameterize_charts(mesh, o);
  ASSERT_EQ(r.charts.size(), 2u);
  for (const ChartSummary& c : r.charts) {
    const bool given = c.component == c0;
    EXPECT_EQ(c.fallback, given ? ChartFallback::None : ChartFallback::NoGivenPositions);
    EXPECT_EQ(c.boundary, given ? BoundaryShape::Given : BoundaryShape::Natural);
    EXPECT_EQ(c.weights.method, given ? Method::Authalic : Method::Conformal);
  }
  EXPECT_EQ(chart_fallback_name(ChartFallback::NoGivenPositions), "natural map: the boundary file gives no position on this chart");
}

// Bug: BoundaryEditor::move left Parameterizer::boundary() stale.
TEST(Pipeline, EditorMovesUpdateTheParameterizersBoundary) {
  const Mesh mesh = test::wavy(6);
  Parameterizer p(mesh, ParamOptions{});
  BoundaryEditor editor(p);
  const FixedVertex moved{p.boundary()[3].vertex, p.boundary()[3].uv + Eigen::Vector2d(0.01, -0.02)};
  const MatrixX2d after = editor.move({moved});
  bool found = false;
  for (const FixedVertex& fv : p.boundary())
    if (fv.vertex == moved.vertex) {
      found = true;
      EXPECT_EQ(fv.uv, moved.uv);
    }
  EXPECT_TRUE(found);
  // Solving from the Parameterizer's boundary gives the editor's map.
  const ParamResult solved = p.solve_with_boundary(p.boundary());
  EXPECT_LT((solved.UV - after).cwiseAbs().maxCoeff(), 1e-12);
}

}  // namespace
}  // namespace intrinsic
