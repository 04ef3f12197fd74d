// `intrinsic serve` end to end: the built executable runs on a free port as a
// child process (killed at the end of every test, also on failure) and is
// driven over HTTP; its maps must equal `intrinsic param` with the same
// settings (moved boundary written to a boundary file, moved pins as --pin)
// to 1e-9 on generated surfaces (and on shared meshes: ServeCorpus), also
// when constraints change on the kept factorization (path and factorization
// count checked); the optimization endpoints equal the library's
// optimal_lambda and optimize_boundary; bad requests get 400/413 and the
// server keeps answering; two sessions stay independent. Every request
// carries the server's token (X-Intrinsic-Token; test_serve_guard.cpp tests
// the guard itself).
#include <array>
#include <cstdio>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "intrinsic/boundary_optimization.h"
#include "intrinsic/io.h"
#include "intrinsic/optimal_lambda.h"
#include "intrinsic/mesh.h"
#include "serve_support.h"
#include "test_support.h"

// Last: httplib.h includes <resolv.h>, whose macro _res breaks Eigen's headers.
#include <httplib.h>

namespace intrinsic {
namespace {

using nlohmann::json;

using test::ServerProcess;

struct Reply {
  int status = -1;
  json body;
};

// The server's token goes in the header (test_serve_guard.cpp checks the guard).
httplib::Headers api_headers(const ServerProcess& server, const std::string& session = "s1") {
  return {{"X-Session", session}, {"X-Intrinsic-Token", server.token()}};
}

Reply post(const ServerProcess& server, const std::string& body, const std::string& session = "s1",
           const std::string& route = "/api/solve") {
  httplib::Client client("127.0.0.1", server.port());
  client.set_read_timeout(300, 0);
  client.set_write_timeout(300, 0);
  auto res = client.Post(route.c_str(), api_headers(server, session), body, "application/json");
  Reply r;
  if (!res) return r;
  r.status = res->status;
  r.body = json::parse(res->body, nullptr, false);
  return r;
}

MatrixX2d uv_of(const json& answer) {
  MatrixX2d uv(answer.at("uv").size(), 2);
  for (size_t i = 0; i < answer["uv"].size(); ++i) uv.row(i) << answer["uv"][i][0], answer["uv"][i][1];
  return uv;
}

// Per-vertex UVs of a mesh written by `intrinsic param`.
MatrixX2d uv_of_file(const std::string& path) {
  const MeshData d = read_mesh(path);
  MatrixX2d uv = MatrixX2d::Zero(d.V.rows(), 2);
  for (Eigen::Index f = 0; f < d.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) uv.row(d.F(f, k)) = d.TC.row(d.FTC(f, k));
  return uv;
}

std::string g17(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

MatrixX2d run_param(const std::string& args, const test::TempDir& dir) {
  const test::CliResult r = test::run_cli("param " + args + " -o " + (dir / "out.obj") + " -q", dir);
  EXPECT_EQ(r.code, 0) << r.err;
  return uv_of_file(dir / "out.obj");
}

// The outer loop at the positions of `base` (an unmoved answer), with `moves` applied.
std::string boundary_file(const Mesh& mesh, const MatrixX2d& base, const json& moves) {
  std::map<int, Eigen::Vector2d> pos;
  for (const int v : mesh.topology.boundary_loops[0]) pos[v] = base.row(v).transpose();
  for (const auto& m : moves) pos[m[0].get<int>()] = {m[1].get<double>(), m[2].get<double>()};
  std::string text;
  for (const auto& [v, p] : pos) text += std::to_string(v) + " " + g17(p.x()) + " " + g17(p.y()) + "\n";
  return text;
}

std::vector<char> boundary_flags(const Mesh& mesh) {
  std::vector<char> on(mesh.V.rows(), 0);
  for (const auto& loop : mesh.topology.boundary_loops)
    for (const int i : loop) on[i] = 1;
  return on;
}

// Two faces sharing an edge, no corner on the boundary.
std::array<int, 2> interior_face_pair(const Mesh& mesh) {
  const std::vector<char> on = boundary_flags(mesh);
  auto interior = [&](Eigen::Index f) { return !on[mesh.F(f, 0)] && !on[mesh.F(f, 1)] && !on[mesh.F(f, 2)]; };
  std::map<std::pair<int, int>, int> edge_face;
  for (Eigen::Index f = mesh.F.rows() / 3; f < mesh.F.rows(); ++f) {
    if (!interior(f)) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      const auto e = std::minmax(a, b);
      auto it = edge_face.find(e);
      if (it != edge_face.end()) return {it->second, static_cast<int>(f)};
      edge_face[e] = static_cast<int>(f);
    }
  }
  return {-1, -1};
}

double max_diff(const MatrixX2d& a, const MatrixX2d& b) {
  return a.rows() == b.rows() ? (a - b).cwiseAbs().maxCoeff() : 1e300;
}

class ServeTest : public ::testing::Test {
 protected:
  // Serves a generated wavy patch written to the test's folder: rings 8
  // (about 190 vertices, near cat_head.obj's 131) or more.
  void start(int rings = 8) {
    GenerateOptions g;
    g.rings = rings;
    const MeshData d = generate_wavy_patch(g);
    write_mesh(dir_ / "wave.obj", d.V, d.F, MatrixX2d());
    serve(dir_ / "wave.obj");
  }
  void serve(const std::string& path) {
    path_ = path;
    mesh_ = make_mesh(read_mesh(path_));
    server_ = std::make_unique<ServerProcess>(path_);
    ASSERT_GT(server_->port(), 0) << "intrinsic serve did not print its URL";
  }
  int port() const { return server_->port(); }
  const ServerProcess& server() const { return *server_; }

