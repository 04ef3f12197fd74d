// Tests of mesh reading and writing: every supported format variant, the
// error messages for malformed input, gzip, exact write/read round trips,
// atomic writes, and the shared test meshes.
#include <dirent.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "intrinsic/io.h"
#include "test_support.h"

using intrinsic::Error;
using intrinsic::ErrorKind;
using intrinsic::MeshData;
using intrinsic::ReadOptions;

namespace {

MeshData read_text(const std::string& text, const std::string& name, const ReadOptions& opt = {}) {
  return intrinsic::read_mesh_from_memory(text, name, opt);
}

// Reads `bytes` as `name` expecting an Input error whose message contains
// `fragment`; returns the message.
std::string input_error(const std::string& bytes, const std::string& name, const std::string& fragment,
                        const ReadOptions& opt = {}) {
  try {
    intrinsic::read_mesh_from_memory(bytes, name, opt);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos)
        << "message: " << e.what() << "\nexpected to contain: " << fragment;
    return e.what();
  }
  ADD_FAILURE() << "no error reading " << name << " (expected '" << fragment << "')";
  return "";
}

using intrinsic::test::gzip;

class TempDir {
 public:
  TempDir() {
    std::string t = ::testing::TempDir() + "intrinsic_io_XXXXXX";
    std::vector<char> buf(t.begin(), t.end());
    buf.push_back('\0');
    char* d = mkdtemp(buf.data());
    if (!d) throw std::runtime_error("mkdtemp failed");
    path_ = d;
  }
  ~TempDir() {
    for (const auto& f : files()) ::unlink((path_ + "/" + f).c_str());
    ::rmdir(path_.c_str());
  }
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  std::set<std::string> files() const {
    std::set<std::string> out;
    if (DIR* d = opendir(path_.c_str())) {
      while (dirent* e = readdir(d)) {
        std::string n = e->d_name;
        if (n != "." && n != "..") out.insert(n);
      }
      closedir(d);
    }
    return out;
  }

 private:
  std::string path_;
};

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string read_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

// ---------- binary PLY construction ----------

enum class T { i8, u8, i16, u16, i32, u32, f32, f64 };
const char* type_name(T t) {
  switch (t) {
    case T::i8: return "char";
    case T::u8: return "uchar";
    case T::i16: return "short";
    case T::u16: return "ushort";
    case T::i32: return "int";
    case T::u32: return "uint";
    case T::f32: return "float";
    case T::f64: return "double";
  }
  return "?";
}

// Appends a value of type t in the requested byte order.
void put(std::string& out, T t, double v, bool big) {
  unsigned char b[8];
  std::size_t n = 0;
  auto store = [&](auto x) {
    n = sizeof x;
    std::memcpy(b, &x, n);
  };
  switch (t) {
    case T::i8: store(static_cast<std::int8_t>(v)); break;
    case T::u8: store(static_cast<std::uint8_t>(v)); break;
    case T::i16: store(static_cast<std::int16_t>(v)); break;
    case T::u16: store(static_cast<std::uint16_t>(v)); break;
    case T::i32: store(static_cast<std::int32_t>(v)); break;
    case T::u32: store(static_cast<std::uint32_t>(v)); break;
    case T::f32: store(static_cast<float>(v)); break;
    case T::f64: store(v); break;
  }
  if (big) std::reverse(b, b + n);  // the test machine is little-endian (checked below)
  out.append(reinterpret_cast<const char*>(b), n);
}

bool host_little() {
  const std::uint16_t one = 1;
  unsigned char c;
  std::memcpy(&c, &one, 1);
  return c == 1;
}

// A unit square (4 vertices) split into a quad and a triangle: faces {0,1,2,3}
// and {0,2,3}... as polygons, with extra vertex properties, an extra face
// property and an extra "edge" element holding a list.
std::string square_ply(bool big, T coord, T count, T index, bool with_uv = false) {
  std::string h = "ply\n";
  h += big ? "format binary_big_endian 1.0\n" : "format binary_little_endian 1.0\n";
  h += "comment made by the test\nobj_info nothing\n";
  h += "element vertex 4\n";
  h += "property uchar red\n";
  h += std::string("property ") + type_name(coord) + " z\n";
  h += std::string("property ") + type_name(coord) + " x\n";
  h += "property list uchar int vertex_extra\n";
  h += std::string("property ") + type_name(coord) + " y\n";
  if (with_uv) h += "property float u\nproperty double v\n";
  h += "property short weight\n";
  h += "element face 2\n";
  h += "property int flags\n";
  h += std::string("property list ") + type_name(count) + " " + type_name(index) + " vertex_indices\n";
  h += "property float quality\n";
  h += "element edge 2\nproperty list uchar int pair\nproperty uchar color\n";
  h += "end_header\n";
  const double xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 4; ++i) {
    put(h, T::u8, 200, big);
    put(h, coord, 0.5 * i, big);
    put(h, coord, xy[i][0], big);
    put(h, T::u8, 2, big);
    put(h, T::i32, 7, big);
    put(h, T::i32, 8, big);
    put(h, coord, xy[i][1], big);
    if (with_uv) {
      put(h, T::f32, 0.25 * i, big);
      put(h, T::f64, 1 - 0.25 * i, big);
    }
    put(h, T::i16, -3, big);
  }
  put(h, T::i32, 99, big);
  put(h, count, 4, big);
  for (int v : {0, 1, 2, 3}) put(h, index, v, big);
  put(h, T::f32, 0.5, big);
  put(h, T::i32, 99, big);
  put(h, count, 3, big);
  for (int v : {3, 1, 0}) put(h, index, v, big);
  put(h, T::f32, 0.5, big);
  for (int e = 0; e < 2; ++e) {
    put(h, T::u8, 3, big);
    for (int k = 0; k < 3; ++k) put(h, T::i32, k, big);
    put(h, T::u8, 1, big);
  }
  return h;
}

