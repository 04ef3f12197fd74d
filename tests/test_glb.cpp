// glTF 2.0 binary output: the atlas of a closed surface
// written as .glb and read back with tinygltf's own loader; every corner's
// position and texture coordinate must equal the atlas result (as float32,
// v flipped to glTF's top-left origin), vertices split exactly where corners
// of one vertex carry different texture coordinates; no file on failure.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

// The same configuration as src/io/glb_writer.cpp, which holds the implementation.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include "cli_support.h"
#include "intrinsic/atlas.h"
#include "intrinsic/generate.h"
#include "intrinsic/io.h"
#include "test_support.h"

namespace intrinsic {
namespace {

tinygltf::Model load_glb(const std::string& path) {
  const std::string bytes = test::slurp(path);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  const bool ok = loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                              static_cast<unsigned>(bytes.size()));
  EXPECT_TRUE(ok) << err;
  EXPECT_TRUE(err.empty()) << err;
  return model;
}

template <class T>
const T* accessor_data(const tinygltf::Model& model, int accessor) {
  const tinygltf::Accessor& a = model.accessors.at(accessor);
  const tinygltf::BufferView& v = model.bufferViews.at(a.bufferView);
  EXPECT_EQ(v.byteStride, 0u);  // tightly packed
  return reinterpret_cast<const T*>(model.buffers.at(v.buffer).data.data() + v.byteOffset + a.byteOffset);
}

TEST(Glb, AtlasReadsBackEqual) {
  GenerateOptions g;
  g.rings = 8;
  const MeshData m = generate_torus(g);
  const AtlasResult r = atlas(m);
  test::TempDir dir;
  write_glb(dir / "a.glb", m.V, m.F, r.UV, r.FUV);
  const tinygltf::Model model = load_glb(dir / "a.glb");
  ASSERT_EQ(model.meshes.size(), 1u);
  ASSERT_EQ(model.meshes[0].primitives.size(), 1u);
  const tinygltf::Primitive& p = model.meshes[0].primitives[0];
  EXPECT_EQ(p.mode, TINYGLTF_MODE_TRIANGLES);
  const tinygltf::Accessor& ia = model.accessors.at(p.indices);
  ASSERT_EQ(ia.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  ASSERT_EQ(ia.count, static_cast<size_t>(3 * m.F.rows()));
  const tinygltf::Accessor& pa = model.accessors.at(p.attributes.at("POSITION"));
  const tinygltf::Accessor& ta = model.accessors.at(p.attributes.at("TEXCOORD_0"));
  // As many glTF vertices as distinct (vertex, texture coordinate) corners:
  // the torus is smooth, so normals split nothing more.
  std::set<std::pair<int, int>> corners;
  for (int f = 0; f < m.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) corners.insert({m.F(f, c), r.FUV(f, c)});
  ASSERT_EQ(pa.count, corners.size());
  ASSERT_EQ(ta.count, corners.size());
  EXPECT_GT(corners.size(), static_cast<size_t>(m.V.rows()));  // a closed surface has seams
  const auto* idx = accessor_data<std::uint32_t>(model, p.indices);
  const auto* pos = accessor_data<float>(model, p.attributes.at("POSITION"));
  const auto* tex = accessor_data<float>(model, p.attributes.at("TEXCOORD_0"));
  for (int f = 0; f < m.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t i = idx[3 * f + c];
      ASSERT_LT(i, pa.count);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(pos[3 * i + k], static_cast<float>(m.V(m.F(f, c), k)));
      EXPECT_EQ(tex[2 * i], static_cast<float>(r.UV(r.FUV(f, c), 0)));
      EXPECT_EQ(tex[2 * i + 1], static_cast<float>(1 - r.UV(r.FUV(f, c), 1)));
    }
  ASSERT_EQ(pa.minValues.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(pa.minValues[k], static_cast<float>(m.V.col(k).minCoeff()));
    EXPECT_EQ(pa.maxValues[k], static_cast<float>(m.V.col(k).maxCoeff()));
  }
}

// The NORMAL attribute of every glTF vertex, per face corner.
Eigen::Vector3d corner_normal(const tinygltf::Model& model, int f, int c) {
  const tinygltf::Primitive& p = model.meshes.at(0).primitives.at(0);
  const auto* idx = accessor_data<std::uint32_t>(model, p.indices);
  const auto* nrm = accessor_data<float>(model, p.attributes.at("NORMAL"));
  const std::uint32_t i = idx[3 * f + c];
  return Eigen::Vector3d(nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]);
}

// A smooth surface shades smoothly: on a fine regular torus (R = 1, r = 0.4)
// every corner's normal is within 1.5 degrees of the analytic normal at its
// vertex, with one orientation throughout, and a vertex is split only where
// its texture coordinates differ.
TEST(Glb, NormalsOfSmoothSurfaceFollowTheSurface) {
  GenerateOptions g;
  g.rings = 24;
  g.jitter = 0;
  const MeshData m = generate_torus(g);
  const AtlasResult r = atlas(m);
  test::TempDir dir;
  write_glb(dir / "t.glb", m.V, m.F, r.UV, r.FUV);
  const tinygltf::Model model = load_glb(dir / "t.glb");
  std::set<std::pair<int, int>> corners;
  double sign = 0;
  for (int f = 0; f < m.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      corners.insert({m.F(f, c), r.FUV(f, c)});
      const Eigen::Vector3d x = m.V.row(m.F(f, c));
      const Eigen::Vector3d centre = Eigen::Vector3d(x.x(), x.y(), 0).normalized();
      const Eigen::Vector3d exact = (x - centre).normalized(), n = corner_normal(model, f, c);
      ASSERT_NEAR(n.norm(), 1, 1e-6);
      if (sign == 0) sign = n.dot(exact) > 0 ? 1 : -1;
      ASSERT_GT(sign * n.dot(exact), std::cos(1.5 * M_PI / 180)) << "face " << f << " corner " << c;
    }
  const tinygltf::Primitive& p = model.meshes.at(0).primitives.at(0);
  EXPECT_EQ(model.accessors.at(p.attributes.at("NORMAL")).count, corners.size());
}

// Hard edges stay hard: on a cube each corner's normal is its own face's
// axis, so each cube vertex becomes three glTF vertices (24), even with one
// texture coordinate per vertex.
TEST(Glb, NormalsOfCubeAreItsFaceNormals) {
  MatrixX3d V(8, 3);
  for (int v = 0; v < 8; ++v) V.row(v) << (v & 1), (v >> 1 & 1), (v >> 2 & 1);
  const MatrixX3i F = (MatrixX3i(12, 3) << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,  //
                       2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5)
                          .finished();
  const MatrixX2d UV = V.leftCols(2);
  test::TempDir dir;
  write_glb(dir / "c.glb", V, F, UV, F);
  const tinygltf::Model model = load_glb(dir / "c.glb");
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::Vector3d face = (b - a).cross(c - a).normalized();
    for (int k = 0; k < 3; ++k) EXPECT_LT((corner_normal(model, f, k) - face).norm(), 1e-7) << f;
  }
  const tinygltf::Primitive& p = model.meshes.at(0).primitives.at(0);
  EXPECT_EQ(model.accessors.at(p.attributes.at("POSITION")).count, 24u);
}

