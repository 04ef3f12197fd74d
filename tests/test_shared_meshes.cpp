// Every shared real mesh: the topology we find agrees with the independent
// meshstat.json of ../shared/meshes, and every method with a circle boundary
// gives a finite map whose flips and distortion match the committed
// regression table tests/regression/shared_meshes.tsv (regenerate it with
// INTRINSIC_UPDATE_REGRESSION=1 after an intended change, and say why in the
// commit). A missing mesh fails; nothing is skipped.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "intrinsic/io.h"
#include "intrinsic/metrics.h"
#include "intrinsic/parameterize.h"
#include "test_support.h"

namespace intrinsic {
namespace {

const char* kSmallMeshes[] = {"alligator.obj", "animal.obj", "beetle.off", "camel_b.obj", "camelhead.off",
                              "cat_head.obj", "face-bff.obj", "fairing-cross.off", "inspired_mesh.obj",
                              "inverted-triangles.obj", "max-planck-partial.obj", "maze.obj", "snail.obj",
                              "stanford-bunny.obj"};
const char* kLargeMesh = "max-planck-partial-loop2.obj.gz";

std::string regression_path() { return std::string(INTRINSIC_SOURCE_DIR) + "/tests/regression/shared_meshes.tsv"; }

struct Row {
  int flipped = 0;
  double angle_mean = 0, area_mean = 0;
};

std::map<std::string, Row> read_table() {
  std::map<std::string, Row> table;
  std::ifstream in(regression_path());
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    std::string key, mesh, method;
    Row r;
    s >> mesh >> method >> r.flipped >> r.angle_mean >> r.area_mean;
    table[mesh + " " + method] = r;
  }
  return table;
}

nlohmann::json meshstat() {
  std::ifstream in(test::shared_mesh("meshstat.json"));
  EXPECT_TRUE(in.good()) << "missing meshstat.json";
  return nlohmann::json::parse(in);
}

void check_topology(const std::string& name, const Mesh& mesh, const nlohmann::json& stat) {
  const nlohmann::json& s = stat.at(name);
  EXPECT_EQ(mesh.V.rows(), s.at("vertices").get<int>());
  EXPECT_EQ(mesh.topology.num_components, s.at("components").get<int>());
  EXPECT_EQ(mesh.validation.unreferenced_vertices, s.at("unreferenced_vertices").get<int>());
  EXPECT_EQ(mesh.validation.reoriented_faces, s.at("faces_to_flip_for_consistent_orientation").get<int>());
  std::vector<int> ours, theirs = s.at("boundary_loop_lengths").get<std::vector<int>>();
  for (const auto& loop : mesh.topology.boundary_loops) ours.push_back(static_cast<int>(loop.size()));
  std::sort(ours.begin(), ours.end());
  std::sort(theirs.begin(), theirs.end());
  EXPECT_EQ(ours, theirs);
}

struct MethodCase {
  const char* label;
  Method method;
  double lambda, mu;
};
const MethodCase kMethods[] = {{"conformal", Method::Conformal, 1, 0},
                               {"authalic", Method::Authalic, 0, 1},
                               {"mixed-0.5-0.5", Method::Mixed, 0.5, 0.5}};

void run_mesh(const std::string& name, std::ostream* update) {
  const MeshData data = read_mesh(test::shared_mesh(name));
  const Mesh mesh = make_mesh(data);
  check_topology(name, mesh, meshstat());
  const auto table = read_table();
  for (const MethodCase& m : kMethods) {
    ParamOptions o;
    o.weights.method = m.method;
    o.weights.lambda = m.lambda;
    o.weights.mu = m.mu;
    const ParamResult r = parameterize(mesh, o);
    ASSERT_TRUE(r.UV.allFinite()) << name << " " << m.label;
    EXPECT_LT(r.residual, 1e-8);
    const DistortionSummary d = summarize_distortion(mesh.V, mesh.F, r.UV);
    if (update) {
      *update << name << '\t' << m.label << '\t' << d.flipped_triangles << '\t' << d.angle_distortion.mean << '\t'
              << d.area_distortion.mean << '\n';
      continue;
    }
    const auto it = table.find(name + " " + m.label);
    ASSERT_NE(it, table.end()) << "no regression entry for " << name << " " << m.label;
    EXPECT_EQ(d.flipped_triangles, it->second.flipped) << name << " " << m.label;
    EXPECT_NEAR(d.angle_distortion.mean, it->second.angle_mean, 1e-5 * it->second.angle_mean) << name << " " << m.label;
    EXPECT_NEAR(d.area_distortion.mean, it->second.area_mean, 1e-5 * it->second.area_mean) << name << " " << m.label;
  }
}

TEST(SharedMeshes, EveryMeshEveryMethodMatchesRegressionTable) {
  const bool update = std::getenv("INTRINSIC_UPDATE_REGRESSION") != nullptr;
  std::ostringstream rows;
  rows.precision(12);
  if (update)
    rows << "# mesh\tmethod\tflipped\tangle_mean\tarea_mean  (circle boundary, arc-length spacing, default holes rule)\n";
  for (const char* name : kSmallMeshes) {
    SCOPED_TRACE(name);
    run_mesh(name, update ? &rows : nullptr);
  }
  if (update) {
    std::ofstream out(regression_path());
    out << rows.str();
  }
}

TEST(SharedMeshes, AlligatorIsFlatSoItsOwnBoundaryReproducesIt) {
  const Mesh mesh = make_mesh(read_mesh(test::shared_mesh("alligator.obj")));
  ParamOptions o;
  o.boundary = BoundaryShape::Given;
  for (int v : mesh.topology.boundary_loops[0]) o.given.push_back({v, mesh.V.row(v).head<2>().transpose()});
  for (Method m : {Method::Conformal, Method::Authalic}) {
    o.weights.method = m;
    const ParamResult r = parameterize(mesh, o);
    EXPECT_LT((r.UV - mesh.V.leftCols(2)).cwiseAbs().maxCoeff(), 1e-10 * test::diameter3(mesh.V));
  }
}

TEST(SharedMeshesLarge, GzipLoop2ParameterizesWithoutFlips) {
  const Mesh mesh = make_mesh(read_mesh(test::shared_mesh(kLargeMesh)));
  EXPECT_EQ(mesh.V.rows(), 507655);
  check_topology(kLargeMesh, mesh, meshstat());
  ParamOptions o;
  const ParamResult r = parameterize(mesh, o);
  EXPECT_LT(r.residual, 1e-8);
  EXPECT_EQ(summarize_distortion(mesh.V, mesh.F, r.UV).flipped_triangles, 0);
}

}  // namespace
}  // namespace intrinsic