void expect_square(const MeshData& m) {
  ASSERT_EQ(m.V.rows(), 4);
  ASSERT_EQ(m.F.rows(), 3);
  const double xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(m.V(i, 0), xy[i][0]);
    EXPECT_EQ(m.V(i, 1), xy[i][1]);
    EXPECT_EQ(m.V(i, 2), 0.5 * i);
  }
  EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(m.F.row(2), Eigen::RowVector3i(3, 1, 0));
}

const char* kCube = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";

}  // namespace

// ---------------------------------------------------------------- OBJ

TEST(IoObj, PlainTriangles) {
  MeshData m = read_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0.5\nf 1 2 3\nf 2 4 3\n", "t.obj");
  ASSERT_EQ(m.V.rows(), 4);
  ASSERT_EQ(m.F.rows(), 2);
  EXPECT_EQ(m.V(3, 2), 0.5);
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(1, 3, 2));
  EXPECT_FALSE(m.has_uv());
  EXPECT_EQ(m.TC.rows(), 0);
  EXPECT_EQ(m.FTC.rows(), 0);
  EXPECT_EQ(m.face_line, (std::vector<int>{5, 6}));
  EXPECT_EQ(m.path, "t.obj");
}

TEST(IoObj, SlashForms) {
  const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1 0\nvn 0 0 1\n";
  MeshData a = read_text(head + "f 1/3 2/2 3/1\n", "a.obj");
  ASSERT_TRUE(a.has_uv());
  EXPECT_EQ(a.FTC.row(0), Eigen::RowVector3i(2, 1, 0));
  EXPECT_EQ(a.TC(1, 0), 1.0);
  MeshData b = read_text(head + "f 1/1/1 2/2/1 3/3/1\n", "b.obj");
  ASSERT_TRUE(b.has_uv());
  EXPECT_EQ(b.FTC.row(0), Eigen::RowVector3i(0, 1, 2));
  MeshData c = read_text(head + "f 1//1 2//1 3//1\n", "c.obj");
  EXPECT_EQ(c.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_FALSE(c.has_uv());
  EXPECT_EQ(c.TC.rows(), 0);
}

TEST(IoObj, NegativeIndices) {
  MeshData m = read_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf -3/-3 -2/-2 -1/-1\n"
                         "v 1 1 0\nvt 1 1\nf -3/-3 -1/-1 -2/-2\n",
                         "neg.obj");
  ASSERT_EQ(m.F.rows(), 2);
  EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(1, 3, 2));
  EXPECT_EQ(m.FTC.row(1), Eigen::RowVector3i(1, 3, 2));
}

TEST(IoObj, PolygonsAreFanTriangulated) {
  MeshData m = read_text(std::string(kCube) + "# a quad and a pentagon\nf 1 2 3 4\n\nf 5 6 7 8 1\n", "p.obj");
  ASSERT_EQ(m.F.rows(), 5);
  EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(m.F.row(2), Eigen::RowVector3i(4, 5, 6));
  EXPECT_EQ(m.F.row(4), Eigen::RowVector3i(4, 7, 0));
  EXPECT_EQ(m.face_line, (std::vector<int>{10, 10, 12, 12, 12}));
}

TEST(IoObj, CrlfCommentsAndIgnoredStatements) {
  const std::string text =
      "# header comment\r\n"
      "mtllib scene.mtl\r\n"
      "o thing\r\n"
      "g group\r\n"
      "\r\n"
      "v 0 0 0 1.0 0.5 0.25 0.125   \r\n"  // w / colour values after x y z
      "v 1e0 +0 -0.0\r\n"
      "   v\t0.0 1.0 0.0 # trailing comment\r\n"
      "vn 0 0 1\r\n"
      "vp 0.5\r\n"
      "vt 0.5 0.5 0\r\n"
      "s off\r\n"
      "usemtl red\r\n"
      "l 1 2\r\n"
      "f 1 2 3   \r\n"
      "f 1 2 3";  // no final newline
  MeshData m = read_text(text, "crlf.obj");
  ASSERT_EQ(m.V.rows(), 3);
  ASSERT_EQ(m.F.rows(), 2);
  EXPECT_EQ(m.V(1, 0), 1.0);
  EXPECT_EQ(m.V(2, 1), 1.0);
  EXPECT_EQ(m.face_line, (std::vector<int>{15, 16}));
  EXPECT_FALSE(m.has_uv());  // vt present but faces do not use it
}