  // Solves `options` + moves through the server, then `intrinsic param` with
  // the moved boundary in a file, and compares.
  void expect_fixed_equals_param(json options, const std::string& cli_options, const json& moves,
                                 const std::string& constraints_file = "") {
    const Reply base = post(server(), options.dump());
    ASSERT_EQ(base.status, 200) << base.body.dump();
    EXPECT_EQ(base.body["path"], "factor");
    options["moves"] = moves;
    const Reply moved = post(server(), options.dump());
    ASSERT_EQ(moved.status, 200) << moved.body.dump();
    EXPECT_EQ(moved.body["path"], "responses");
    test::write_text(dir_ / "b.txt", boundary_file(mesh_, uv_of(base.body), moves));
    const std::string extra = constraints_file.empty() ? "" : " --constraints " + constraints_file;
    const MatrixX2d cli = run_param(path_ + " --boundary " + (dir_ / "b.txt") + " " + cli_options + extra, dir_);
    EXPECT_LT(max_diff(uv_of(moved.body), cli), 1e-9);
  }

  test::TempDir dir_;
  std::string path_;
  Mesh mesh_;
  std::unique_ptr<ServerProcess> server_;
};

TEST_F(ServeTest, MeshCountsEqualTheMesh) {
  start();
  httplib::Client client("127.0.0.1", port());
  auto res = client.Get("/api/mesh", api_headers(server()));
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200);
  const json m = json::parse(res->body);
  EXPECT_EQ(m["vertices"], mesh_.V.rows());
  EXPECT_EQ(m["faces"], mesh_.F.rows());
  EXPECT_EQ(m["positions"].size(), 3 * mesh_.V.rows());
  EXPECT_EQ(m["triangles"].size(), 3 * mesh_.F.rows());
  EXPECT_EQ(m["boundary_loops"].size(), mesh_.topology.boundary_loops.size());
  auto page = client.Get(server().page().c_str());
  ASSERT_TRUE(page);
  EXPECT_NE(page->body.find("<canvas"), std::string::npos);
}

TEST_F(ServeTest, FixedCircleWithMovesEqualsParam) {
  start();
  const int v = mesh_.topology.boundary_loops[0][3], w = mesh_.topology.boundary_loops[0][10];
  expect_fixed_equals_param(json::object(), "", json::array({json::array({v, 0.55, 0.02})}));
  // The next drag from the same base: v goes back, w moves.
  const json moves = json::array({json::array({w, 0.9, 0.95})});
  const Reply again = post(server(), json{{"moves", moves}}.dump());
  ASSERT_EQ(again.status, 200);
  EXPECT_EQ(again.body["path"], "responses");
  const Reply base = post(server(), "{}");
  test::write_text(dir_ / "b2.txt", boundary_file(mesh_, uv_of(base.body), moves));
  EXPECT_LT(max_diff(uv_of(again.body), run_param(path_ + " --boundary " + (dir_ / "b2.txt"), dir_)), 1e-9);
}

TEST_F(ServeTest, MixedSquareEqualsParam) {
  start(24);
  const int v = mesh_.topology.boundary_loops[0][5];
  expect_fixed_equals_param({{"method", "mixed"}, {"lambda", 0.3}, {"mu", 0.7}, {"boundary", "square"}},
                            "--method mixed --lambda 0.3 --mu 0.7", json::array({json::array({v, 0.1, -0.05})}));
}

TEST_F(ServeTest, ConstraintsEqualParam) {
  start();
  std::vector<char> on_boundary(mesh_.V.rows(), 0);
  for (const auto& loop : mesh_.topology.boundary_loops)
    for (const int i : loop) on_boundary[i] = 1;
  int interior = 0;
  while (on_boundary[interior]) ++interior;
  const json c = {{"points", {{{"vertex", interior}, {"uv", {0.45, 0.55}}}}}};
  test::write_text(dir_ / "c.json", c.dump());
  const int v = mesh_.topology.boundary_loops[0][0];
  expect_fixed_equals_param({{"constraints", c}}, "", json::array({json::array({v, 1.02, 0.5})}), dir_ / "c.json");
}

TEST_F(ServeTest, NaturalWithMovedPinsEqualsParam) {
  start();
  const Reply first = post(server(), R"({"boundary": "natural"})");
  ASSERT_EQ(first.status, 200) << first.body.dump();
  json pins = first.body.at("pins");
  ASSERT_EQ(pins.size(), 2u);
  // The default pins given explicitly: the same map, on the same factorization.
  const Reply given = post(server(), json{{"boundary", "natural"}, {"pins", pins}}.dump());
  ASSERT_EQ(given.status, 200);
  EXPECT_EQ(given.body["path"], "responses");
  EXPECT_EQ(given.body["factorizations"], 1);
  EXPECT_LT(max_diff(uv_of(given.body), uv_of(first.body)), 1e-9);
  pins[1][1] = pins[1][1].get<double>() + 0.1;
  pins[1][2] = pins[1][2].get<double>() - 0.2;
  // Pin drags: two responses per pin superposed on the kept factorization.
  for (int step = 0; step < 2; ++step) {
    pins[step][1] = pins[step][1].get<double>() + 0.1;
    pins[1][2] = pins[1][2].get<double>() - 0.2;
    const Reply moved = post(server(), json{{"boundary", "natural"}, {"pins", pins}}.dump());
    ASSERT_EQ(moved.status, 200);
    EXPECT_EQ(moved.body["path"], "responses") << step;
    EXPECT_EQ(moved.body["factorizations"], 1) << step;
    std::string args = path_ + " --boundary natural";
    for (const auto& p : pins)
      args += " --pin " + std::to_string(p[0].get<int>()) + ":" + g17(p[1].get<double>()) + "," + g17(p[2].get<double>());
    EXPECT_LT(max_diff(uv_of(moved.body), run_param(args, dir_)), 1e-9) << step;
  }
  // No pins again: back to the default pins, still without refactoring.
  const Reply back = post(server(), R"({"boundary": "natural"})");
  ASSERT_EQ(back.status, 200);
  EXPECT_EQ(back.body["factorizations"], 1);
  EXPECT_LT(max_diff(uv_of(back.body), uv_of(first.body)), 1e-9);
}

// Circle <-> square keeps the factorization (same fixed vertices, new
// positions: one solve), with and without moves, against `intrinsic param`.
TEST_F(ServeTest, CircleSquareSwitchKeepsTheFactorization) {
  start(24);
  const Reply circle = post(server(), R"({"method": "authalic"})");
  ASSERT_EQ(circle.status, 200);
  EXPECT_EQ(circle.body["path"], "factor");
  const Reply square = post(server(), R"({"method": "authalic", "boundary": "square"})");
  ASSERT_EQ(square.status, 200) << square.body.dump();
  EXPECT_NE(square.body["path"], "factor");
  EXPECT_EQ(square.body["factorizations"], 1);
  EXPECT_LT(max_diff(uv_of(square.body), run_param(path_ + " --method authalic --boundary square", dir_)), 1e-9);
  // A square drag, then back to the circle with a drag: moves are relative to each request's shape.
  const int v = mesh_.topology.boundary_loops[0][6];
  const json moves = json::array({json::array({v, 0.3, -0.1})});
  const Reply dragged = post(server(), json{{"method", "authalic"}, {"boundary", "square"}, {"moves", moves}}.dump());
  ASSERT_EQ(dragged.status, 200);
  EXPECT_EQ(dragged.body["path"], "responses");
  test::write_text(dir_ / "b.txt", boundary_file(mesh_, uv_of(square.body), moves));
  EXPECT_LT(max_diff(uv_of(dragged.body), run_param(path_ + " --method authalic --boundary " + (dir_ / "b.txt"), dir_)), 1e-9);
  const Reply back = post(server(), json{{"method", "authalic"}, {"moves", moves}}.dump());
  ASSERT_EQ(back.status, 200);
  EXPECT_NE(back.body["path"], "factor");
  EXPECT_EQ(back.body["factorizations"], 1);
  test::write_text(dir_ / "b2.txt", boundary_file(mesh_, uv_of(circle.body), moves));
  EXPECT_LT(max_diff(uv_of(back.body), run_param(path_ + " --method authalic --boundary " + (dir_ / "b2.txt"), dir_)), 1e-9);
}

// Adding, retargeting, extending and removing constraints: one
// factorization throughout, each answer equal to `intrinsic param` with the
// constraint file and the moved boundary.
TEST_F(ServeTest, ConstraintChangesReuseTheFactorization) {
  start();
  const std::array<int, 2> faces = interior_face_pair(mesh_);
  ASSERT_GE(faces[0], 0);
  const Reply base = post(server(), "{}");
  ASSERT_EQ(base.status, 200);
  EXPECT_EQ(base.body["path"], "factor");
  const int v = mesh_.topology.boundary_loops[0][4];
  const json moves = json::array({json::array({v, 0.6, -0.03})});
  test::write_text(dir_ / "b.txt", boundary_file(mesh_, uv_of(base.body), moves));
  const json p0 = {{"face", faces[0]}, {"bary", {0.2, 0.3, 0.5}}};
  const json p1 = {{"face", faces[1]}, {"bary", {0.6, 0.2, 0.2}}};
  const json steps[] = {
      {{"points", {{{"face", faces[0]}, {"bary", {0.2, 0.3, 0.5}}, {"uv", {0.45, 0.55}}}}}},
      {{"points", {{{"face", faces[0]}, {"bary", {0.2, 0.3, 0.5}}, {"uv", {0.40, 0.62}}}}}},
      {{"points", {{{"face", faces[0]}, {"bary", {0.2, 0.3, 0.5}}, {"uv", {0.40, 0.62}}}}},
       {"lines", {{{"path", {p0, p1}}, {"to", {{0.40, 0.62}, {0.47, 0.60}}}}}}},
      {{"points", {{{"face", faces[0]}, {"bary", {0.2, 0.3, 0.5}}, {"uv", {0.40, 0.62}}}}},
       {"lines", {{{"path", {p0, p1}}, {"to", {{0.40, 0.62}, {0.50, 0.66}}}}}}},
  };
  // Same rows, new targets: the target responses (computed on a row's first new target).
  const char* const paths[] = {"constraints", "responses", "constraints", "responses"};
  for (int k = 0; k < 4; ++k) {
    const Reply r = post(server(), json{{"constraints", steps[k]}, {"moves", moves}}.dump());
    ASSERT_EQ(r.status, 200) << r.body.dump();
    EXPECT_EQ(r.body["path"], paths[k]) << k;
    EXPECT_EQ(r.body["factorizations"], 1) << k;
    test::write_text(dir_ / "c.json", steps[k].dump());
    const MatrixX2d cli =
        run_param(path_ + " --boundary " + (dir_ / "b.txt") + " --constraints " + (dir_ / "c.json"), dir_);
    EXPECT_LT(max_diff(uv_of(r.body), cli), 1e-9) << k;
  }
  const Reply cleared = post(server(), json{{"moves", moves}}.dump());
  ASSERT_EQ(cleared.status, 200);
  EXPECT_EQ(cleared.body["path"], "constraints");
  EXPECT_EQ(cleared.body["factorizations"], 1);
  EXPECT_LT(max_diff(uv_of(cleared.body), run_param(path_ + " --boundary " + (dir_ / "b.txt"), dir_)), 1e-9);
  // A constraint the boundary cannot meet (on fixed vertices only, elsewhere): 400, and the session recovers.
  const json bad = {{"points", {{{"vertex", v}, {"uv", {0.1, 0.1}}}}}};
  EXPECT_EQ(post(server(), json{{"constraints", bad}}.dump()).status, 400);
  EXPECT_EQ(post(server(), "{}").status, 200);
}

// Natural map: a constraint added and retargeted on the kept factorization,
// then moved pins, against `intrinsic param --pin ... --constraints`.
TEST_F(ServeTest, NaturalConstraintsAndPinsReuseTheFactorization) {
  start();
  const std::array<int, 2> faces = interior_face_pair(mesh_);
  const Reply first = post(server(), R"({"boundary": "natural"})");
  ASSERT_EQ(first.status, 200);
  json pins = first.body.at("pins");
  ASSERT_EQ(post(server(), json{{"boundary", "natural"}, {"pins", pins}}.dump()).status, 200);  // the default pins, given
  const json c1 = {{"points", {{{"face", faces[0]}, {"bary", {0.3, 0.3, 0.4}}, {"uv", {0.5, 0.4}}}}}};
  const json c2 = {{"points", {{{"face", faces[0]}, {"bary", {0.3, 0.3, 0.4}}, {"uv", {0.55, 0.35}}}}}};
  const Reply a = post(server(), json{{"boundary", "natural"}, {"constraints", c1}, {"pins", pins}}.dump());
  ASSERT_EQ(a.status, 200) << a.body.dump();
  EXPECT_EQ(a.body["path"], "constraints");
  pins[1][1] = pins[1][1].get<double>() + 0.05;
  const Reply b = post(server(), json{{"boundary", "natural"}, {"constraints", c2}, {"pins", pins}}.dump());
  ASSERT_EQ(b.status, 200) << b.body.dump();
  EXPECT_EQ(b.body["path"], "responses") << "new target and pin through the editor's responses";
  EXPECT_EQ(b.body["factorizations"], 1);
  test::write_text(dir_ / "c.json", c2.dump());
  std::string args = path_ + " --boundary natural --constraints " + (dir_ / "c.json");
  for (const auto& p : pins)
    args += " --pin " + std::to_string(p[0].get<int>()) + ":" + g17(p[1].get<double>()) + "," + g17(p[2].get<double>());
  EXPECT_LT(max_diff(uv_of(b.body), run_param(args, dir_)), 1e-9);
}

TEST_F(ServeTest, OptimalLambdaEqualsTheLibrary) {
  start(24);
  for (const char* energy : {"edge", "area"}) {
    const Reply r = post(server(), json{{"energy", energy}, {"boundary", "square"}}.dump(), "s1", "/api/optimal_lambda");
    ASSERT_EQ(r.status, 200) << r.body.dump();
    OptimalLambdaOptions o;
    o.base.boundary = BoundaryShape::Square;
    o.energy = parse_lambda_energy(energy);
    const OptimalLambdaResult lib = optimal_lambda(mesh_, o);
    EXPECT_NEAR(r.body["lambda"].get<double>(), lib.lambda, 1e-9) << energy;
    EXPECT_NEAR(r.body["energy"].get<double>(), lib.energy, 1e-9 * std::max(1.0, lib.energy)) << energy;
    EXPECT_LT(max_diff(uv_of(r.body), lib.map.UV), 1e-9) << energy;
    EXPECT_EQ(r.body["path"], "blend");
  }
  // With moves: the library with the moved boundary as given positions.
  const Reply base = post(server(), "{}");
  const int v = mesh_.topology.boundary_loops[0][6];
  const json moves = json::array({json::array({v, 0.3, -0.1})});
  const Reply r = post(server(), json{{"moves", moves}}.dump(), "s1", "/api/optimal_lambda");
  ASSERT_EQ(r.status, 200) << r.body.dump();
  OptimalLambdaOptions o;
  o.base.boundary = BoundaryShape::Given;
  for (const int i : mesh_.topology.boundary_loops[0])
    o.base.given.push_back({i, i == v ? Eigen::Vector2d(0.3, -0.1) : Eigen::Vector2d(uv_of(base.body).row(i))});
  const OptimalLambdaResult lib = optimal_lambda(mesh_, o);
  EXPECT_NEAR(r.body["lambda"].get<double>(), lib.lambda, 1e-9);
  EXPECT_LT(max_diff(uv_of(r.body), lib.map.UV), 1e-9);
}

TEST_F(ServeTest, BoundaryOptimizationEqualsTheLibraryAndReportsProgress) {
  start();
  const Reply r = post(server(), R"({"energy": "area", "max_iterations": 5})", "s1", "/api/optimize_boundary");
  ASSERT_EQ(r.status, 200) << r.body.dump();
  BoundaryOptimizationOptions o;
  o.energy = BoundaryEnergy::Area;
  o.max_iterations = 5;
  const BoundaryOptimizationResult lib = optimize_boundary(mesh_, o);
  ASSERT_EQ(r.body["energy_history"].size(), lib.energy_history.size());
  for (size_t k = 0; k < lib.energy_history.size(); ++k)
    EXPECT_NEAR(r.body["energy_history"][k].get<double>(), lib.energy_history[k], 1e-9 * lib.energy_history[0]);
  EXPECT_LT(max_diff(uv_of(r.body), lib.map.UV), 1e-9);
  EXPECT_EQ(r.body["iterations"], lib.iterations);
  httplib::Client client("127.0.0.1", port());
  auto progress = client.Get("/api/optimize_boundary/progress", api_headers(server()));
  ASSERT_TRUE(progress);
  const json p = json::parse(progress->body);
  EXPECT_EQ(p["running"], false);
  EXPECT_EQ(p["energies"].size(), static_cast<size_t>(lib.iterations));
}

TEST_F(ServeTest, BadOptimizationRequestsGet400) {
  start();
  const char* const bad_lambda[] = {"{", R"({"energy": "fancy"})", R"({"energy": 3})", R"({"boundary": "natural"})",
                                    R"({"constraints": {"points": [{"vertex": 0, "uv": [0, 0]}]}})",
                                    R"({"max_iterations": 3})", R"({"moves": [[-1, 0, 0]]})"};
  for (const char* body : bad_lambda) {
    const Reply r = post(server(), body, "s1", "/api/optimal_lambda");
    EXPECT_EQ(r.status, 400) << body << " -> " << r.body.dump();
    EXPECT_TRUE(r.body.is_object() && r.body.contains("error")) << body;
  }
  const char* const bad_boundary[] = {"[]", R"({"energy": "stretch"})", R"({"max_iterations": 0})",
                                      R"({"max_iterations": 1.5})", R"({"max_iterations": 100000})",
                                      R"({"boundary": "natural"})", R"({"moves": [[0, NaN, 0]]})"};
  for (const char* body : bad_boundary) {
    const Reply r = post(server(), body, "s1", "/api/optimize_boundary");
    EXPECT_EQ(r.status, 400) << body << " -> " << r.body.dump();
  }
  EXPECT_EQ(post(server(), R"({"energy": "area"})", "s1", "/api/optimal_lambda").status, 200);
  EXPECT_TRUE(server_->alive());
}

TEST_F(ServeTest, BadRequestsGet400AndTheServerKeepsServing) {
  start();
  const std::string n = std::to_string(mesh_.V.rows());
  const char* const bad[] = {
      "{", "[]", "nonsense", R"({"method": "fancy"})", R"({"unknown": 1})", R"({"boundary": 3})",
      R"({"moves": [[-1, 0, 0]]})", R"({"moves": [[0, NaN, 0]]})", R"({"moves": [[0, 1e999, 0]]})",
      R"({"moves": [[0, "a", 0]]})", R"({"moves": [[0.5, 0, 0]]})", R"({"moves": {"a": 1}})",
      R"({"lambda": 0.5})", R"({"method": "mixed", "lambda": 0, "mu": 0})", R"({"pins": [[0, 0, 0], [1, 1, 1]]})",
      R"({"boundary": "natural", "pins": [[0, 0, 0]]})", R"({"constraints": {"points": [{"vertex": 0}]}})",
      R"({"constraints": {"points": [{"vertex": 99999999, "uv": [0, 0]}]}})", R"({"constraints": 5})"};
  for (const char* body : bad) {
    const Reply r = post(server(), body);
    EXPECT_EQ(r.status, 400) << body << " -> " << r.body.dump();
    EXPECT_TRUE(r.body.is_object() && r.body.contains("error")) << body;
  }
  EXPECT_EQ(post(server(), "{\"moves\": [[" + n + ", 0, 0]]}").status, 400);
  const int interior_or_not = 0;  // vertex 0 may or may not be fixed: 200 or 400, never a crash
  const int s = post(server(), "{\"moves\": [[" + std::to_string(interior_or_not) + ", 0.5, 0.5]]}").status;
  EXPECT_TRUE(s == 200 || s == 400);
  EXPECT_EQ(post(server(), std::string(200, '[') + std::string(200, ']')).status, 400);
  const Reply big = post(server(), "{\"moves\": [" + std::string(17 << 20, ' ') + "]}");
  EXPECT_EQ(big.status, 413);
  const Reply ok = post(server(), "{}");
  EXPECT_EQ(ok.status, 200);
  EXPECT_TRUE(server_->alive());
}

// ?uv=binary (what the page uses): the same UVs bit for bit as raw
// little-endian float64, the rest of the answer in the X-Answer header.
TEST_F(ServeTest, BinaryAnswerEqualsTheJsonAnswer) {
  start();
  const int v = mesh_.topology.boundary_loops[0][2];
  const std::string body = "{\"moves\": [[" + std::to_string(v) + ", 0.4, 0.1]]}";
  const Reply text = post(server(), body);
  ASSERT_EQ(text.status, 200);
  httplib::Client client("127.0.0.1", port());
  auto res = client.Post("/api/solve?uv=binary", api_headers(server()), body, "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200);
  ASSERT_EQ(res->body.size(), static_cast<size_t>(16 * mesh_.V.rows()));
  const MatrixX2d uv = uv_of(text.body);
  for (Eigen::Index i = 0; i < uv.rows(); ++i)
    for (int k = 0; k < 2; ++k) {
      std::uint64_t bits = 0;
      for (int b = 0; b < 8; ++b) bits |= std::uint64_t(static_cast<unsigned char>(res->body[16 * i + 8 * k + b])) << (8 * b);
      double x;
      std::memcpy(&x, &bits, 8);
      ASSERT_EQ(x, uv(i, k)) << i;
    }
  const json header = json::parse(res->get_header_value("X-Answer"));
  EXPECT_FALSE(header.contains("uv"));
  EXPECT_EQ(header["flipped_triangles"], text.body["flipped_triangles"]);
  EXPECT_EQ(header["path"], "responses");
  EXPECT_EQ(client.Post("/api/solve?uv=text", api_headers(server()), body, "application/json")->status, 400);
  // ?uv=float32: each value is the JSON answer's double rounded to float32 (half the bytes).
  auto small = client.Post("/api/solve?uv=float32", api_headers(server()), body, "application/json");
  ASSERT_TRUE(small);
  ASSERT_EQ(small->status, 200);
  ASSERT_EQ(small->body.size(), static_cast<size_t>(8 * mesh_.V.rows()));
  for (Eigen::Index i = 0; i < uv.rows(); ++i)
    for (int k = 0; k < 2; ++k) {
      std::uint32_t bits = 0;
      for (int b = 0; b < 4; ++b) bits |= std::uint32_t(static_cast<unsigned char>(small->body[8 * i + 4 * k + b])) << (8 * b);
      float x;
      std::memcpy(&x, &bits, 4);
      ASSERT_EQ(x, static_cast<float>(uv(i, k))) << i;
    }
  const json drag = json::parse(small->get_header_value("X-Answer"));
  EXPECT_EQ(drag["path"], "responses");
  // While dragging only the flips are counted (the same count); the means come with the exact answer.
  EXPECT_EQ(drag["flipped_triangles"], text.body["flipped_triangles"]);
  EXPECT_FALSE(drag.contains("angle_distortion_mean"));
  EXPECT_TRUE(header.contains("angle_distortion_mean"));
}

// The same server on shared real meshes (skipped where ../shared is absent).
class ServeCorpus : public ServeTest {};

TEST_F(ServeCorpus, SharedMeshesEqualParam) {
  REQUIRE_SHARED_MESHES();
  serve(test::shared_mesh("cat_head.obj"));
  const int v = mesh_.topology.boundary_loops[0][3];
  expect_fixed_equals_param(json::object(), "", json::array({json::array({v, 0.55, 0.02})}));
  serve(test::shared_mesh("camel_b.obj"));
  const int w = mesh_.topology.boundary_loops[0][5];
  expect_fixed_equals_param({{"method", "mixed"}, {"lambda", 0.3}, {"mu", 0.7}, {"boundary", "square"}},
                            "--method mixed --lambda 0.3 --mu 0.7", json::array({json::array({w, 0.1, -0.05})}));
}

TEST_F(ServeTest, TwoSessionsAreIndependent) {
  start();
  const Reply base_a = post(server(), "{}", "tab-a");
  const Reply base_b = post(server(), R"({"boundary": "square"})", "tab-b");
  ASSERT_EQ(base_a.status, 200);
  ASSERT_EQ(base_b.status, 200);
  const int v = mesh_.topology.boundary_loops[0][7];
  const std::string move = "{\"moves\": [[" + std::to_string(v) + ", 0.3, 0.3]]}";
  const Reply moved_a = post(server(), move, "tab-a");
  ASSERT_EQ(moved_a.status, 200);
  EXPECT_EQ(moved_a.body["path"], "responses");
  const Reply again_b = post(server(), R"({"boundary": "square"})", "tab-b");
  EXPECT_EQ(again_b.body["path"], "responses");  // b's factorization was kept
  EXPECT_LT(max_diff(uv_of(again_b.body), uv_of(base_b.body)), 1e-12);
  const Reply again_a = post(server(), move, "tab-a");
  EXPECT_EQ(again_a.body["path"], "responses");
  EXPECT_LT(max_diff(uv_of(again_a.body), uv_of(moved_a.body)), 1e-12);
}

}  // namespace
}  // namespace intrinsic