TEST(Glb, FailuresLeaveNoFile) {
  const MatrixX3d V = (MatrixX3d(3, 3) << 0, 0, 0, 1, 0, 0, 0, 1, 0).finished();
  const MatrixX3i F = (MatrixX3i(1, 3) << 0, 1, 2).finished();
  const MatrixX2d UV = (MatrixX2d(3, 2) << 0, 0, 1, 0, 0, 1).finished();
  test::TempDir dir;
  test::expect_error([&] { write_glb(dir / "x.glb", V, F, UV, (MatrixX3i(1, 3) << 0, 1, 3).finished()); },
                     ErrorKind::Input, "out of range");
  MatrixX3d huge = V;
  huge(1, 0) = 1e300;
  test::expect_error([&] { write_glb(dir / "x.glb", huge, F, UV, F); }, ErrorKind::Input, "32-bit float");
  test::expect_error([&] { write_glb(dir / "no/such/dir/x.glb", V, F, UV, F); }, ErrorKind::Output, "");
  EXPECT_TRUE(std::filesystem::is_empty(std::string(dir / "")));
}

// `intrinsic atlas IN -o x.glb`: one mesh with every face; .glb.gz refused.
void expect_atlas_cli_glb(const std::string& in, const test::TempDir& dir) {
  const auto r = test::run_cli("atlas " + in + " -o " + (dir / "t.glb") + " -q", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const MeshData m = read_mesh(in);
  const tinygltf::Model model = load_glb(dir / "t.glb");
  ASSERT_EQ(model.meshes.size(), 1u);
  EXPECT_EQ(model.accessors.at(model.meshes[0].primitives[0].indices).count, static_cast<size_t>(3 * m.F.rows()));
  const auto bad = test::run_cli("atlas " + in + " -o " + (dir / "t.glb.gz") + " -q", dir);
  EXPECT_NE(bad.code, 0);
  EXPECT_FALSE(std::filesystem::exists(std::string(dir / "t.glb.gz")));
}

TEST(Glb, AtlasCliWritesGlb) {
  test::TempDir dir;
  ASSERT_EQ(test::run_cli("generate genus2 --rings 8 -o " + (dir / "g.obj"), dir).code, 0);
  expect_atlas_cli_glb(dir / "g.obj", dir);
}

TEST(GlbCorpus, AtlasCliWritesGlb) {
  REQUIRE_SHARED_MESHES();
  test::TempDir dir;
  expect_atlas_cli_glb(test::shared_mesh("assets/teapot.obj"), dir);
}

// `intrinsic param IN -o p.glb`: every corner's position and texture
// coordinate equal to the OBJ output's.
void expect_param_glb(const std::string& in, const test::TempDir& dir) {
  const auto r = test::run_cli("param " + in + " -o " + (dir / "p.glb") + " -q", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_EQ(test::run_cli("param " + in + " -o " + (dir / "p.obj") + " -q", dir).code, 0);
  const MeshData obj = read_mesh(dir / "p.obj");
  const tinygltf::Model model = load_glb(dir / "p.glb");
  const tinygltf::Primitive& p = model.meshes.at(0).primitives.at(0);
  // Without seams, glTF vertices are split only at hard edges (NORMAL).
  ASSERT_GE(model.accessors.at(p.attributes.at("POSITION")).count, static_cast<size_t>(obj.V.rows()));
  const auto* idx = accessor_data<std::uint32_t>(model, p.indices);
  const auto* tex = accessor_data<float>(model, p.attributes.at("TEXCOORD_0"));
  const auto* pos = accessor_data<float>(model, p.attributes.at("POSITION"));
  for (int f = 0; f < obj.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t i = idx[3 * f + c];
      for (int k = 0; k < 3; ++k) EXPECT_EQ(pos[3 * i + k], static_cast<float>(obj.V(obj.F(f, c), k)));
      EXPECT_NEAR(tex[2 * i], obj.TC(obj.FTC(f, c), 0), 1e-6);
      EXPECT_NEAR(tex[2 * i + 1], 1 - obj.TC(obj.FTC(f, c), 1), 1e-6);
    }
}

TEST(Glb, ParamWritesGlbWithOneUvPerVertex) {
  test::TempDir dir;
  ASSERT_EQ(test::run_cli("generate wave --rings 8 -o " + (dir / "w.obj"), dir).code, 0);
  expect_param_glb(dir / "w.obj", dir);
}

TEST(GlbCorpus, ParamWritesGlbWithOneUvPerVertex) {
  REQUIRE_SHARED_MESHES();
  test::TempDir dir;
  expect_param_glb(test::shared_mesh("cat_head.obj"), dir);
}

}  // namespace
}  // namespace intrinsic