TEST(IoObj, UvOnlyWhenEveryFaceHasIt) {
  MeshData m = read_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\nf 1 3 2\n", "mix.obj");
  EXPECT_EQ(m.F.rows(), 2);
  EXPECT_FALSE(m.has_uv());
  EXPECT_EQ(m.TC.rows(), 0);
  EXPECT_EQ(m.FTC.rows(), 0);
}

TEST(IoObj, RepeatedIndexIsReadAsIs) {
  MeshData m = read_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 2\n", "rep.obj");
  EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(0, 0, 1));
}

TEST(IoObj, MalformedInputNamesFileAndLine) {
  // The example from the specification: line 17, 8 vertices.
  std::string lines = std::string(kCube);  // 8 lines
  for (int i = 0; i < 8; ++i) lines += "# filler\n";  // lines 9-16
  lines += "f 1 2 9\n";                                 // line 17
  input_error(lines, "mesh.obj", "mesh.obj:17: face index 9 out of range (file has 8 vertices)");

  input_error("v 0 0 0\nv 1 0 0\nv 1 x 0\nf 1 2 3\n", "mesh.obj", "mesh.obj:3: expected a number after 'v'");
  input_error("v 0 0 0\nv 1 0 0\nv 1\nf 1 2 3\n", "mesh.obj", "mesh.obj:3: expected a number after 'v'");
  input_error("v 0 0 0\nv 1 0 0\nv 1 2.5e 3\n", "mesh.obj", "mesh.obj:3: expected a number");
  input_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "z.obj", "z.obj:4: face vertex index 0 is invalid");
  input_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", "n.obj", "n.obj:4: face vertex index -4 out of range");
  input_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "few.obj", "few.obj:4: face has 2 vertices");
  input_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf\n", "few.obj", "few.obj:4: face has 0 vertices");
  input_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", "g.obj", "g.obj:4: expected a vertex index in face");
  input_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3x\n", "g.obj", "g.obj:4: unexpected");
  input_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999\n", "big.obj", "big.obj:4: face vertex index 99999999999 is too large");
  input_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n", "big.obj", "big.obj:4:");
  input_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/3\n", "t.obj",
              "t.obj:5: face texture index 2 out of range (file has 1 texture coordinates)");
  input_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 0\nv 0 0 0\nv 1 inf 0\nf 1 2 3\n", "nf.obj",
              "nf.obj:6: vertex 6 has a non-finite coordinate");
  input_error("v 0 0 0\nv nan 0 0\n", "nf.obj", "nf.obj:2: vertex 2 has a non-finite coordinate");
  input_error("v 0 0 0\nv 1e999 0 0\n", "nf.obj", "nf.obj:2: vertex 2 has a non-finite coordinate");
  input_error("", "empty.obj", "empty.obj: no vertices");
  input_error("# nothing\n\n", "empty.obj", "empty.obj: no vertices");
  input_error("v 0 0 0\nv 1 0 0\nv 0 1 0\n", "nf.obj", "nf.obj: no faces");
  input_error(std::string("v 0 0 0\nv 1 0 0\0\0\0\nv 0 1 0\nf 1 2 3\n", 32), "nul.obj", "nul.obj:2:");
  ReadOptions small;
  small.max_vertices = 2;
  input_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "lim.obj", "lim.obj:3: more than 2 vertices", small);
  small = {};
  small.max_faces = 1;
  input_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 4\n", "lim.obj", "lim.obj:5: more than 1 faces", small);
}

// ---------------------------------------------------------------- OFF

TEST(IoOff, PlainWithCommentsAndPolygons) {
  const std::string text =
      "OFF\n# comment after the keyword\n\n4 2 0\n"
      "0 0 0\n1 0 0\n# a comment between vertices\n1 1 0\n0 1 0\n"
      "4 0 1 2 3\n3 3 1 0\n";
  MeshData m = read_text(text, "sq.off");
  ASSERT_EQ(m.V.rows(), 4);
  ASSERT_EQ(m.F.rows(), 3);
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(m.F.row(2), Eigen::RowVector3i(3, 1, 0));
  EXPECT_EQ(m.face_line, (std::vector<int>{10, 10, 11}));
}

TEST(IoOff, VariantsAndCrlf) {
  // COFF (colours), NOFF (normals), STOFF (texture), counts on the keyword
  // line, per-face colours, CRLF.
  const char* cases[] = {
      "COFF\r\n3 1 3\r\n0 0 0 255 0 0 255\r\n1 0 0 0 255 0 255\r\n0 1 0 0 0 255 255\r\n3 0 1 2 255 255 255\r\n",
      "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n",
      "STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2 0.5 0.5 0.5\n",
      "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
      "OFF 3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2",
      "  # leading comment\nCNOFF\n3 1 0\n0 0 0 1 1 1 0 0 1\n1 0 0 1 1 1 0 0 1\n0 1 0 1 1 1 0 0 1\n3 0 1 2\n",
  };
  for (const char* c : cases) {
    MeshData m = read_text(c, "v.off");
    ASSERT_EQ(m.V.rows(), 3) << c;
    ASSERT_EQ(m.F.rows(), 1) << c;
    EXPECT_EQ(m.V(1, 0), 1.0);
    EXPECT_EQ(m.V(2, 1), 1.0);
    EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(0, 1, 2));
  }
}

