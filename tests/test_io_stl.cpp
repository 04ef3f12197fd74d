// Tests of the STL reader (ASCII and binary, welding of coincident corners,
// errors) and of PLY headers with free-text lines. The STL files are written
// here by the test's own small writers from a generated torus, and what is
// read is compared face by face with the torus' float32-rounded positions.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "cli_support.h"
#include "intrinsic/generate.h"
#include "intrinsic/io.h"
#include "test_support.h"

using namespace intrinsic;

namespace {

MeshData torus() {
  GenerateOptions o;
  o.rings = 8;
  return generate_torus(o);
}

std::array<float, 3> corner(const MeshData& m, int f, int c) {
  const auto p = m.V.row(m.F(f, c));
  return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
}

std::array<float, 3> face_normal(const MeshData& m, int f) {
  const Eigen::Vector3d n =
      (m.V.row(m.F(f, 1)) - m.V.row(m.F(f, 0))).cross(m.V.row(m.F(f, 2)) - m.V.row(m.F(f, 0))).normalized();
  return {static_cast<float>(n.x()), static_cast<float>(n.y()), static_cast<float>(n.z())};
}

// ASCII STL, faces [first, last) as one solid, corners at float32 precision
// (%.9g restores every float exactly).
std::string ascii_solid(const MeshData& m, int first, int last, const std::string& eol = "\n",
                        const std::string& name = "torus") {
  std::string s = "solid " + name + eol;
  char buf[160];
  for (int f = first; f < last; ++f) {
    const auto n = face_normal(m, f);
    std::snprintf(buf, sizeof buf, "  facet normal %e %e %e", n[0], n[1], n[2]);
    s += buf + eol + "    outer loop" + eol;
    for (int c = 0; c < 3; ++c) {
      const auto p = corner(m, f, c);
      std::snprintf(buf, sizeof buf, "      vertex %.9g %.9g %.9g", p[0], p[1], p[2]);
      s += buf + eol;
    }
    s += "    endloop" + eol + "  endfacet" + eol;
  }
  return s + "endsolid " + name + eol;
}

std::string ascii_stl(const MeshData& m, const std::string& eol = "\n") {
  return ascii_solid(m, 0, static_cast<int>(m.F.rows()), eol);
}

void put_u32(std::string& s, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) s += static_cast<char>((v >> (8 * i)) & 0xff);
}
void put_f32(std::string& s, float x) {
  std::uint32_t v;
  std::memcpy(&v, &x, 4);
  put_u32(s, v);
}

// Binary STL (little endian) with the given 80-byte header text.
std::string binary_stl(const MeshData& m, const std::string& header = "binary STL from test_io_stl") {
  std::string s = header;
  s.resize(80, '\0');
  put_u32(s, static_cast<std::uint32_t>(m.F.rows()));
  for (int f = 0; f < m.F.rows(); ++f) {
    for (float x : face_normal(m, f)) put_f32(s, x);
    for (int c = 0; c < 3; ++c)
      for (float x : corner(m, f, c)) put_f32(s, x);
    s += std::string(2, '\0');  // attribute byte count
  }
  return s;
}

// What was read holds the generated faces in order, each corner at the
// float32 position of the generated one, and exactly as many vertices: every
// corner shared in the generated mesh was welded, nothing else.
void expect_generated(const MeshData& got, const MeshData& gen) {
  ASSERT_EQ(got.F.rows(), gen.F.rows());
  EXPECT_EQ(got.V.rows(), gen.V.rows());
  std::set<std::array<float, 9>> want, have;
  for (int f = 0; f < gen.F.rows(); ++f) {
    std::array<float, 9> a{}, b{};
    for (int c = 0; c < 3; ++c) {
      const auto p = corner(gen, f, c);
      for (int k = 0; k < 3; ++k) {
        a[3 * c + k] = p[k];
        b[3 * c + k] = static_cast<float>(got.V(got.F(f, c), k));
        EXPECT_EQ(got.V(got.F(f, c), k), static_cast<double>(p[k])) << "face " << f << " corner " << c;
      }
    }
    want.insert(a);
    have.insert(b);
  }
  EXPECT_EQ(want, have);
}

// Reads `bytes` as `name` expecting an Input error containing every fragment.
std::string stl_input_error(const std::string& bytes, const std::string& name, std::vector<std::string> fragments,
                        const ReadOptions& opt = {}) {
  try {
    read_mesh_from_memory(bytes, name, opt);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
    for (const auto& f : fragments)
      EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << "message: " << e.what() << "\nlacks: " << f;
    return e.what();
  }
  ADD_FAILURE() << "no error reading " << name;
  return "";
}

