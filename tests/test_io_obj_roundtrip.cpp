// The OBJ round trip of `atlas`: what the input OBJ carried (mtllib lines,
// usemtl / g / o / s per face, normals per corner) comes back from the atlas
// OBJ, read by the reader, face by face; only the texture coordinates are
// replaced. The input is a quad sphere written here, with its expected labels
// and normals recorded by the writer of the test (not by the reader under
// test). Plain files still give exactly the bytes of before, checked against
// an assembly of the file written in the test.
#include <gtest/gtest.h>

#include <charconv>
#include <map>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "intrinsic/atlas.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/generate.h"
#include "intrinsic/io.h"
#include "test_support.h"

namespace intrinsic {
namespace {

using test::TempDir;
using Label = std::optional<std::string>;  // nullopt: no statement of the kind before the face

std::string num(double x) {
  char b[32];
  return std::string(b, std::to_chars(b, b + sizeof b, x).ptr);
}

// What the test wrote for one triangle (the fan of its polygon).
struct ExpectedFace {
  Label material, group, object, smoothing;
  int v[3];
  std::optional<Eigen::Vector3d> normal[3];  // per corner; none when written without one
};

struct ObjFile {
  std::string text;
  std::vector<ExpectedFace> faces;  // after fan triangulation, in file order
  std::vector<std::string> libraries;
  int statements[4] = {0, 0, 0, 0};  // o, g, usemtl, s lines written (each one a change)
};

// A closed quad sphere: an n x n grid on every side of a cube, pushed onto
// the unit sphere, vertices shared along the cube's edges.
struct QuadSphere {
  MatrixX3d V;
  std::vector<std::array<int, 4>> quads[6];  // per side, outward counter-clockwise
};

QuadSphere quad_sphere(int n) {
  QuadSphere q;
  std::map<std::array<int, 3>, int> index;
  std::vector<Eigen::Vector3d> pos;
  auto vertex = [&](std::array<int, 3> g) {
    auto [it, fresh] = index.emplace(g, static_cast<int>(pos.size()));
    if (fresh) pos.push_back(Eigen::Vector3d(2.0 * g[0] / n - 1, 2.0 * g[1] / n - 1, 2.0 * g[2] / n - 1).normalized());
    return it->second;
  };
  for (int side = 0; side < 6; ++side) {
    const int axis = side / 2, a = (axis + 1) % 3, b = (axis + 2) % 3;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        std::array<int, 4> c;
        const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
        for (int k = 0; k < 4; ++k) {
          std::array<int, 3> g;
          g[axis] = side % 2 ? n : 0, g[a] = i + di[k], g[b] = j + dj[k];
          c[k] = vertex(g);
        }
        const Eigen::Vector3d n0 = (pos[c[1]] - pos[c[0]]).cross(pos[c[2]] - pos[c[0]]);
        if (n0.dot(pos[c[0]] + pos[c[2]]) < 0) std::swap(c[1], c[3]);
        q.quads[side].push_back(c);
      }
  }
  q.V.resize(static_cast<Eigen::Index>(pos.size()), 3);
  for (std::size_t i = 0; i < pos.size(); ++i) q.V.row(static_cast<Eigen::Index>(i)) = pos[i];
  return q;
}

// The sphere as an OBJ with everything: a usemtl before any mtllib, two
// mtllib lines (one in the middle of the faces, naming two files), three
// materials (one used twice), faces before the first `g`, a bare `g`, names
// with blanks and '#', two objects, smoothing groups on and off, old texture
// coordinates, smooth normals (one per vertex), flat normals (one per side),
// a side without normals and a side with negative normal indices.
ObjFile sphere_obj(int n) {
  const QuadSphere q = quad_sphere(n);
  const int nv = static_cast<int>(q.V.rows());
  ObjFile o;
  std::ostringstream s;
  Label material, group, object, smoothing;
  auto statement = [&](const char* kw, Label& state, const std::string& name) {
    s << kw << (name.empty() ? "" : " ") << name << "\n";
    state = name;
    const std::string k = kw;
    ++o.statements[k == "o" ? 0 : k == "g" ? 1 : k == "usemtl" ? 2 : 3];
  };
  auto library = [&](const std::string& name) {
    s << "mtllib " << name << "\n";
    o.libraries.push_back(name);
  };
  s << "# a quad sphere with materials, groups, objects, smoothing groups and normals\n";
  statement("usemtl", material, "red");
  library("first.mtl");
  statement("o", object, "Ball");
  for (int v = 0; v < nv; ++v) s << "v " << num(q.V(v, 0)) << ' ' << num(q.V(v, 1)) << ' ' << num(q.V(v, 2)) << "\n";
  for (int v = 0; v < nv; ++v) s << "vt " << num(0.5 + 0.5 * q.V(v, 0)) << ' ' << num(0.5 + 0.5 * q.V(v, 1)) << "\n";
  for (int v = 0; v < nv; ++v) s << "vn " << num(q.V(v, 0)) << ' ' << num(q.V(v, 1)) << ' ' << num(q.V(v, 2)) << "\n";
  Eigen::Vector3d flat[6];
  for (int side = 0; side < 6; ++side) {
    flat[side] = Eigen::Vector3d::Zero();
    flat[side][side / 2] = side % 2 ? 1 : -1;
    s << "vn " << num(flat[side][0]) << ' ' << num(flat[side][1]) << ' ' << num(flat[side][2]) << "\n";
  }
  const int n_normals = nv + 6;
  for (int side = 0; side < 6; ++side) {
    if (side == 0) statement("s", smoothing, "1");
    if (side == 1) statement("g", group, "north cap");
    if (side == 2) {
      library("second.mtl third.mtl");
      statement("usemtl", material, "green");
      statement("s", smoothing, "off");
      statement("g", group, "");
    }
    if (side == 3) statement("g", group, "belt #2");
    if (side == 4) statement("o", object, "Ball.001"), statement("usemtl", material, "blue"), statement("s", smoothing, "2");
    if (side == 5) statement("usemtl", material, "red"), statement("s", smoothing, "1");
    for (const std::array<int, 4>& c : q.quads[side]) {
      s << "f";
      std::optional<Eigen::Vector3d> normal[4];
      for (int k = 0; k < 4; ++k) {
        const int v = c[k];
        s << ' ' << v + 1 << '/' << v + 1;
        if (side <= 1) s << '/' << v + 1, normal[k] = Eigen::Vector3d(q.V.row(v));
        if (side == 2 || side == 3) s << '/' << nv + side + 1, normal[k] = flat[side];
        if (side == 5) s << '/' << v - n_normals, normal[k] = Eigen::Vector3d(q.V.row(v));  // negative: counted back
      }
      s << "\n";
      for (int k = 1; k + 1 < 4; ++k) {
        ExpectedFace e{material, group, object, smoothing, {c[0], c[k], c[k + 1]}, {normal[0], normal[k], normal[k + 1]}};
        o.faces.push_back(e);
      }
    }
  }
  o.text = s.str();
  return o;
}

const Label none;

Label label(const FaceLabels& l, int f) {
  const std::string* s = l.of(f);
  return s ? Label(*s) : none;
}

// Every face of `file` carries the labels and, corner by corner (matched by
// vertex, so a face written in another corner order still compares), the
// normal the test wrote.
void expect_as_written(const ObjFile& o, const MeshFile& file, const std::string& what) {
  const MeshData& got = file.mesh;
  const ObjExtras& x = file.document.obj;
  ASSERT_EQ(got.F.rows(), static_cast<Eigen::Index>(o.faces.size())) << what;
  EXPECT_EQ(x.material_libraries, o.libraries) << what;
  ASSERT_TRUE(x.has_normals(got.F)) << what;
  int mismatches = 0;
  for (int f = 0; f < got.F.rows() && mismatches < 10; ++f) {
    const ExpectedFace& e = o.faces[static_cast<std::size_t>(f)];
    const bool same = label(x.materials, f) == e.material && label(x.groups, f) == e.group &&
                      label(x.objects, f) == e.object && label(x.smoothing, f) == e.smoothing;
    if (!same) ++mismatches, ADD_FAILURE() << what << ": face " << f << " has other labels than written";
    for (int c = 0; c < 3; ++c) {
      const int v = got.F(f, c);
      const int k = v == e.v[0] ? 0 : v == e.v[1] ? 1 : v == e.v[2] ? 2 : -1;
      ASSERT_GE(k, 0) << what << ": face " << f << " has vertex " << v << " the test did not write";
      const int n = x.FN(f, c);
      if (!e.normal[k]) {
        EXPECT_EQ(n, -1) << what << ": face " << f << " corner " << c;
        continue;
      }
      ASSERT_GE(n, 0) << what << ": face " << f << " corner " << c << " lost its normal";
      if (Eigen::Vector3d(x.N.row(n)) != *e.normal[k])
        ++mismatches, ADD_FAILURE() << what << ": face " << f << " corner " << c << " has another normal";
    }
  }
}

// Lines of `text` starting with `keyword` and a blank or the line's end.
int count_statements(const std::string& text, const std::string& keyword) {
  std::istringstream in(text);
  std::string line;
  int n = 0;
  while (std::getline(in, line))
    if (line.compare(0, keyword.size(), keyword) == 0 && (line.size() == keyword.size() || line[keyword.size()] == ' '))
      ++n;
  return n;
}

TEST(ObjRoundTrip, ReaderKeepsWhatTheFileCarried) {
  const ObjFile o = sphere_obj(3);
  const MeshFile file = read_mesh_file_from_memory(o.text, "sphere.obj");
  const MeshData& m = file.mesh;
  const ObjExtras& x = file.document.obj;
  expect_as_written(o, file, "read");
  EXPECT_TRUE(m.has_uv());
  EXPECT_TRUE(m.had_texcoords);
  EXPECT_FALSE(x.empty());
  EXPECT_FALSE(file.document.gltf);
  // Three materials, each name once in the table although red is used twice.
  EXPECT_EQ(x.materials.names, (std::vector<std::string>{"red", "green", "blue"}));
  EXPECT_EQ(x.groups.names, (std::vector<std::string>{"north cap", "", "belt #2"}));
  // The geometry alone is the same mesh.
  const MeshData alone = read_mesh_from_memory(o.text, "sphere.obj");
  EXPECT_EQ(alone.V, m.V);
  EXPECT_EQ(alone.F, m.F);
  EXPECT_EQ(alone.TC, m.TC);
  EXPECT_EQ(alone.FTC, m.FTC);
  EXPECT_EQ(alone.face_line, m.face_line);
}

TEST(ObjRoundTrip, LibraryAtlasGivesEverythingBack) {
  const ObjFile o = sphere_obj(4);
  TempDir dir;
  const MeshFile in_file = read_mesh_file_from_memory(o.text, dir / "in.obj");
  const MeshData& in = in_file.mesh;
  const AtlasResult r = atlas(in);
  write_atlas_obj(dir / "out.obj", in_file, r);
  const MeshFile back_file = read_mesh_file(dir / "out.obj");
  const MeshData& back = back_file.mesh;
  expect_as_written(o, back_file, "atlas OBJ");
  // Same positions, same faces; the texture coordinates are the atlas's.
  EXPECT_EQ(back.V, in.V);
  EXPECT_EQ(back.F, r.F);
  ASSERT_TRUE(back.has_uv());
  EXPECT_EQ(back.TC, r.UV);
  EXPECT_EQ(back.FTC, r.FUV);
  // A statement only where the label changes, so exactly as many as written.
  const std::string text = test::slurp(dir / "out.obj");
  const char* keywords[] = {"o", "g", "usemtl", "s"};
  for (int k = 0; k < 4; ++k) EXPECT_EQ(count_statements(text, keywords[k]), o.statements[k]) << keywords[k];
  EXPECT_EQ(count_statements(text, "vn"), in_file.document.obj.N.rows());
  // mtllib lines come first, before any vertex.
  EXPECT_EQ(text.find("mtllib first.mtl\nmtllib second.mtl third.mtl\nv "), text.find('\n') + 1);
}

TEST(ObjRoundTrip, CliAtlasGivesEverythingBack) {
  const ObjFile o = sphere_obj(4);
  TempDir dir;
  test::write_text(dir / "in.obj", o.text);
  const test::CliResult res = test::run_cli("atlas " + dir / "in.obj" + " -o " + dir / "out.obj" + " --quiet", dir);
  ASSERT_EQ(res.code, 0) << res.err;
  const MeshFile in = read_mesh_file(dir / "in.obj");
  const MeshFile back = read_mesh_file(dir / "out.obj");
  expect_as_written(o, back, "intrinsic atlas");
  EXPECT_EQ(back.mesh.V, in.mesh.V);
  // Same bytes as the library's writer.
  write_atlas_obj(dir / "lib.obj", in, atlas(in));
  EXPECT_EQ(test::slurp(dir / "out.obj"), test::slurp(dir / "lib.obj"));
}

// The atlas OBJ of a file with nothing but v and f, assembled here from the
// result as the writer did before it kept anything else.
std::string plain_atlas_obj(const MeshData& m, const AtlasResult& r) {
  std::string s = "# intrinsic atlas: " + std::to_string(r.charts.size()) + " charts\n";
  for (int v = 0; v < m.V.rows(); ++v) s += "v " + num(m.V(v, 0)) + " " + num(m.V(v, 1)) + " " + num(m.V(v, 2)) + "\n";
  for (int t = 0; t < r.UV.rows(); ++t) s += "vt " + num(r.UV(t, 0)) + " " + num(r.UV(t, 1)) + "\n";
  for (int f = 0; f < r.F.rows(); ++f) {
    s += "f";
    for (int c = 0; c < 3; ++c) s += " " + std::to_string(r.F(f, c) + 1) + "/" + std::to_string(r.FUV(f, c) + 1);
    s += "\n";
  }
  return s;
}

TEST(ObjRoundTrip, PlainFileGivesTheSameBytesAsBefore) {
  TempDir dir;
  GenerateOptions g;
  g.rings = 6;
  const MeshData torus = generate_torus(g);
  write_mesh(dir / "torus.obj", torus.V, torus.F, MatrixX2d());
  const MeshFile in_file = read_mesh_file(dir / "torus.obj");
  const MeshData& in = in_file.mesh;
  const ObjExtras& x = in_file.document.obj;
  // Nothing beyond positions and faces: nothing allocated for it.
  EXPECT_TRUE(x.empty());
  EXPECT_FALSE(in.had_texcoords);
  EXPECT_EQ(x.N.rows(), 0);
  EXPECT_EQ(x.FN.rows(), 0);
  EXPECT_TRUE(x.materials.of_face.empty() && x.groups.of_face.empty() && x.objects.of_face.empty() &&
              x.smoothing.of_face.empty());
  const AtlasResult r = atlas(in);
  write_atlas_obj(dir / "out.obj", in_file, r);
  EXPECT_EQ(test::slurp(dir / "out.obj"), plain_atlas_obj(in, r));
}

TEST(ObjRoundTrip, NormalIndexOutOfRangeNamesFileAndLine) {
  // vt indices there are fine, so that only the normal index is wrong.
  const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 1\nvt 0 0\n";
  struct Case {
    std::string face, fragment;
  };
  const Case cases[] = {
      {"f 1//1 2//3 3//1\n", "bad.obj:8: face normal index 3 out of range (file has 2 normals)"},
      {"f 1/1/1 2/1/1 3/1/9\n", "bad.obj:8: face normal index 9 out of range (file has 2 normals)"},
      {"f 1//-3 2//1 3//1\n", "bad.obj:8: face normal index -3 out of range (only 2 defined so far)"},
      {"f 1//0 2//1 3//1\n", "bad.obj:8: face normal index 0 is invalid"},
      {"f 1//x 2//1 3//1\n", "bad.obj:8: expected a normal index"},
  };
  for (const Case& c : cases) {
    const std::string text = head + "g a\n" + c.face;
    try {
      read_mesh_from_memory(text, "bad.obj");
      ADD_FAILURE() << "no error for " << c.face;
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input);
      EXPECT_NE(std::string(e.what()).find(c.fragment), std::string::npos) << e.what();
    }
  }
  TempDir dir;
  test::write_text(dir / "bad.obj", head + "f 1/1/1 2/1/7 3/1/1\n");
  const test::CliResult res = test::run_cli("atlas " + dir / "bad.obj" + " -o " + dir / "out.obj", dir);
  EXPECT_NE(res.code, 0);
  EXPECT_NE(res.err.find("bad.obj:7: face normal index 7 out of range"), std::string::npos) << res.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{"bad.obj"});  // nothing written
}