TEST(IoOff, MalformedInput) {
  input_error("", "e.off", "e.off: no vertices");
  input_error("PLY\n", "h.off", "h.off:1: expected the OFF header");
  input_error("4OFF\n", "h.off", "h.off:1: unsupported OFF variant");
  input_error("OFF BINARY\n3 1 0\n", "h.off", "h.off:1: binary OFF is not supported");
  input_error("OFF\nthree 1 0\n", "h.off", "h.off:2: expected the number of vertices");
  input_error("OFF\n3 -1 0\n", "h.off", "h.off:2: negative number of faces");
  input_error("OFF\n4000000000 1 0\n0 0 0\n", "big.off", "big.off:2: header announces 4000000000 vertices");
  input_error("OFF\n1000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "big.off", "big.off:2: header announces 1000 vertices");
  input_error("OFF\n3 1 0\n0 0 0\n1 0 0\n# padding padding padding padding\n", "t.off",
              "t.off:6: file ends after 2 of 3 vertices");
  input_error("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "t.off", "t.off:7: file ends after 1 of 2 faces");
  input_error("OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", "c.off", "c.off:4: expected 3 coordinates for vertex 1");
  input_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n", "c.off", "c.off:5: vertex 2 has a non-finite coordinate");
  input_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "i.off", "i.off:6: face index 3 out of range (file has 3 vertices)");
  input_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n", "i.off", "i.off:6: face index -1 out of range");
  input_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "i.off", "i.off:6: face 0 has 2 vertices");
  input_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", "i.off", "i.off:6: face 0 announces 4 vertices but lists 3");
  input_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 99999999999999999999\n", "i.off", "i.off:6: face index");
  input_error("OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", "nf.off", "nf.off: no faces");
  ReadOptions small;
  small.max_vertices = 2;
  input_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "l.off", "l.off:2: header announces 3 vertices, more than the limit of 2", small);
}

// ---------------------------------------------------------------- PLY

TEST(IoPly, AsciiWithTextureCoordinates) {
  for (const char* names : {"u v", "s t", "texture_u texture_v"}) {
    std::string a(names), b;
    b = a.substr(a.find(' ') + 1);
    a = a.substr(0, a.find(' '));
    std::string text = "ply\r\nformat ascii 1.0\r\ncomment hi\r\nelement vertex 4\r\n"
                       "property float x\r\nproperty float y\r\nproperty float z\r\n"
                       "property float " + a + "\r\nproperty float " + b + "\r\nproperty uchar red\r\n"
                       "element face 1\r\nproperty list uchar uint vertex_index\r\nend_header\r\n"
                       "0 0 0 0 0 9\r\n1 0 0 1 0 9\r\n1 1 0 1 1 9\r\n0 1 0 0 1 9\r\n4 0 1 2 3\r\n";
    MeshData m = read_text(text, "a.ply");
    ASSERT_EQ(m.V.rows(), 4);
    ASSERT_EQ(m.F.rows(), 2);
    ASSERT_TRUE(m.has_uv()) << names;
    EXPECT_EQ(m.FTC, m.F);
    EXPECT_EQ(m.TC(2, 0), 1.0);
    EXPECT_EQ(m.TC(2, 1), 1.0);
    EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(0, 2, 3));
    EXPECT_EQ(m.face_line, (std::vector<int>{18, 18}));
  }
}

TEST(IoPly, AsciiExtraElementsAndNoUv) {
  std::string text = "ply\nformat ascii 1.0\nelement material 2\nproperty list uchar float colors\n"
                     "element vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
                     "element face 1\nproperty uchar flag\nproperty list uchar int vertex_indices\n"
                     "property list uchar int other\nelement edge 1\nproperty int a\nproperty int b\nend_header\n"
                     "3 1 2 3\n0\n"
                     "0 0 0\n1 0 0\n0 1 0.25\n"
                     "7 3 0 1 2 2 5 5\n"
                     "0 1\n";
  MeshData m = read_text(text, "x.ply");
  ASSERT_EQ(m.V.rows(), 3);
  ASSERT_EQ(m.F.rows(), 1);
  EXPECT_EQ(m.V(2, 2), 0.25);
  EXPECT_FALSE(m.has_uv());
}