// 1-based number of the line holding the n-th (0-based) occurrence of `what`.
int line_of(const std::string& text, const std::string& what, int n = 0) {
  std::size_t at = text.find(what);
  for (int i = 0; i < n; ++i) at = text.find(what, at + 1);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

TEST(StlRead, GeneratedTorusHasNoCoincidentVertices) {
  // The precondition of the comparisons below: distinct generated vertices
  // stay distinct at float32 precision.
  const MeshData m = torus();
  std::set<std::array<float, 3>> pts;
  for (int v = 0; v < m.V.rows(); ++v)
    pts.insert({static_cast<float>(m.V(v, 0)), static_cast<float>(m.V(v, 1)), static_cast<float>(m.V(v, 2))});
  EXPECT_EQ(static_cast<Eigen::Index>(pts.size()), m.V.rows());
}

TEST(StlRead, AsciiAndBinaryReadAsTheGeneratedMesh) {
  const MeshData m = torus();
  const MeshData a = read_mesh_from_memory(ascii_stl(m), "t.stl");
  const MeshData b = read_mesh_from_memory(binary_stl(m), "t.stl");
  expect_generated(a, m);
  expect_generated(b, m);
  EXPECT_EQ(a.V, b.V);  // same welding order: first use by the faces
  EXPECT_EQ(a.F, b.F);
  EXPECT_FALSE(a.has_uv());
  // A closed torus once welded: Euler characteristic 0.
  std::set<std::pair<int, int>> edges;
  for (int f = 0; f < b.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int u = b.F(f, c), v = b.F(f, (c + 1) % 3);
      edges.insert({std::min(u, v), std::max(u, v)});
    }
  EXPECT_EQ(b.V.rows() - static_cast<Eigen::Index>(edges.size()) + b.F.rows(), 0);
  // ASCII facets carry their line for messages; binary ones none.
  ASSERT_EQ(a.face_line.size(), static_cast<std::size_t>(m.F.rows()));
  EXPECT_EQ(a.face_line[0], 2);
  EXPECT_EQ(a.face_line[1], 9);
}

TEST(StlRead, CrlfLineEnds) {
  const MeshData m = torus();
  expect_generated(read_mesh_from_memory(ascii_stl(m, "\r\n"), "t.stl"), m);
}

TEST(StlRead, UpperCaseKeywordsAndFreeLayout) {
  const std::string text =
      "SOLID x\nFACET NORMAL 0 0 1 OUTER LOOP VERTEX 0 0 0 VERTEX 1 0 0\n VERTEX 0 1 0 ENDLOOP ENDFACET\n"
      "facet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nENDSOLID\n";
  const MeshData r = read_mesh_from_memory(text, "q.stl");
  EXPECT_EQ(r.V.rows(), 4);
  ASSERT_EQ(r.F.rows(), 2);
  EXPECT_EQ(r.F(1, 0), r.F(0, 1));  // (1,0,0) welded
  EXPECT_EQ(r.F(1, 2), r.F(0, 2));  // (0,1,0) welded
}

TEST(StlRead, BinaryWhoseHeaderStartsWithSolid) {
  const MeshData m = torus();
  expect_generated(read_mesh_from_memory(binary_stl(m, "solid torus exported by a CAD tool"), "t.stl"), m);
  expect_generated(read_mesh_from_memory(binary_stl(m, "solid"), "t.stl"), m);
}

TEST(StlRead, SeveralSolidsInOneFileAreWeldedTogether) {
  const MeshData m = torus();
  const int nf = static_cast<int>(m.F.rows());
  const std::string text = ascii_solid(m, 0, nf / 3, "\n", "a") + ascii_solid(m, nf / 3, nf / 2, "\n", "") +
                           "\n\n" + ascii_solid(m, nf / 2, nf, "\n", "part c");
  expect_generated(read_mesh_from_memory(text, "t.stl"), m);
}

TEST(StlRead, Gzip) {
  const MeshData m = torus();
  expect_generated(read_mesh_from_memory(test::gzip(ascii_stl(m)), "t.stl.gz"), m);
  expect_generated(read_mesh_from_memory(test::gzip(binary_stl(m)), "t.stl.gz"), m);
}

TEST(StlRead, WeldingIsExact) {
  // Corners a float ulp apart stay apart; -0 and +0 are one point.
  const float one = 1.0f, next = std::nextafter(1.0f, 2.0f);
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex %.9g 0 0\nvertex 0 1 0\nendloop\n"
                "endfacet\nfacet normal 0 0 1\nouter loop\nvertex -0 0 0\nvertex %.9g 0 0\nvertex 0 1 -0\nendloop\n"
                "endfacet\nendsolid s\n",
                one, next);
  const MeshData r = read_mesh_from_memory(buf, "w.stl");
  EXPECT_EQ(r.V.rows(), 4);
  EXPECT_EQ(r.F(1, 0), r.F(0, 0));
  EXPECT_NE(r.F(1, 1), r.F(0, 1));
  EXPECT_EQ(r.F(1, 2), r.F(0, 2));
  EXPECT_EQ(r.V(r.F(1, 1), 0), static_cast<double>(next));
}