TEST(ObjRoundTrip, NormalsMayBeDefinedAfterTheFaces) {
  const MeshFile m =
      read_mesh_file_from_memory("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//2 2//2 3//1\nvn 0 0 1\nvn 0 0 -1\n", "late.obj");
  const ObjExtras& x = m.document.obj;
  ASSERT_TRUE(x.has_normals(m.mesh.F));
  EXPECT_EQ(x.FN.row(0), Eigen::RowVector3i(1, 1, 0));
  EXPECT_EQ(x.N(1, 2), -1.0);
}

TEST(ObjRoundTrip, PolygonTrianglesInheritEverything) {
  const std::string text =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0.5 0\nvn 0 0 1\nvn 0 0.6 0.8\n"
      "f 1 2 3\n"                          // before any statement
      "usemtl Material #25\r\n"            // before any mtllib, with '#' and CRLF
      "g left  right \n"                   // a list of names: one label
      "s 4\n"
      "f 1//1 2//2 3//1 4//2 5//1\n"       // a pentagon: three triangles
      "mtllib  lib one.mtl \n"
      "f 1//2 3 4\n";                      // mixed corner forms
  const MeshFile file = read_mesh_file_from_memory(text, "poly.obj");
  const ObjExtras& m = file.document.obj;
  ASSERT_EQ(file.mesh.F.rows(), 5);
  EXPECT_EQ(m.material_libraries, std::vector<std::string>{"lib one.mtl"});
  const Label mat = std::string("Material #25"), grp = std::string("left  right"), sm = std::string("4");
  const Label want_mat[] = {none, mat, mat, mat, mat}, want_grp[] = {none, grp, grp, grp, grp};
  const Label want_s[] = {none, sm, sm, sm, sm};
  for (int f = 0; f < 5; ++f) {
    EXPECT_EQ(label(m.materials, f), want_mat[f]) << f;
    EXPECT_EQ(label(m.groups, f), want_grp[f]) << f;
    EXPECT_EQ(label(m.smoothing, f), want_s[f]) << f;
    EXPECT_EQ(label(m.objects, f), none) << f;
  }
  EXPECT_TRUE(m.objects.empty());
  ASSERT_TRUE(m.has_normals(file.mesh.F));
  // Fan (0, k, k+1) of the pentagon's corners 1//1 2//2 3//1 4//2 5//1.
  EXPECT_EQ(m.FN.row(0), Eigen::RowVector3i(-1, -1, -1));
  EXPECT_EQ(m.FN.row(1), Eigen::RowVector3i(0, 1, 0));
  EXPECT_EQ(m.FN.row(2), Eigen::RowVector3i(0, 0, 1));
  EXPECT_EQ(m.FN.row(3), Eigen::RowVector3i(0, 1, 0));
  EXPECT_EQ(m.FN.row(4), Eigen::RowVector3i(1, -1, -1));
}

