// Hostile input through the command-line tool: one table of malformed files
// (written here, byte by byte) and bad options, each with its exit code and a
// fragment of the message; after every case the directory holds the inputs
// and nothing else (no output, no report, no temporary file). Then the
// atomic-output guarantees: a write that fails for lack of room, a failure
// after the first output, and a run killed while writing.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "cli_support.h"
#include "intrinsic/io.h"
#include "test_support.h"

namespace intrinsic {
namespace {

using test::run_cli;
using test::TempDir;

// ---- writing inputs --------------------------------------------------------

// An n x n grid on [0,1]^2 with a small bump, as OBJ; vertex (x, y) is y*n + x.
std::string grid_obj(int n) {
  std::string s;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      s += "v " + std::to_string(double(x) / (n - 1)) + " " + std::to_string(double(y) / (n - 1)) + " " +
           std::to_string(0.1 * std::sin(x + 2.0 * y)) + "\n";
  for (int y = 0; y + 1 < n; ++y)
    for (int x = 0; x + 1 < n; ++x) {
      const int a = y * n + x + 1;  // 1-based
      s += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(a + n + 1) + "\n";
      s += "f " + std::to_string(a) + " " + std::to_string(a + n + 1) + " " + std::to_string(a + n) + "\n";
    }
  return s;
}

// The grid's outer loop at its own (x, y): a valid boundary file.
std::string grid_boundary(int n) {
  std::string s = "# outer loop of the grid\n";
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      if (x == 0 || y == 0 || x == n - 1 || y == n - 1)
        s += std::to_string(y * n + x) + " " + std::to_string(double(x) / (n - 1)) + " " +
             std::to_string(double(y) / (n - 1)) + "\n";
  return s;
}

const char* const kSquareObj =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 0.1\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n";
const char* const kSquareOff = "OFF\n5 4 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 0.1\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n";

std::string ply_ascii(const std::string& vertex_count, const std::string& body) {
  return "ply\nformat ascii 1.0\nelement vertex " + vertex_count +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
         "property list uchar int vertex_indices\nend_header\n" +
         body;
}

// Binary little-endian PLY: float x y z per vertex, uchar count + int indices per face.
struct BinaryPly {
  std::string body;
  int vertices = 0, faces = 0;
  void vertex(float x, float y, float z) {
    for (float c : {x, y, z}) raw(c);
    ++vertices;
  }
  void face(std::vector<std::int32_t> idx) {
    body.push_back(static_cast<char>(idx.size()));
    for (std::int32_t i : idx) raw(i);
    ++faces;
  }
  template <class T>
  void raw(T v) {
    char b[sizeof v];
    std::memcpy(b, &v, sizeof v);  // the test machines are little-endian
    body.append(b, sizeof v);
  }
  std::string str(std::int64_t announce_vertices = -1) const {
    return "ply\nformat binary_little_endian 1.0\nelement vertex " +
           std::to_string(announce_vertices >= 0 ? announce_vertices : vertices) +
           "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(faces) +
           "\nproperty list uchar int vertex_indices\nend_header\n" + body;
  }
};

BinaryPly square_ply() {
  BinaryPly p;
  p.vertex(0, 0, 0), p.vertex(1, 0, 0), p.vertex(1, 1, 0), p.vertex(0, 1, 0), p.vertex(0.5f, 0.5f, 0.1f);
  p.face({0, 1, 4}), p.face({1, 2, 4}), p.face({2, 3, 4}), p.face({3, 0, 4});
  return p;
}

std::string gzip(const std::string& data) { return test::gzip(data, 9, 9); }

// A Moebius strip of 5 quads: non-orientable, every face fine on its own.
std::string moebius_obj() {
  std::string s;
  const int n = 5;
  const double pi = std::acos(-1.0);
  for (int i = 0; i < n; ++i)
    for (double w : {0.3, -0.3}) {
      const double t = 2 * pi * i / n, r = 1 + w * std::cos(t / 2);
      s += "v " + std::to_string(r * std::cos(t)) + " " + std::to_string(r * std::sin(t)) + " " +
           std::to_string(w * std::sin(t / 2)) + "\n";
    }
  auto top = [](int i) { return 2 * i + 1; };
  auto bottom = [](int i) { return 2 * i + 2; };
  for (int i = 0; i < n; ++i) {
    int a = top(i), b = bottom(i), c = bottom((i + 1) % n), d = top((i + 1) % n);
    if (i == n - 1) std::swap(c, d);  // the half twist
    s += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "\n";
    s += "f " + std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(d) + "\n";
  }
  return s;
}

std::string garbage(std::size_t n, unsigned seed) {
  std::string s(n, '\0');
  for (char& c : s) {
    seed = seed * 1103515245u + 12345u;
    c = static_cast<char>(seed >> 16);
  }
  return s;
}

// ---- the table -------------------------------------------------------------

struct BadCase {
  std::string name;
  std::string input;     // file name in the temporary directory ("" for none)
  std::string contents;  // its bytes
  std::string args;      // after "param IN -o OUT --report REPORT", or the whole command line if it starts with '!'
  int code;
  std::string message;
  std::string boundary;  // contents of b.txt, if any (pass "--boundary {dir}/b.txt")
};

std::vector<BadCase> bad_cases() {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::string grid = grid_obj(5);
  const std::string bnd = grid_boundary(5);
  const std::string with_b = "--boundary {dir}/b.txt";
  std::vector<BadCase> c = {
      // OBJ
      {"obj empty file", "in.obj", "", "", 2, "no vertices"},
      {"obj only comments", "in.obj", "# nothing here\n\n", "", 2, "no vertices"},
      {"obj no faces", "in.obj", tri, "", 2, "no faces"},
      {"obj truncated vertex", "in.obj", tri + "v 1 1", "", 2, "in.obj:4: expected a number after 'v'"},
      {"obj truncated face", "in.obj", tri + "f 1 2", "", 2, "face has 2 vertices"},
      {"obj NaN coordinate", "in.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "", 2, "in.obj:1: vertex 1 has a non-finite"},
      {"obj inf coordinate", "in.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n", "", 2, "vertex 2 has a non-finite"},
      {"obj zero index", "in.obj", tri + "f 0 1 2\n", "", 2, "index 0 is invalid"},
      {"obj index overflow", "in.obj", tri + "f 1 2 99999999999999999999\n", "", 2, "is too large"},
      {"obj negative index out of range", "in.obj", tri + "f -1 -2 -4\n", "", 2, "out of range (only 3 defined so far)"},
      {"obj index past the end", "in.obj", tri + "f 1 2 9\n", "", 2, "in.obj:4: face index 9 out of range"},
      {"obj texture index past the end", "in.obj", tri + "vt 0 0\nf 1/1 2/1 3/2\n", "", 2, "face texture index 2 out of range"},
      {"obj garbage in face", "in.obj", tri + "f 1 2 three\n", "", 2, "expected a vertex index in face, found 'three'"},
      {"obj binary garbage", "in.obj", garbage(3000, 7), "", 2, "no vertices"},
      {"obj non-manifold edge", "in.obj", tri + "v 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n", "", 2,
       "has 3 faces (non-manifold edge"},
      {"obj non-manifold vertex", "in.obj", tri + "v -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 4 5\n", "", 2, "non-manifold"},
      {"obj non-orientable", "in.obj", moebius_obj(), "", 2, "not orientable"},
      {"obj closed", "in.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n", "", 2,
       "closed (no boundary)"},
      {"obj collinear face", "in.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", "", 2, "face 0 (line 4) is degenerate"},
      {"obj coincident vertices", "in.obj", tri + "v 1 0 0\nf 1 2 3\nf 2 4 3\n", "", 2, "face 1 (line 6) is degenerate"},
      {"obj repeated vertex", "in.obj", tri + "f 1 2 2\n", "", 2, "repeats vertex"},
      {"obj disk beside a closed component", "in.obj",
       tri + "v 5 0 0\nv 6 0 0\nv 5 1 0\nv 5 0 1\nf 1 2 3\nf 4 6 5\nf 4 5 7\nf 5 6 7\nf 4 7 6\n", "", 2,
       "closed"},
      {"obj over --max-vertices", "in.obj", kSquareObj, "--max-vertices 4", 2, "more than 4 vertices (the limit)"},
      // OFF
      {"off empty file", "in.off", "", "", 2, "no vertices (empty file)"},
      {"off wrong keyword", "in.off", "PFF\n3 1 0\n", "", 2, "expected the OFF header, found 'PFF'"},
      {"off 4-D variant", "in.off", "4OFF\n3 1 0\n", "", 2, "unsupported OFF variant"},
      {"off negative count", "in.off", "OFF\n-3 1 0\n", "", 2, "negative number of vertices"},
      {"off non-numeric count", "in.off", "OFF\nthree 1 0\n", "", 2, "expected the number of vertices"},
      {"off gigantic counts", "in.off", "OFF\n2000000000 2000000000 0\n0 0 0\n", "", 2,
       "header announces 2000000000 vertices, more than the limit"},
      {"off counts beyond the file", "in.off", "OFF\n1000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "", 2,
       "but the file holds only"},
      {"off truncated faces", "in.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "", 2, "file ends after 1 of 2 faces"},
      {"off face index out of range", "in.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "", 2,
       "face index 3 out of range (file has 3 vertices)"},
      {"off face shorter than announced", "in.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2\n", "", 2,
       "face 0 announces 4 vertices but lists 3"},
      {"off inf coordinate", "in.off", "OFF\n3 1 0\n0 0 inf\n1 0 0\n0 1 0\n3 0 1 2\n", "", 2, "vertex 0 has a non-finite"},
      {"off over --max-vertices", "in.off", kSquareOff, "--max-vertices 4", 2, "5 vertices, more than the limit of 4"},
      // PLY ASCII
      {"ply not a ply file", "in.ply", "plx\n", "", 2, "not a PLY file"},
      {"ply header never ends", "in.ply", "ply\nformat ascii 1.0\nelement vertex 3\n", "", 2, "no 'end_header'"},
      {"ply unknown format", "in.ply", "ply\nformat utf16 1.0\nend_header\n", "", 2, "unknown PLY format 'utf16'"},
      {"ply negative count", "in.ply", ply_ascii("-5", ""), "", 2, "expected the number of 'vertex' elements"},
      {"ply gigantic count", "in.ply", ply_ascii("3000000000", "0 0 0\n"), "", 2, "but the file holds at most"},
      {"ply truncated body", "in.ply", ply_ascii("3", "0 0 0\n1 0 0\n0 1 0\n3 0 1"), "", 2, "truncated file"},
      {"ply NaN", "in.ply", ply_ascii("3", "0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"), "", 2, "vertex 1: non-finite coordinate"},
      {"ply index out of range", "in.ply", ply_ascii("3", "0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n"), "", 2,
       "face index 5 out of range"},
      {"ply missing z", "in.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nelement face 1\n"
       "property list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n3 0 1 2\n",
       "", 2, "no 'z' property"},
      // PLY binary
      {"ply binary truncated", "in.ply", square_ply().str().substr(0, square_ply().str().size() - 6), "", 2,
       "face of 3 vertices runs past the end of the file"},
      {"ply binary gigantic count", "in.ply", square_ply().str(4000000000LL), "", 2, "but the file holds at most"},
      {"ply binary over --max-vertices", "in.ply", square_ply().str(), "--max-vertices 4", 2,
       "5 vertices, more than the limit of 4"},
      {"file larger than the limits admit", "in.obj", std::string(2 << 20, '#'), "--max-vertices 10", 2,
       "the most a mesh within the limits (10 vertices"},
      // GZIP
      {"gz garbage", "in.obj.gz", "\x1f\x8b" + garbage(500, 3), "", 2, "corrupt gzip data"},
      {"gz truncated", "in.obj.gz", gzip(grid).substr(0, gzip(grid).size() / 2), "", 2, "truncated gzip data"},
      {"gz bomb", "in.obj.gz", gzip(std::string(8 << 20, ' ')), "--max-vertices 1000", 2,
       "refusing a possible gzip bomb"},
      {"gz NaN inside", "in.off.gz", gzip("OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"), "", 2, "non-finite"},
      // Boundary files
      {"boundary duplicate vertex", "in.obj", grid, with_b, 2, "b.txt:18: vertex 0 is listed twice", bnd + "0 0.5 0.5\n"},
      {"boundary out of range", "in.obj", grid, with_b, 2, "vertex 25 is out of range (the mesh has 25 vertices)",
       bnd + "25 0 0\n"},
      {"boundary negative vertex", "in.obj", grid, with_b, 2, "vertex -1 is out of range", "-1 0 0\n" + bnd},
      {"boundary non-numeric", "in.obj", grid, with_b, 2, "b.txt:1: 'zero' is not a number", "0 zero 0\n"},
      {"boundary non-finite", "in.obj", grid, with_b, 2, "b.txt:1: non-finite position", "0 inf 0\n"},
      {"boundary missing field", "in.obj", grid, with_b, 2, "b.txt:1: expected 'vertex_index u v'", "0 0\n"},
      {"boundary empty", "in.obj", grid, with_b, 2, "no boundary positions", "# nothing\n"},
      {"boundary misses the outer loop", "in.obj", grid, with_b, 2, "miss 1 of the 16 outer-loop vertices, e.g. vertex 24",
       bnd.substr(0, bnd.rfind("24 "))},
      {"boundary coincident positions", "in.obj", grid, with_b, 2, "give vertices 20 and 24 the same position (0, 1)",
       bnd.substr(0, bnd.rfind("24 ")) + "24 0 1\n"},
      // Options
      {"unknown input format", "in.xyz", "hello\n", "", 1, "unknown input format '.xyz'"},
      {"input is a directory", "", "", "!param {dir} -o {dir}/out.obj", 2, "is a directory"},
      {"missing input", "", "", "!param {dir}/nothing.obj -o {dir}/out.obj", 2, "cannot open"},
      {"--max-vertices zero", "in.obj", kSquareObj, "--max-vertices 0", 1, "--max-vertices"},
      {"--max-vertices not a number", "in.obj", kSquareObj, "--max-vertices many", 1, "--max-vertices"},
      {"--max-residual NaN", "in.obj", kSquareObj, "--max-residual nan", 1, "--max-residual"},
      {"unknown method", "in.obj", kSquareObj, "--method foo", 1, "--method"},
      {"unknown output format", "in.obj", kSquareObj, "!param {dir}/in.obj -o {dir}/out.stl", 1, "unknown format '.stl'"},
      {"output directory missing", "in.obj", kSquareObj, "!param {dir}/in.obj -o {dir}/nowhere/out.obj", 4,
       "cannot write"},
      {"metrics without UVs", "in.obj", kSquareObj, "!metrics {dir}/in.obj --report {dir}/r.json", 2,
       "no texture coordinates"},
      {"metrics over --max-vertices", "in.obj", grid, "!metrics {dir}/in.obj --max-vertices 10", 2,
       "more than 10 vertices (the limit)"},
      // Numerical
      {"residual too large", "in.obj", grid, "--solver bicgstab --max-residual 1e-300", 3, "exceeds 1e-300"},
      {"failed solve names a nearly degenerate face", "in.obj",
       "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1e-9 0\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n",
       "--max-residual 1e-300", 3, "likely cause: face 0 (line 6) is nearly degenerate"},
  };
  return c;
}

TEST(BadInputs, TableHasEnoughCases) { EXPECT_GE(bad_cases().size(), 40u); }

TEST(BadInputs, ExitCodeMessageAndNothingWritten) {
  for (const BadCase& c : bad_cases()) {
    SCOPED_TRACE(c.name);
    TempDir dir;
    std::vector<std::string> inputs;
    if (!c.input.empty()) {
      test::write_text(dir / c.input, c.contents);
      inputs.push_back(c.input);
    }
    if (!c.boundary.empty()) {
      test::write_text(dir / "b.txt", c.boundary);
      inputs.push_back("b.txt");
    }
    std::sort(inputs.begin(), inputs.end());
    std::string args = c.args;
    if (!args.empty() && args[0] == '!') {
      args = args.substr(1);
    } else {
      args = "param {dir}/" + c.input + " -o {dir}/out.obj --report {dir}/r.json " + args;
    }
    for (size_t p; (p = args.find("{dir}")) != std::string::npos;) args.replace(p, 5, dir.path().string());
    const auto r = run_cli(args, dir);
    EXPECT_EQ(r.code, c.code) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << "expected '" << c.message << "' in: " << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
    EXPECT_EQ(dir.files(), inputs) << "a refused run must leave no output and no temporary file";
  }
}

// ---- atomic output ---------------------------------------------------------

// Runs `shell_prefix; intrinsic ARGS` through /bin/sh.
test::CliResult run_cli_with(const std::string& shell_prefix, const std::string& args, const TempDir& dir) {
  const std::string out = dir / ".stdout", err = dir / ".stderr";
  const std::string cmd = shell_prefix + "; exec " + std::string(INTRINSIC_CLI) + " " + args + " >" + out + " 2>" +
                          err + " </dev/null";
  const int status = std::system(cmd.c_str());
  test::CliResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = test::slurp(out);
  r.err = test::slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

TEST(AtomicOutput, FileSizeLimitFailsTheWriteAndLeavesNothing) {
  TempDir dir;
  test::write_text(dir / "in.obj", grid_obj(30));  // about 50 KB of output
  // ulimit -f counts 512-byte blocks in POSIX sh: 8 KB, far less than the mesh.
  const auto r = run_cli_with("ulimit -f 16", "param " + (dir / "in.obj") + " -o " + (dir / "out.obj"), dir);
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("cannot write " + (dir / "out.obj")), std::string::npos) << r.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{"in.obj"});
}

// Large meshes are formatted on worker threads and streamed: a write failing
// after several chunks went out must still leave nothing (and no thread).
TEST(AtomicOutput, FileSizeLimitMidStreamLeavesNothing) {
  TempDir dir;
  ASSERT_EQ(run_cli("generate wave --rings 200 -o " + (dir / "in.obj"), dir).code, 0);  // 120k vertices
  const auto r = run_cli_with("ulimit -f 4000", "param " + (dir / "in.obj") + " -o " + (dir / "out.obj"), dir);  // 2 MB
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("cannot write " + (dir / "out.obj")), std::string::npos) << r.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{"in.obj"});
}

TEST(AtomicOutput, ProducerExceptionLeavesNothing) {
  TempDir dir;
  const std::string path = dir / "out.bin";
  test::expect_error(
      [&] {
        write_file_atomically(path, [](const ByteSink& sink) {
          sink("partial", 7);
          throw_numerical("stop");
        });
      },
      ErrorKind::Numerical, "stop");
  EXPECT_TRUE(dir.files().empty());
  write_file_atomically(path, [](const ByteSink& sink) {
    sink("ab", 2);
    sink("cd", 2);
  });
  EXPECT_EQ(test::slurp(path), "abcd");
}

TEST(AtomicOutput, FailingReportRemovesTheMeshAlreadyWritten) {
  TempDir dir;
  test::write_text(dir / "in.obj", grid_obj(6));
  const auto r = run_cli("param " + (dir / "in.obj") + " -o " + (dir / "out.obj") + " --report " +
                             (dir / "missing-dir/r.json"),
                         dir);
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("missing-dir/r.json"), std::string::npos) << r.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{"in.obj"});
}