// Scanners' PLY files (igea.ply) store faces as triangle strips: -1 ends a
// strip, every second triangle is reversed to keep the strip's orientation,
// and triangles with a repeated vertex (strip joins) are dropped.
TEST(IoPly, TriangleStrips) {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
                           "property float z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n"
                           "0 0 0\n0 1 0\n1 0 0\n1 1 0\n2 0 0\n2 1 0\n";
  MeshData m = read_text(head + "11 0 1 2 3 4 5 -1 0 2 2 4\n", "s.ply");
  ASSERT_EQ(m.F.rows(), 4);
  EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(2, 1, 3));
  EXPECT_EQ(m.F.row(2), Eigen::RowVector3i(2, 3, 4));
  EXPECT_EQ(m.F.row(3), Eigen::RowVector3i(4, 3, 5));
  // One orientation throughout: every triangle has the same signed area sign.
  for (int f = 0; f < 4; ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    EXPECT_LT((b - a).cross(c - a).z(), 0) << f;
  }
  EXPECT_NE(input_error(head + "3 0 1 9\n", "s.ply", "s.ply").find("strip index 9 out of range"), std::string::npos);
}

TEST(IoPly, BinaryBothEndiannessAndAllIndexTypes) {
  ASSERT_TRUE(host_little());
  const T counts[] = {T::u8, T::i8, T::u16, T::i16, T::i32, T::u32};
  const T indices[] = {T::i32, T::u32, T::u16, T::i16, T::u8, T::i8, T::f32, T::f64};
  int n = 0;
  for (bool big : {false, true})
    for (T coord : {T::f32, T::f64})
      for (T c : counts)
        for (T i : indices) {
          SCOPED_TRACE(std::string(big ? "BE " : "LE ") + type_name(coord) + " " + type_name(c) + " " + type_name(i));
          MeshData m = read_text(square_ply(big, coord, c, i), "sq.ply");
          expect_square(m);
          EXPECT_FALSE(m.has_uv());
          EXPECT_EQ(m.face_line, (std::vector<int>{0, 0, 0}));
          ++n;
        }
  EXPECT_EQ(n, 2 * 2 * 6 * 8);
  for (bool big : {false, true}) {
    MeshData m = read_text(square_ply(big, T::f64, T::u8, T::i32, true), "uv.ply");
    expect_square(m);
    ASSERT_TRUE(m.has_uv());
    EXPECT_EQ(m.TC(1, 0), 0.25);
    EXPECT_EQ(m.TC(1, 1), 0.75);
    EXPECT_EQ(m.FTC, m.F);
  }
}

TEST(IoPly, MalformedInput) {
  const std::string good = square_ply(false, T::f32, T::u8, T::i32);
  const std::size_t body = good.find("end_header\n") + 11;
  // Truncated anywhere in the body: an error naming an element and offset.
  for (std::size_t cut : {body, body + 1, body + 30, good.size() - 40, good.size() - 1}) {
    std::string msg = input_error(good.substr(0, cut), "cut.ply", "cut.ply: ");
    EXPECT_TRUE(msg.find("byte offset") != std::string::npos || msg.find("header announces") != std::string::npos)
        << msg;
  }
  input_error(good.substr(0, good.size() - 1), "cut.ply", "cut.ply: edge 1 (byte offset");

  std::string huge = good;
  huge.replace(huge.find("element vertex 4"), 16, "element vertex 4000000000");
  std::string msg = input_error(huge, "bunny.ply", "bunny.ply: header announces 4000000000 vertices, but the file holds at most ");
  EXPECT_NE(msg.find("bytes of vertex data"), std::string::npos);

  std::string many_faces = good;
  many_faces.replace(many_faces.find("element face 2"), 14, "element face 2000");
  input_error(many_faces, "f.ply", "f.ply: header announces 2000 faces, but the file holds at most");

  ReadOptions small;
  small.max_vertices = 3;
  input_error(good, "l.ply", "l.ply:5: header announces 4 vertices, more than the limit of 3", small);

  std::string bad_format = good;
  bad_format.replace(bad_format.find("binary_little_endian"), 20, "binary_middle_endian");
  input_error(bad_format, "fmt.ply", "fmt.ply:2: unknown PLY format 'binary_middle_endian'");

  input_error("", "e.ply", "e.ply:1: not a PLY file");
  input_error("ply\nformat ascii 1.0\nelement vertex 3\n", "h.ply", "h.ply:4: the header has no 'end_header' line");
  input_error("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nelement face 1\n"
              "property list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n3 0 1 2\n",
              "noz.ply", "noz.ply:3: the vertex element has no 'z' property");
  input_error("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
              "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
              "r.ply", "r.ply:13: face 0: face index 3 out of range (file has 3 vertices)");
  input_error("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
              "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
              "r.ply", "r.ply:13: face 0: face has 2 vertices");
  input_error("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
              "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n",
              "r.ply", "r.ply:11: vertex 1: non-finite coordinate");
  input_error("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
              "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n",
              "t.ply", "t.ply:14: face 0: file ends inside the element");
  input_error("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
              "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2.5\n",
              "t.ply", "t.ply:13: face 0: vertex index is not an integer");
  input_error("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
              "element face 1\nproperty list uchar int other\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
              "t.ply", "t.ply:7: the face element has no 'vertex_indices' list");
  input_error("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
              "end_header\n0 0 0\n1 0 0\n0 1 0\n",
              "nf.ply", "nf.ply: no faces");
  input_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n", "ty.ply",
              "ty.ply:4: unknown PLY type 'quad'");
  input_error("ply\nformat ascii 1.0\nproperty float x\nend_header\n", "p.ply", "p.ply:3: property before any element");
  input_error("ply\nformat ascii 1.0\nelement vertex -3\nend_header\n", "p.ply", "p.ply:3: expected the number of 'vertex' elements");

  // A huge list length in an extra element is refused before allocating.
  std::string h = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                  "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n";
  for (int i = 0; i < 9; ++i) put(h, T::f32, i % 2, false);
  put(h, T::u32, 4000000000.0, false);
  put(h, T::i32, 0, false);
  input_error(h, "list.ply", "list.ply: face 0 (byte offset");
}