// With reorientation the result lists some faces 0, 2, 1: each corner keeps
// its own normal. A strip of two triangles, the second listed backwards.
TEST(ObjRoundTrip, ReversedFacesKeepTheirCornersNormals) {
  const std::string text =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
      "vn 1 0 0\nvn 0 1 0\nvn 0 0 1\nvn 1 1 0\nvn 1 0 1\nvn 0 1 1\n"
      "usemtl a\nf 1//1 2//2 3//3\nf 1//4 3//5 4//6\nusemtl b\nf 2//1 3//2 5//3\nf 3//4 5//5 6//6\n";
  TempDir dir;
  const MeshFile in = read_mesh_file_from_memory(text, "strip.obj");
  const AtlasResult r = atlas(in);
  ASSERT_GE(r.cleaning.reversed_faces, 1);
  write_atlas_obj(dir / "out.obj", in, r);
  const MeshFile back = read_mesh_file(dir / "out.obj");
  const ObjExtras &bx = back.document.obj, &ix = in.document.obj;
  ASSERT_TRUE(bx.has_normals(back.mesh.F));
  for (int f = 0; f < 4; ++f) {
    EXPECT_EQ(*bx.materials.of(f), f < 2 ? "a" : "b");
    for (int c = 0; c < 3; ++c) {
      const int v = back.mesh.F(f, c);
      const int k = v == in.mesh.F(f, 0) ? 0 : v == in.mesh.F(f, 1) ? 1 : 2;
      EXPECT_EQ(Eigen::Vector3d(bx.N.row(bx.FN(f, c))), Eigen::Vector3d(ix.N.row(ix.FN(f, k)))) << f << " " << c;
    }
  }
}