TEST(StlRead, MalformedAsciiNamesFileAndLine) {
  const MeshData m = torus();
  const std::string good = ascii_stl(m);
  // A misspelt keyword in the second facet.
  std::string bad = good;
  const std::size_t at = bad.find("endloop", bad.find("endloop") + 1);
  bad.replace(at, 7, "endlop");
  stl_input_error(bad, "x.stl", {"x.stl:" + std::to_string(line_of(good, "endloop", 1)) + ":", "'endlop'"});
  // A non-finite coordinate, and one beyond float32, in the first vertex.
  const std::size_t v0 = good.find("      vertex"), v0_end = good.find('\n', v0);
  std::string nan = good;
  nan.replace(v0, v0_end - v0, "      vertex 0 nan 0");
  stl_input_error(nan, "x.stl", {"x.stl:4:", "non-finite"});
  std::string big = good;
  big.replace(v0, v0_end - v0, "      vertex 1e39 0 0");
  stl_input_error(big, "x.stl", {"x.stl:4:", "float32"});
  // Cut inside a facet, and before 'endsolid'.
  const std::string cut = good.substr(0, good.find("outer loop", 300));
  stl_input_error(cut, "x.stl", {"x.stl:", "truncated"});
  stl_input_error(good.substr(0, good.rfind("endsolid")), "x.stl",
              {"x.stl:" + std::to_string(line_of(good, "endsolid")) + ":", "'endsolid'", "truncated"});
  // A fourth vertex, a missing 'normal', text before 'solid'.
  std::string four = good;
  four.insert(four.find("    endloop"), "      vertex 1 2 3\n");
  stl_input_error(four, "x.stl", {"x.stl:7:", "'endloop'"});
  std::string nonormal = good;
  nonormal.replace(nonormal.find("facet normal"), 12, "facet");
  stl_input_error(nonormal, "x.stl", {"x.stl:2:", "'normal'"});
  stl_input_error("hello " + good, "x.stl", {"not an STL file"});
  stl_input_error("solid a\nfacet normal 0 0 1\nouter loop\nvertex 1 2 x\n", "x.stl", {"x.stl:4:", "'x'"});
}

TEST(StlRead, MalformedBinaryNamesFacetAndOffset) {
  const MeshData m = torus();
  const std::string good = binary_stl(m);
  const int nf = static_cast<int>(m.F.rows());
  stl_input_error(good.substr(0, good.size() - 20), "x.stl",
              {"x.stl: facet " + std::to_string(nf - 1) + " (byte offset " + std::to_string(84 + 50 * (nf - 1)) + ")",
               "truncated"});
  stl_input_error(good + std::string(7, '\0'), "x.stl", {"x.stl:", "announces " + std::to_string(nf) + " facets"});
  std::string nan = good;
  const float q = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&nan[84 + 50 * 3 + 12 + 4], &q, 4);
  stl_input_error(nan, "x.stl", {"x.stl: facet 3 (byte offset 234)", "non-finite"});
  std::string inf = binary_stl(m, "solid with infinity");
  const float i = std::numeric_limits<float>::infinity();
  std::memcpy(&inf[84 + 50 * 5 + 12 + 24], &i, 4);
  stl_input_error(inf, "x.stl", {"x.stl: facet 5 (byte offset 334)", "non-finite"});
  // A count larger than the file, with and without a "solid" header.
  std::string more = good;
  more[80] = static_cast<char>(more[80] + 1);
  stl_input_error(more, "x.stl", {"facet " + std::to_string(nf), "truncated"});
  std::string solid_more = binary_stl(m, "solid x");
  solid_more[80] = static_cast<char>(solid_more[80] + 1);
  stl_input_error(solid_more, "x.stl", {"truncated", "not ASCII STL either"});
  stl_input_error(good.substr(0, 80) + std::string(4, '\0'), "x.stl", {"no faces"});
  stl_input_error(good.substr(0, 60), "x.stl", {"too short"});
}