// ---------------------------------------------------------------- gzip

TEST(IoGzip, RoundTripAndDetectionByMagic) {
  const std::string text = std::string(kCube) + "f 1 2 3 4\nf 5 6 7\n";
  MeshData plain = read_text(text, "c.obj");
  const std::string z = gzip(text);
  MeshData a = read_text(z, "c.obj.gz");
  MeshData b = read_text(z, "c.obj");  // compressed but not named so
  EXPECT_EQ(a.V, plain.V);
  EXPECT_EQ(a.F, plain.F);
  EXPECT_EQ(b.F, plain.F);
  EXPECT_EQ(a.face_line, plain.face_line);
  // Two concatenated members, as `cat a.gz b.gz` makes.
  const std::string half = std::string(kCube);
  MeshData c = read_text(gzip(half) + gzip("f 1 2 3 4\nf 5 6 7\n"), "two.obj.gz");
  EXPECT_EQ(c.F, plain.F);

  TempDir dir;
  write_bytes(dir.file("cube.OFF.GZ"), gzip("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_EQ(intrinsic::read_mesh(dir.file("cube.OFF.GZ")).F.rows(), 1);
}

TEST(IoGzip, CorruptTruncatedAndBombs) {
  const std::string text = std::string(kCube) + "f 1 2 3 4\n";
  const std::string z = gzip(text);
  input_error(z.substr(0, z.size() / 2), "t.obj.gz", "t.obj.gz: truncated gzip data");
  std::string bad = z;
  bad[12] = static_cast<char>(bad[12] ^ 0x55);
  bad[13] = static_cast<char>(bad[13] ^ 0xff);
  input_error(bad, "b.obj.gz", "b.obj.gz: ");
  input_error(std::string("\x1f\x8b", 2), "m.obj.gz", "m.obj.gz: ");
  // Small limits give a small inflate cap: a highly compressible stream is refused.
  ReadOptions small;
  small.max_vertices = 10;
  small.max_faces = 10;
  const std::string bomb = gzip(std::string(8u << 20, ' '));
  EXPECT_LT(bomb.size(), 20000u);
  input_error(bomb, "bomb.obj.gz", "bomb.obj.gz: decompressed data exceeds the limit", small);
}

// ---------------------------------------------------------------- writing

namespace {

struct Mesh {
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;
  Eigen::MatrixX2d UV;
};

// Awkward doubles: shortest round-trip printing must reproduce each bit.
Mesh random_mesh(int nv, int nf, bool uv, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Mesh m;
  m.V.resize(nv, 3);
  for (int i = 0; i < nv; ++i)
    for (int k = 0; k < 3; ++k) m.V(i, k) = u(rng) * std::pow(10.0, static_cast<int>(rng() % 40) - 20);
  m.V(0, 0) = 0.1;
  m.V(0, 1) = -0.0;
  m.V(0, 2) = std::numeric_limits<double>::denorm_min();
  m.V(1, 0) = std::numeric_limits<double>::max();
  m.V(1, 1) = std::numeric_limits<double>::lowest();
  m.V(1, 2) = 1e-310;
  m.F.resize(nf, 3);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) m.F(f, k) = static_cast<int>(rng() % static_cast<unsigned>(nv));
  if (uv) {
    m.UV.resize(nv, 2);
    for (int i = 0; i < nv; ++i) m.UV(i, 0) = u(rng), m.UV(i, 1) = u(rng) * 1e-7;
  }
  return m;
}

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  return std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

}  // namespace

TEST(IoWrite, RoundTripIsExact) {
  TempDir dir;
  // 500 vertices: one chunk, formatted in place; 100k: many chunks
  // formatted on worker threads and streamed in order.
  for (auto [uv, rows] : {std::pair{false, 500}, std::pair{true, 500}, std::pair{true, 100000}}) {
    const Mesh m = random_mesh(rows, 2 * rows, uv, uv ? 7 : 11);
    struct Case {
      const char* name;
      bool binary;
    } cases[] = {{"out.obj", false}, {"out.ply", false}, {"bin.ply", true}};
    for (const Case& c : cases) {
      SCOPED_TRACE(std::string(c.name) + (uv ? " with uv, " : " without uv, ") + std::to_string(rows));
      intrinsic::WriteOptions wo;
      wo.binary = c.binary;
      intrinsic::write_mesh(dir.file(c.name), m.V, m.F, m.UV, wo);
      MeshData r = intrinsic::read_mesh(dir.file(c.name));
      EXPECT_TRUE(same_bits(r.V, m.V));
      EXPECT_EQ(r.F, m.F);
      EXPECT_EQ(r.has_uv(), uv);
      if (uv) {
        EXPECT_TRUE(same_bits(r.TC, m.UV));
        EXPECT_EQ(r.FTC, m.F);
      }
    }
  }
  EXPECT_EQ(dir.files(), (std::set<std::string>{"out.obj", "out.ply", "bin.ply"}));
}

TEST(IoWrite, FormatOfWrittenFiles) {
  TempDir dir;
  Eigen::MatrixX3d V(3, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 0.5, 0;
  Eigen::MatrixX3i F(1, 3);
  F << 0, 1, 2;
  Eigen::MatrixX2d UV(3, 2);
  UV << 0, 0, 1, 0, 0, 1;
  intrinsic::write_mesh(dir.file("a.obj"), V, F, UV);
  const std::string obj = read_bytes(dir.file("a.obj"));
  EXPECT_NE(obj.find("v 0 0.5 0\n"), std::string::npos);
  EXPECT_NE(obj.find("vt 1 0\n"), std::string::npos);
  EXPECT_NE(obj.find("f 1/1 2/2 3/3\n"), std::string::npos);
  intrinsic::write_mesh(dir.file("b.obj"), V, F, Eigen::MatrixX2d());
  EXPECT_NE(read_bytes(dir.file("b.obj")).find("f 1 2 3\n"), std::string::npos);
  intrinsic::write_mesh(dir.file("c.ply"), V, F, UV, {true});
  const std::string ply = read_bytes(dir.file("c.ply"));
  EXPECT_EQ(ply.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  EXPECT_NE(ply.find("property double u\nproperty double v\n"), std::string::npos);
  EXPECT_NE(ply.find("property list uchar int vertex_indices\nend_header\n"), std::string::npos);
  const std::size_t body = ply.find("end_header\n") + 11;
  EXPECT_EQ(ply.size() - body, 3u * 5 * 8 + 1 + 3 * 4);
}

TEST(IoWrite, ErrorsLeaveNoFileBehind) {
  TempDir dir;
  Eigen::MatrixX3d V(3, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  Eigen::MatrixX3i F(1, 3);
  F << 0, 1, 2;
  try {
    intrinsic::write_mesh(dir.file("m.xyz"), V, F, Eigen::MatrixX2d());
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("unknown output format '.xyz' (use .obj, .ply or .glb)"), std::string::npos);
  }
  try {
    intrinsic::write_mesh(dir.file("missing/m.obj"), V, F, Eigen::MatrixX2d());
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Output);
    EXPECT_NE(std::string(e.what()).find(dir.file("missing/m.obj")), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("No such file or directory"), std::string::npos) << e.what();
  }
  // Renaming onto a directory fails after the temporary file was written:
  // the temporary file must be gone.
  ASSERT_EQ(::mkdir(dir.file("taken.obj").c_str(), 0755), 0);
  try {
    intrinsic::write_mesh(dir.file("taken.obj"), V, F, Eigen::MatrixX2d());
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Output);
    EXPECT_NE(std::string(e.what()).find("taken.obj"), std::string::npos);
  }
  ::rmdir(dir.file("taken.obj").c_str());
  Eigen::MatrixX3d bad = V;
  bad(1, 1) = std::nan("");
  intrinsic::test::expect_error([&] { intrinsic::write_mesh(dir.file("nan.obj"), bad, F, Eigen::MatrixX2d()); },
                                ErrorKind::Output, "the vertex positions are not all finite");
  Eigen::MatrixX3i badF = F;
  badF(0, 2) = 3;
  intrinsic::test::expect_error([&] { intrinsic::write_mesh(dir.file("f.obj"), V, badF, Eigen::MatrixX2d()); },
                                ErrorKind::Output, "face 0 has vertex index 3");
  intrinsic::test::expect_error([&] { intrinsic::write_mesh(dir.file("uv.obj"), V, F, Eigen::MatrixX2d(2, 2)); },
                                ErrorKind::Output, "2 texture coordinates for");
  EXPECT_TRUE(dir.files().empty());

  // Success replaces an existing file and leaves only that file.
  write_bytes(dir.file("keep.obj"), "old");
  intrinsic::write_file_atomically(dir.file("keep.obj"), "new contents");
  EXPECT_EQ(read_bytes(dir.file("keep.obj")), "new contents");
  EXPECT_EQ(dir.files(), (std::set<std::string>{"keep.obj"}));
  struct stat st {};
  ASSERT_EQ(::stat(dir.file("keep.obj").c_str(), &st), 0);
  EXPECT_NE(st.st_mode & S_IRUSR, 0u);
  EXPECT_NE(st.st_mode & S_IWUSR, 0u);
}

// ---------------------------------------------------------------- files

TEST(IoRead, MissingFileAndUnknownFormat) {
  try {
    intrinsic::read_mesh("/nonexistent/dir/mesh.obj");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_NE(std::string(e.what()).find("cannot open /nonexistent/dir/mesh.obj"), std::string::npos) << e.what();
  }
  TempDir dir;
  try {
    intrinsic::read_mesh(dir.path() + "/");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
  }
  // (.3ds is read through assimp now: test_io_assimp.cpp.)
  intrinsic::test::expect_error([] { intrinsic::read_mesh_from_memory("garbage", "m.xyz"); }, ErrorKind::Usage,
                                "unknown input format '.xyz' for m.xyz");
}

// Random damage to valid files of every format must give an Error, never a
// crash or another exception type.
TEST(IoRead, DamagedInputOnlyThrowsError) {
  const std::string z = std::string(kCube) + "vt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3 4/1\nf -1/-1 -2/-2 -3/-3\n";
  std::vector<std::pair<std::string, std::string>> seeds = {
      {z, "a.obj"},
      {"OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n3 3 1 0 255 0 0\n", "a.off"},
      {square_ply(false, T::f32, T::u8, T::i32, true), "a.ply"},
      {square_ply(true, T::f64, T::u16, T::u32), "b.ply"},
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
       "c.ply"},
      {gzip(z), "g.obj.gz"},
  };
  std::mt19937 rng(1234);
  int errors = 0, reads = 0;
  for (const auto& [bytes, name] : seeds) {
    for (int trial = 0; trial < 400; ++trial) {
      std::string b = bytes;
      const int edits = 1 + static_cast<int>(rng() % 4);
      for (int e = 0; e < edits && !b.empty(); ++e) {
        const std::size_t at = rng() % b.size();
        switch (rng() % 4) {
          case 0: b[at] = static_cast<char>(rng()); break;
          case 1: b.resize(at); break;
          case 2: b.insert(at, 1, "0123456789 \n-/.e#\xff"[rng() % 18]); break;
          case 3: b.erase(at, 1 + rng() % 8); break;
        }
      }
      try {
        MeshData m = intrinsic::read_mesh_from_memory(b, name);
        ++reads;
        EXPECT_GT(m.V.rows(), 0);
        EXPECT_GT(m.F.rows(), 0);
        EXPECT_EQ(m.face_line.size(), static_cast<std::size_t>(m.F.rows()));
        EXPECT_GE(m.F.minCoeff(), 0);
        EXPECT_LT(m.F.maxCoeff(), m.V.rows());
        if (m.has_uv()) {
          EXPECT_GE(m.FTC.minCoeff(), 0);
          EXPECT_LT(m.FTC.maxCoeff(), m.TC.rows());
        }
        EXPECT_TRUE(m.V.allFinite());
      } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
        ++errors;
      }
    }
  }
  EXPECT_GT(errors, 100);
  EXPECT_GT(reads, 10);
}