TEST(ObjRoundTrip, HandMadeInconsistentDataIsRefused) {
  TempDir dir;
  const MeshFile m = read_mesh_file_from_memory("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "t.obj");
  const AtlasResult r = atlas(m);
  MeshFile bad = m;
  bad.document.obj.materials.names = {"x"};
  bad.document.obj.materials.of_face = {3};
  EXPECT_THROW(write_atlas_obj(dir / "a.obj", bad, r), Error);
  bad = m;
  bad.document.obj.groups.names = {"two\nlines"};
  bad.document.obj.groups.of_face = {0};
  EXPECT_THROW(write_atlas_obj(dir / "b.obj", bad, r), Error);
  bad = m;
  bad.document.obj.N = MatrixX3d::Zero(1, 3);
  bad.document.obj.FN = MatrixX3i::Constant(1, 3, 1);
  EXPECT_THROW(write_atlas_obj(dir / "c.obj", bad, r), Error);
  EXPECT_TRUE(dir.files().empty());
}

// The real assets carry no usemtl; what they carry still comes back:
// suzanne's normals per corner (quads), snail's group, spot's texture
// coordinates replaced.
TEST(ObjRoundTripCorpus, AssetsKeepWhatTheyCarried) {
  REQUIRE_SHARED_MESHES();
  TempDir dir;
  {
    const MeshFile in_file = read_mesh_file(test::shared_mesh("assets/suzanne.obj"));
    const MeshData& in = in_file.mesh;
    const ObjExtras& ix = in_file.document.obj;
    ASSERT_TRUE(ix.has_normals(in.F));
    const AtlasResult r = atlas(in);
    write_atlas_obj(dir / "suzanne.obj", in_file, r);
    const MeshFile back_file = read_mesh_file(dir / "suzanne.obj");
    const MeshData& back = back_file.mesh;
    const ObjExtras& bx = back_file.document.obj;
    ASSERT_TRUE(bx.has_normals(back.F));
    ASSERT_EQ(back.F.rows(), in.F.rows());
    EXPECT_EQ(back.V, in.V);
    for (int f = 0; f < in.F.rows(); ++f)
      for (int c = 0; c < 3; ++c) {
        const int v = back.F(f, c);
        const int k = v == in.F(f, 0) ? 0 : v == in.F(f, 1) ? 1 : 2;
        ASSERT_EQ(Eigen::Vector3d(bx.N.row(bx.FN(f, c))), Eigen::Vector3d(ix.N.row(ix.FN(f, k)))) << f;
      }
  }
  {
    const MeshFile in = read_mesh_file(test::shared_mesh("snail.obj"));
    ASSERT_FALSE(in.document.obj.groups.empty());
    const AtlasResult r = atlas(in);
    write_atlas_obj(dir / "snail.obj", in, r);
    const MeshFile back = read_mesh_file(dir / "snail.obj");
    EXPECT_EQ(back.document.obj.groups.names, std::vector<std::string>{"object"});
    EXPECT_EQ(back.document.obj.groups.of_face, in.document.obj.groups.of_face);
  }
  {
    const MeshFile in = read_mesh_file(test::shared_mesh("assets/spot.obj"));
    EXPECT_TRUE(in.mesh.had_texcoords);
    EXPECT_TRUE(in.document.obj.empty());
  }
}

}  // namespace
}  // namespace intrinsic