TEST(StlRead, EmptyFilesAndLimits) {
  stl_input_error("", "x.stl", {"x.stl", "empty"});
  stl_input_error("solid a\nendsolid a\n", "x.stl", {"x.stl", "no"});
  const MeshData m = torus();
  ReadOptions few_faces;
  few_faces.max_faces = m.F.rows() - 1;
  stl_input_error(binary_stl(m), "x.stl", {"limit"}, few_faces);
  stl_input_error(ascii_stl(m), "x.stl", {"limit"}, few_faces);
  ReadOptions few_vertices;
  few_vertices.max_vertices = m.V.rows() - 1;
  stl_input_error(binary_stl(m), "x.stl", {"x.stl: facet", "limit"}, few_vertices);
  stl_input_error(ascii_stl(m), "x.stl", {"x.stl:", "limit"}, few_vertices);
  ReadOptions exact;
  exact.max_faces = m.F.rows();
  exact.max_vertices = m.V.rows();
  expect_generated(read_mesh_from_memory(binary_stl(m), "x.stl", exact), m);
}

TEST(StlRead, DamagedBytesGiveErrorsNotCrashes) {
  // A few thousand random byte edits of both kinds of file: each read either
  // succeeds or throws Error (the fuzzer goes much further, fuzz/fuzz_stl.cpp).
  GenerateOptions o;
  o.rings = 3;
  const MeshData m = generate_torus(o);
  const std::string files[] = {ascii_stl(m), binary_stl(m), binary_stl(m, "solid x")};
  std::mt19937 rng(7);
  int refused = 0, read = 0;
  for (const std::string& f : files) {
    for (int trial = 0; trial < 1500; ++trial) {
      std::string s = f;
      const int edits = 1 + static_cast<int>(rng() % 4);
      for (int e = 0; e < edits; ++e) {
        const std::size_t at = rng() % s.size();
        switch (rng() % 3) {
          case 0: s[at] = static_cast<char>(rng()); break;
          case 1: s.erase(at, 1 + rng() % 8); break;
          default: s.resize(at); break;
        }
        if (s.empty()) break;
      }
      try {
        read_mesh_from_memory(s, "d.stl");
        ++read;
      } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input);
        ++refused;
      }
    }
  }
  EXPECT_GT(refused, 0);
  EXPECT_GT(read, 0);
}

TEST(PlyHeader, FreeTextLinesAreSkipped) {
  // The header line Blender 2.47's exporter wrote, and obj_info.
  const std::string ply =
      "ply\nformat ascii 1.0\nCreated by Blender3D 247 - www.blender3d.com\nobj_info num_cols 2\n"
      "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const MeshData r = read_mesh_from_memory(ply, "b.ply");
  EXPECT_EQ(r.V.rows(), 3);
  ASSERT_EQ(r.F.rows(), 1);
  EXPECT_EQ(r.V(1, 0), 1.0);
}

TEST(PlyHeader, MalformedElementAndPropertyLinesAreStillRefused) {
  const std::string head = "ply\nformat ascii 1.0\nCreated by Blender3D 247 - www.blender3d.com\n";
  const std::string rest =
      "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  stl_input_error(head + "element vertex many\nproperty float x\n" + rest, "b.ply", {"b.ply:4:", "'vertex'"});
  stl_input_error(head + "element vertex 3\nproperty flot x\n" + rest, "b.ply", {"b.ply:5:", "unknown PLY type 'flot'"});
  stl_input_error(head + "element vertex 3\nproperty float\n" + rest, "b.ply", {"b.ply:5:", "without a name"});
  stl_input_error(head + "format binary_middle_endian 1.0\n", "b.ply", {"b.ply:4:", "unknown PLY format"});
  // A header that never ends is still reported as such.
  stl_input_error("ply\nformat ascii 1.0\nsome text\n", "b.ply", {"no 'end_header'"});
}

TEST(StlCli, AtlasOfAnStlFile) {
  test::TempDir dir;
  const MeshData m = torus();
  const std::string in = dir / "x.stl", out = dir / "y.obj";
  test::write_text(in, binary_stl(m, "solid torus"));
  const test::CliResult r = test::run_cli("atlas " + in + " -o " + out + " -q", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const MeshData back = read_mesh(out);
  ASSERT_TRUE(back.has_uv());
  EXPECT_EQ(back.F.rows(), m.F.rows());
  EXPECT_EQ(back.V.rows(), m.V.rows());  // the welded vertices, not 3 per face
  // A damaged file: exit code 2 and the file and facet in the message.
  test::write_text(in, binary_stl(m).substr(0, 84 + 50 * 10 + 7));
  const test::CliResult bad = test::run_cli("atlas " + in + " -o " + out + " -q", dir);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find(in + ": facet 10 (byte offset 584)"), std::string::npos) << bad.err;
}

}  // namespace