// The shared meshes and their counts from shared/meshes/README.md. Where
// ../shared/meshes is present, a missing file is a failure: these are the
// project's reference inputs.
TEST(IoCorpus, CountsMatchTheReadme) {
  REQUIRE_SHARED_MESHES();
  struct Expect {
    const char* file;
    int v, f;
  } table[] = {
      {"max-planck-partial.obj", 31894, 63347}, {"face-bff.obj", 17157, 34144},
      {"camelhead.off", 11381, 22704},          {"stanford-bunny.obj", 35947, 69451},
      {"beetle.off", 19887, 38656},             {"fairing-cross.off", 4983, 9762},
      {"maze.obj", 6120, 9174},                 {"camel_b.obj", 2032, 3576},
      {"animal.obj", 19937, 39036},             {"inverted-triangles.obj", 12577, 24685},
      {"inspired_mesh.obj", 2244, 4288},        {"snail.obj", 871, 1653},
      {"cat_head.obj", 131, 248},               {"alligator.obj", 3208, 5981},
      {"max-planck-partial-loop2.obj.gz", 507655, 1013552},
  };
  for (const Expect& e : table) {
    SCOPED_TRACE(e.file);
    const std::string path = intrinsic::test::shared_mesh(e.file);
    ASSERT_EQ(::access(path.c_str(), R_OK), 0) << "shared mesh missing: " << path;
    MeshData m;
    ASSERT_NO_THROW(m = intrinsic::read_mesh(path));
    EXPECT_EQ(m.V.rows(), e.v);
    EXPECT_EQ(m.F.rows(), e.f);
    EXPECT_EQ(m.face_line.size(), static_cast<std::size_t>(e.f));
    EXPECT_TRUE(m.V.allFinite());
    EXPECT_GE(m.F.minCoeff(), 0);
    EXPECT_LT(m.F.maxCoeff(), e.v);
    const std::string name = e.file;
    if (name == "maze.obj" || name == "camel_b.obj") {
      EXPECT_TRUE(m.has_uv());
    }
  }
}

TEST(IoObj, ByteOrderMarkIsSkipped) {
  MeshData m = read_text("\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "bom.obj");
  EXPECT_EQ(m.V.rows(), 3);
  EXPECT_EQ(m.face_line, (std::vector<int>{4}));
}