TEST(AtomicOutput, FailedRunKeepsThePreviousOutput) {
  TempDir dir;
  test::write_text(dir / "in.obj", grid_obj(30));
  test::write_text(dir / "out.obj", "previous\n");
  const auto r = run_cli_with("ulimit -f 16", "param " + (dir / "in.obj") + " -o " + (dir / "out.obj"), dir);
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_EQ(test::slurp(dir / "out.obj"), "previous\n");
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"in.obj", "out.obj"}));
}

// SIGTERM at various moments: whenever it lands, the output is either absent
// or complete, and no temporary file is left (the handler removes it).
TEST(AtomicOutput, KilledRunLeavesNoTemporaryFile) {
  TempDir dir;
  test::write_text(dir / "in.obj", grid_obj(150));
  for (int delay_ms : {0, 50, 200, 500}) {
    SCOPED_TRACE(delay_ms);
    const std::string out = dir / "out.obj";
    std::filesystem::remove(out);
    // The outer redirection silences the shell's "Terminated" notice.
    const std::string cmd = "(" + std::string(INTRINSIC_CLI) + " param " + (dir / "in.obj") + " -o " + out +
                            " -q >/dev/null 2>&1 </dev/null & pid=$!; sleep " + std::to_string(delay_ms / 1000.0) +
                            "; kill -TERM $pid; wait $pid) >/dev/null 2>&1";
    std::system(cmd.c_str());
    for (const std::string& f : dir.files()) EXPECT_EQ(f.find(".tmp"), std::string::npos) << f;
    if (std::filesystem::exists(out)) EXPECT_EQ(read_mesh(out).V.rows(), 150 * 150);
  }
}

// The same, deterministically, one level down: SIGTERM while
// write_file_atomically is writing (its temporary file exists) removes the
// temporary file, and the signal still terminates the process.
TEST(AtomicOutput, SignalDuringWriteRemovesTheTemporaryFile) {
  TempDir dir;
  const std::string path = dir / "big.bin";
  for (std::size_t megabytes : {64, 256}) {  // bigger if the write won the race
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      remove_temporary_files_on_signals();
      write_file_atomically(path, std::string(megabytes << 20, 'x'));
      _exit(0);
    }
    bool seen = false;
    for (int i = 0; i < 100000 && !seen; ++i) {
      for (const std::string& f : dir.files()) seen = seen || f.find(".tmp") != std::string::npos;
      if (!seen) std::this_thread::sleep_for(std::chrono::microseconds(50));
    }
    ::kill(pid, SIGTERM);
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (seen && WIFSIGNALED(status)) {
      EXPECT_EQ(WTERMSIG(status), SIGTERM);
      EXPECT_EQ(dir.files(), std::vector<std::string>{});
      return;
    }
    std::filesystem::remove(path);
  }
  GTEST_SKIP() << "the write always finished before the signal";
}

}  // namespace
}  // namespace intrinsic
