// glTF 2.0 documents in and out (docs/formats.md "glTF"). Documents are built
// here by hand (JSON + one binary buffer), read through read_mesh_file, given an
// atlas, written back, and the output read with tinygltf's own loader: every
// output corner must carry, byte for byte, the attributes of the input corner
// it came from plus the atlas coordinate of that corner; everything outside
// the meshes must be unchanged JSON; the Khronos validator must find no error.
// Malformed documents are refused with the JSON path of the culprit.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstring>
#include <functional>
#include <filesystem>
#include <map>

#include "atlas_test_support.h"
#include "cli_support.h"
#include "gltf_support.h"
#include "intrinsic/atlas.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/generate.h"
#include "intrinsic/gltf.h"
#include "intrinsic/io.h"
#include "test_support.h"

namespace intrinsic {
namespace {

using nlohmann::json;
using namespace gltf_test;

// Per output corner, the input corner it came from, matched by its full
// attribute bytes (every input vertex of the torus has its own position).
TEST(Gltf, RoundTripKeepsEveryAttributePerCorner) {
  RichAsset a = rich_asset();
  test::TempDir dir;
  test::write_text(dir / "in.gltf", a.doc.gltf());
  expect_valid(dir / "in.gltf");
  const MeshFile file = read_mesh_file(dir / "in.gltf");
  const MeshData& data = file.mesh;
  ASSERT_TRUE(file.document.gltf);
  ASSERT_EQ(data.F.rows(), a.m.F.rows());
  ASSERT_EQ(data.F, a.m.F);
  const std::vector<float> input_positions = positions(a.m);
  const AtlasResult r = atlas(data);
  for (const std::string out : {"out.glb", "out.gltf"}) {
    SCOPED_TRACE(out);
    write_atlas_file(dir / out, file, r);
    expect_valid(dir / out);
    const tinygltf::Model m = load(dir / out);
    ASSERT_EQ(m.meshes.size(), 1u);
    const tinygltf::Primitive& p = m.meshes[0].primitives.at(0);
    EXPECT_EQ(p.mode, TINYGLTF_MODE_TRIANGLES);
    ASSERT_EQ(m.accessors.at(static_cast<std::size_t>(p.indices)).count, static_cast<std::size_t>(3 * a.m.F.rows()));
    ASSERT_TRUE(p.attributes.count("TEXCOORD_1"));  // the next free set
    ASSERT_EQ(p.targets.size(), 1u);
    std::size_t split = 0;
    for (int f = 0; f < a.m.F.rows(); ++f)
      for (int c = 0; c < 3; ++c) {
        const std::uint32_t o = index_of(m, p.indices, static_cast<std::size_t>(3 * f + c));
        split = std::max<std::size_t>(split, o + 1);
        const std::string pos = element(m, p.attributes.at("POSITION"), o);
        // Corner c of the output face is corner c of the input face.
        const int src = a.m.F(f, c);
        ASSERT_EQ(bytes_of(input_positions, static_cast<std::size_t>(src), 3), pos) << "face " << f << " corner " << c;
        const auto s = static_cast<std::size_t>(src);
        EXPECT_EQ(element(m, p.attributes.at("NORMAL"), o), bytes_of(a.normal, s, 3));
        EXPECT_EQ(element(m, p.attributes.at("TEXCOORD_0"), o), bytes_of(a.texcoord, s, 2));
        EXPECT_EQ(element(m, p.attributes.at("COLOR_0"), o), bytes_of(a.color, s, 4));
        EXPECT_EQ(element(m, p.attributes.at("JOINTS_0"), o), bytes_of(a.joints, s, 4));
        EXPECT_EQ(element(m, p.attributes.at("WEIGHTS_0"), o), bytes_of(a.weights, s, 4));
        EXPECT_EQ(element(m, p.targets[0].at("POSITION"), o), bytes_of(a.dpos, s, 3));
        EXPECT_EQ(element(m, p.targets[0].at("NORMAL"), o), bytes_of(a.dnrm, s, 3));
        // The atlas coordinate of this corner of this face (every vertex is
        // used, so the merged mesh numbers them as the input does).
        int rc = -1;
        for (int k = 0; k < 3; ++k)
          if (r.F(f, k) == src) rc = k;
        ASSERT_GE(rc, 0);
        const float uv[2] = {static_cast<float>(r.UV(r.FUV(f, rc), 0)), static_cast<float>(1 - r.UV(r.FUV(f, rc), 1))};
        EXPECT_EQ(element(m, p.attributes.at("TEXCOORD_1"), o), std::string(reinterpret_cast<const char*>(uv), 8));
      }
    EXPECT_GT(split, static_cast<std::size_t>(a.m.V.rows()));  // a closed surface has seams
    const json in = a.doc.j;
    const std::string file = test::slurp(dir / out);
    std::uint32_t json_length = 0;
    if (out == "out.glb") std::memcpy(&json_length, &file[12], 4);
    const json got = json::parse(out == "out.glb" ? file.substr(20, json_length) : file);
    {
      for (const char* key : {"nodes", "materials", "cameras", "textures", "images", "samplers",
                              "scenes", "scene", "extras", "asset"})
        EXPECT_EQ(got.at(key).dump(), in.at(key).dump()) << key;
      // Skins and animations name accessors, renumbered when the old ones
      // are dropped (test_gltf_prune.cpp checks the data they then name).
      json skins = in["skins"], animations = in["animations"];
      skins[0]["inverseBindMatrices"] = got["skins"][0]["inverseBindMatrices"];
      animations[0]["samplers"][0]["input"] = got["animations"][0]["samplers"][0]["input"];
      animations[0]["samplers"][0]["output"] = got["animations"][0]["samplers"][0]["output"];
      EXPECT_EQ(got["skins"], skins);
      EXPECT_EQ(got["animations"], animations);
      EXPECT_EQ(got["meshes"][0]["weights"], in["meshes"][0]["weights"]);
      EXPECT_EQ(got["meshes"][0]["primitives"][0]["extras"], in["meshes"][0]["primitives"][0]["extras"]);
      EXPECT_EQ(got["meshes"][0]["primitives"][0]["material"], 0);
    }
  }
}

// Faces the atlas reorients (a disk with every fifth face flipped) keep the
// document's winding, each corner with its own atlas coordinate.
TEST(Gltf, ReorientedFacesKeepTheirWinding) {
  GenerateOptions g;
  g.rings = 6;
  MeshData disk = generate_flat_disk(g);
  for (int f = 0; f < disk.F.rows(); f += 5) std::swap(disk.F(f, 1), disk.F(f, 2));
  test::TempDir dir;
  test::write_text(dir / "in.glb", simple_doc(disk).glb());
  const MeshFile file = read_mesh_file(dir / "in.glb");
  const MeshData& data = file.mesh;
  ASSERT_EQ(data.F, disk.F);
  const AtlasResult r = atlas(data);
  int reversed = 0;
  for (int f = 0; f < r.F.rows(); ++f) reversed += r.F.row(f) != data.F.row(f);
  ASSERT_GT(reversed, 0);  // the case is what it means to be
  write_atlas_file(dir / "out.glb", file, r);
  expect_valid(dir / "out.glb");
  const tinygltf::Model m = load(dir / "out.glb");
  const tinygltf::Primitive& p = m.meshes.at(0).primitives.at(0);
  const std::vector<float> in = positions(disk);
  for (int f = 0; f < disk.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t o = index_of(m, p.indices, static_cast<std::size_t>(3 * f + c));
      ASSERT_EQ(element(m, p.attributes.at("POSITION"), o), bytes_of(in, static_cast<std::size_t>(disk.F(f, c)), 3));
      int rc = 0;
      while (rc < 3 && r.F(f, rc) != disk.F(f, c)) ++rc;
      ASSERT_LT(rc, 3);
      const float uv[2] = {static_cast<float>(r.UV(r.FUV(f, rc), 0)), static_cast<float>(1 - r.UV(r.FUV(f, rc), 1))};
      EXPECT_EQ(element(m, p.attributes.at("TEXCOORD_0"), o), std::string(reinterpret_cast<const char*>(uv), 8));
    }
}

// A mesh drawn twice gets one set of coordinates, sized by its first
// instance: next to an unscaled copy of the same grid, the mesh first drawn
// at scale 3 takes 9 times the copy's UV area; first drawn at scale 1, the same.
double uv_area(const AtlasResult& r, int f0, int f1) {
  double s = 0;
  for (int f = f0; f < f1; ++f) {
    const Eigen::Vector2d a = r.UV.row(r.FUV(f, 0)), b = r.UV.row(r.FUV(f, 1)), c = r.UV.row(r.FUV(f, 2));
    s += 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
  }
  return s;
}

TEST(Gltf, InstancedMeshSizedByItsFirstInstance) {
  GenerateOptions g;
  g.rings = 6;
  const MeshData disk = generate_flat_disk(g);
  for (const double first : {3.0, 1.0}) {
    SCOPED_TRACE(first);
    Doc d = simple_doc(disk);
    d.j["meshes"].push_back(d.j["meshes"][0]);  // mesh 1: the same data
    d.j["nodes"] = json::array({{{"mesh", 0}, {"scale", {first, first, first}}},
                                {{"mesh", 0}, {"scale", {4 - first, 4 - first, 4 - first}}},
                                {{"mesh", 1}, {"translation", {10, 0, 0}}}});
    d.j["scenes"] = json::array({{{"nodes", {0, 1, 2}}}});
    test::TempDir dir;
    test::write_text(dir / "in.glb", d.glb());
    const MeshFile file = read_mesh_file(dir / "in.glb");
    const MeshData& data = file.mesh;
    const int nf = static_cast<int>(disk.F.rows());
    ASSERT_EQ(data.F.rows(), 2 * nf);  // the mesh once, not per instance
    for (int v = 0; v < disk.V.rows(); ++v)
      EXPECT_NEAR((data.V.row(v) - first * disk.V.row(v)).norm(), 0, 1e-6);
    const AtlasResult r = atlas(data);
    EXPECT_NEAR(uv_area(r, 0, nf) / uv_area(r, nf, 2 * nf), first * first, 0.05 * first * first);
    write_atlas_file(dir / "out.glb", file, r);
    expect_valid(dir / "out.glb");
    const tinygltf::Model m = load(dir / "out.glb");
    ASSERT_EQ(m.nodes.size(), 3u);
    EXPECT_EQ(m.nodes[0].mesh, 0);
    EXPECT_EQ(m.nodes[1].mesh, 0);
    EXPECT_EQ(m.meshes[0].primitives.at(0).attributes.count("TEXCOORD_0"), 1u);
    EXPECT_EQ(m.meshes[0].primitives.at(0).attributes.count("TEXCOORD_1"), 0u);
  }
}

// Strips and fans (glTF 2.0 spec 3.7.2.1) read as the list of the same
// triangles, written out by hand.
MeshFile read_indexed(int mode, const std::vector<std::uint16_t>& idx, const std::string& file) {
  Doc d;
  const std::vector<float> p = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0, 1, 2.5f, 0};
  const int pa = d.add(p, 5126, "VEC3", 6, 34962, min_max(p, json::object()));
  const int ia = d.add(idx, 5123, "SCALAR", static_cast<int>(idx.size()), 34963);
  d.j["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", pa}}}, {"indices", ia}, {"mode", mode}}})}}});
  test::write_text(file, d.gltf());
  return read_mesh_file(file);
}

TEST(Gltf, StripsAndFansAreTheirTriangles) {
  test::TempDir dir;
  const MeshFile strip = read_indexed(5, {0, 1, 2, 3, 4, 5}, dir / "strip.gltf");
  const MeshData list = read_indexed(4, {0, 1, 2, 2, 1, 3, 2, 3, 4, 4, 3, 5}, dir / "list.gltf").mesh;
  ASSERT_EQ(strip.mesh.F.rows(), 4);
  EXPECT_EQ(strip.mesh.F, list.F);
  EXPECT_EQ(strip.mesh.V, list.V);
  const MeshData fan = read_indexed(6, {0, 1, 3, 2}, dir / "fan.gltf").mesh;
  const MeshData fan_list = read_indexed(4, {1, 3, 0, 3, 2, 0}, dir / "fanlist.gltf").mesh;
  EXPECT_EQ(fan.F, fan_list.F);
  // Written back as lists that the validator accepts.
  const AtlasResult r = atlas(strip);
  write_atlas_file(dir / "strip_out.glb", strip, r);
  expect_valid(dir / "strip_out.glb");
  const tinygltf::Model m = load(dir / "strip_out.glb");
  EXPECT_EQ(m.meshes.at(0).primitives.at(0).mode, TINYGLTF_MODE_TRIANGLES);
}

// A sparse accessor moves vertex 2 up; a sparse accessor without a buffer
// view is zeros except where it says.
TEST(Gltf, SparseAccessorsApplied) {
  Doc d;
  const std::vector<float> p = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::vector<std::uint8_t> which = {2};
  const std::vector<float> moved = {0, 1, 0.75f};
  json sparse = {{"count", 1},
                 {"indices", {{"bufferView", d.view(which)}, {"componentType", 5121}}},
                 {"values", {{"bufferView", d.view(moved)}}}};
  const int pa = d.add(p, 5126, "VEC3", 3, 34962, {{"sparse", sparse}, {"min", {0, 0, 0}}, {"max", {1, 1, 0.75}}});
  d.j["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", pa}}}}})}}});
  test::TempDir dir;
  test::write_text(dir / "s.gltf", d.gltf());
  const MeshData m = read_mesh(dir / "s.gltf");
  ASSERT_EQ(m.V.rows(), 3);
  EXPECT_EQ(m.V(2, 2), 0.75);
  EXPECT_EQ(m.V(1, 0), 1);
  // All zeros but one value: three points (0,0,0), (0,0,0), (2,3,4) would be
  // degenerate, so two sparse values on a zero accessor.
  Doc z;
  const std::vector<std::uint16_t> at = {1, 2};
  const std::vector<float> vals = {2, 0, 0, 0, 3, 0};
  json zs = {{"count", 2}, {"indices", {{"bufferView", z.view(at)}, {"componentType", 5123}}}, {"values", {{"bufferView", z.view(vals)}}}};
  const int za = z.accessor({{"componentType", 5126}, {"type", "VEC3"}, {"count", 3}, {"sparse", zs}, {"min", {0, 0, 0}}, {"max", {2, 3, 0}}});
  z.j["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", za}}}}})}}});
  test::write_text(dir / "z.gltf", z.gltf());
  const MeshData zm = read_mesh(dir / "z.gltf");
  EXPECT_EQ(zm.V.row(0), Eigen::RowVector3d(0, 0, 0));
  EXPECT_EQ(zm.V.row(1), Eigen::RowVector3d(2, 0, 0));
  EXPECT_EQ(zm.V.row(2), Eigen::RowVector3d(0, 3, 0));
}

// KHR_mesh_quantization: normalized UNSIGNED_SHORT positions are c / 65535,
// normalized SHORT ones max(c / 32767, -1) (glTF 2.0 spec 3.11), then the
// node's transform applies.
TEST(Gltf, NormalizedIntegerPositions) {
  Doc d;
  const std::vector<std::uint16_t> p = {0, 0, 0, 0, 65535, 0, 0, 0, 0, 32768, 0, 0};  // padded to 8 bytes a vertex
  const int pa = d.accessor({{"bufferView", d.view(p, 34962, 8)}, {"componentType", 5123}, {"type", "VEC3"}, {"count", 3},
                             {"normalized", true}, {"min", {0, 0, 0}}, {"max", {65535, 32768, 0}}});
  const std::vector<std::int16_t> q = {0, 0, 0, 0, -32768, 0, 0, 0, 32767, 16384, 0, 0};
  const int qa = d.accessor({{"bufferView", d.view(q, 34962, 8)}, {"componentType", 5122}, {"type", "VEC3"}, {"count", 3},
                             {"normalized", true}, {"min", {-32768, 0, 0}}, {"max", {32767, 16384, 0}}});
  d.j["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", pa}}}}, {{"attributes", {{"POSITION", qa}}}}})}}});
  d.j["nodes"] = json::array({{{"mesh", 0}, {"scale", {2, 2, 2}}}});
  d.j["scenes"] = json::array({{{"nodes", {0}}}});
  d.j["extensionsUsed"] = {"KHR_mesh_quantization"};
  d.j["extensionsRequired"] = {"KHR_mesh_quantization"};
  test::TempDir dir;
  test::write_text(dir / "q.glb", d.glb());
  expect_valid(dir / "q.glb");
  const MeshFile file = read_mesh_file(dir / "q.glb");
  const MeshData& m = file.mesh;
  ASSERT_EQ(m.V.rows(), 6);
  EXPECT_DOUBLE_EQ(m.V(1, 0), 2.0);
  EXPECT_DOUBLE_EQ(m.V(2, 1), 2 * 32768.0 / 65535.0);
  EXPECT_DOUBLE_EQ(m.V(4, 0), -2.0);  // -32768 clamps to -1
  EXPECT_DOUBLE_EQ(m.V(5, 0), 2.0);
  EXPECT_DOUBLE_EQ(m.V(5, 1), 2 * 16384.0 / 32767.0);
  // Where each merged vertex and face came from.
  const GltfProvenance from = gltf_provenance(file);
  EXPECT_EQ(from.vertex_mesh, std::vector<int>(6, 0));
  EXPECT_EQ(from.vertex_primitive, (std::vector<int>{0, 0, 0, 1, 1, 1}));
  EXPECT_EQ(from.vertex_index, (std::vector<int>{0, 1, 2, 0, 1, 2}));
  EXPECT_EQ(from.face_primitive, (std::vector<int>{0, 1}));
  EXPECT_EQ(from.face_mesh, (std::vector<int>{0, 0}));
  const AtlasResult r = atlas(m);
  write_atlas_file(dir / "q_out.glb", file, r);
  expect_valid(dir / "q_out.glb", true);
  // The positions stay quantized (and the extension declared); the atlas is
  // a float set.
  const tinygltf::Model out = load(dir / "q_out.glb");
  EXPECT_EQ(out.extensionsUsed, std::vector<std::string>{"KHR_mesh_quantization"});
  EXPECT_EQ(out.extensionsRequired, std::vector<std::string>{"KHR_mesh_quantization"});
  const int components[2] = {5123, 5122};
  for (int k = 0; k < 2; ++k) {
    const tinygltf::Primitive& p = out.meshes.at(0).primitives.at(static_cast<std::size_t>(k));
    const tinygltf::Accessor& pos = out.accessors.at(static_cast<std::size_t>(p.attributes.at("POSITION")));
    EXPECT_EQ(pos.componentType, components[k]);
    EXPECT_TRUE(pos.normalized);
    EXPECT_EQ(out.accessors.at(static_cast<std::size_t>(p.attributes.at("TEXCOORD_0"))).componentType, 5126);
  }
}

// The atlas set may replace an existing one only where no texture reads it.
TEST(Gltf, ReplacingASetATextureReadsIsRefused) {
  RichAsset a = rich_asset();
  test::TempDir dir;
  test::write_text(dir / "in.glb", a.doc.glb());
  const MeshFile data = read_mesh_file(dir / "in.glb");
  const AtlasResult r = atlas(data);
  GltfWriteOptions o;
  o.texcoord_set = 0;
  try {
    write_gltf_atlas(dir / "out.glb", data, r, o);
    ADD_FAILURE() << "not refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("/meshes/0/primitives/0: TEXCOORD_0 is read by a texture of material 0"),
              std::string::npos) << e.what();
  }
  o.texcoord_set = 3;
  EXPECT_THROW(write_gltf_atlas(dir / "out.glb", data, r, o), Error);  // would leave a gap
  EXPECT_FALSE(std::filesystem::exists(dir / "out.glb"));
  o.texcoord_set = 0;
  o.replace_used_set = true;
  write_gltf_atlas(dir / "out.glb", data, r, o);
  expect_valid(dir / "out.glb");
  const tinygltf::Model m = load(dir / "out.glb");
  EXPECT_EQ(m.meshes[0].primitives[0].attributes.count("TEXCOORD_1"), 0u);
  // The same choice through the command line: refused (usage, exit 1, no
  // file) without --replace-uv-set, written into set 0 with it.
  const std::string cli = "atlas " + (dir / "in.glb") + " -o " + (dir / "cli.glb") + " -q --uv-set 0";
  const test::CliResult refused = test::run_cli(cli, dir);
  EXPECT_EQ(refused.code, 1) << refused.err;
  EXPECT_NE(refused.err.find("TEXCOORD_0 is read by a texture"), std::string::npos) << refused.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "cli.glb"));
  const test::CliResult replaced = test::run_cli(cli + " --replace-uv-set", dir);
  ASSERT_EQ(replaced.code, 0) << replaced.err;
  EXPECT_EQ(test::slurp(dir / "cli.glb"), test::slurp(dir / "out.glb"));  // the CLI is the library's call
}

// External buffer files beside the .gltf are read; a mesh without a glTF
// source written as .gltf is write_glb's document in JSON form.
TEST(Gltf, ExternalBufferAndPlainGltfOutput) {
  GenerateOptions g;
  g.rings = 5;
  const MeshData disk = generate_flat_disk(g);
  Doc d = simple_doc(disk);
  test::TempDir dir;
  json j = d.with_buffer(false);
  j["buffers"][0]["uri"] = "my%20data.bin";
  test::write_text(dir / "e.gltf", j.dump());
  test::write_text(dir / "my data.bin", d.bin);
  expect_valid(dir / "e.gltf");
  const MeshData m = read_mesh(dir / "e.gltf");
  EXPECT_EQ(m.F, disk.F);
  const AtlasResult r = atlas(disk);
  write_atlas_file(dir / "plain.gltf", MeshFile{disk}, r);
  expect_valid(dir / "plain.gltf");
  EXPECT_EQ(read_mesh(dir / "plain.gltf").F.rows(), disk.F.rows());
}

// Each malformed document: Error(Input) with the file and the JSON path, and
// the CLI writes nothing and exits 2.
struct Bad {
  const char* what;
  std::function<void(Doc&)> spoil;
  const char* message;
};

TEST(Gltf, MalformedDocumentsRefusedWithTheirJsonPath) {
  GenerateOptions g;
  g.rings = 2;
  const MeshData disk = generate_flat_disk(g);
  const std::vector<Bad> cases = {
      {"index out of range", [](Doc& d) { reinterpret_cast<std::uint32_t*>(&d.bin[d.j["bufferViews"][1]["byteOffset"].get<std::size_t>()])[4] = 71; },
       "/meshes/0/primitives/0/indices: index 71 out of range ("},
      {"accessor past its view", [](Doc& d) { d.j["accessors"][0]["count"] = 1000; }, "/accessors/0: 1000 elements of 12 bytes"},
      {"view past its buffer", [](Doc& d) { d.j["bufferViews"][0]["byteLength"] = 1 << 20; }, "/bufferViews/0: bytes 0 + 1048576 past the end"},
      {"buffer too short", [](Doc& d) { d.bin.resize(d.bin.size() - 8); }, "/buffers/0: byteLength"},
      {"positions as integers", [](Doc& d) { d.j["accessors"][0]["componentType"] = 5125; }, "/meshes/0/primitives/0/attributes/POSITION: accessor 0 is not a VEC3"},
      {"float indices", [](Doc& d) { d.j["accessors"][1]["componentType"] = 5126; }, "/meshes/0/primitives/0/indices: accessor 1 is not a SCALAR"},
      {"unknown component type", [](Doc& d) { d.j["accessors"][0]["componentType"] = 5000; }, "/accessors/0/componentType: 5000"},
      {"node loop", [](Doc& d) { d.j["nodes"] = json::array({{{"children", {1}}}, {{"children", {0}}, {"mesh", 0}}}); }, "/nodes/0: node loop"},
      {"two parents", [](Doc& d) { d.j["nodes"] = json::array({{{"children", {2}}}, {{"children", {2}}}, {{"mesh", 0}}}); }, "/nodes/1/children/0: node 2 already has parent 0"},
      {"mesh out of range", [](Doc& d) { d.j["nodes"][0]["mesh"] = 4; }, "/nodes/0/mesh: index 4 out of range"},
      {"missing buffer file", [](Doc& d) { d.j["buffers"] = json::array({{{"byteLength", d.bin.size()}, {"uri", "missing.bin"}}}); }, "/buffers/0/uri: cannot open buffer file"},
      {"meshopt", [](Doc& d) { d.j["extensionsRequired"] = {"EXT_meshopt_compression"}; d.j["extensionsUsed"] = {"EXT_meshopt_compression"}; }, "/extensionsRequired/0: EXT_meshopt_compression is not supported"},
      {"no version", [](Doc& d) { d.j.erase("asset"); }, "/asset/version: missing"},
  };
  test::TempDir dir;
  for (const Bad& b : cases) {
    SCOPED_TRACE(b.what);
    Doc d = simple_doc(disk);
    d.j["buffers"] = json::array();
    b.spoil(d);
    json j = d.j;
    if (j["buffers"].empty()) j["buffers"] = json::array({{{"byteLength", disk.V.rows() * 12 + disk.F.rows() * 12}, {"uri", "data:application/octet-stream;base64," + b64(d.bin)}}});
    test::write_text(dir / "bad.gltf", j.dump());
    try {
      read_mesh(dir / "bad.gltf");
      ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input);
      EXPECT_NE(std::string(e.what()).find(dir / "bad.gltf: "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(b.message), std::string::npos) << e.what();
    }
  }
  // Through the command line: exit 2, no output.
  Doc d = simple_doc(disk);
  d.j["accessors"][0]["count"] = 1000;
  test::write_text(dir / "bad.gltf", d.gltf());
  const test::CliResult c = test::run_cli("atlas " + (dir / "bad.gltf") + " -o " + (dir / "out.glb"), dir);
  EXPECT_EQ(c.code, 2) << c.err;
  EXPECT_NE(c.err.find("/accessors/0"), std::string::npos) << c.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.glb"));
}

TEST(Gltf, InvalidJsonAndGlbRefused) {
  EXPECT_THROW(read_gltf_from_memory("{\"asset\": ", "a.gltf"), Error);
  EXPECT_THROW(read_gltf_from_memory(std::string(100000, '['), "a.gltf"), Error);
  const char header[] = "glTF\x02\0\0\0\xff\xff\0\0";
  EXPECT_THROW(read_gltf_from_memory(std::string(header, sizeof header - 1), "a.glb"), Error);
  Doc d = simple_doc(generate_flat_disk(GenerateOptions{}));
  std::string glb = d.glb();
  glb.resize(glb.size() - 100);  // the BIN chunk cut short
  EXPECT_THROW(read_gltf_from_memory(glb, "a.glb"), Error);
}


// The Khronos sample models and glTF-Asset-Generator files that Debian's
// assimp-testmodels ships (scripts/install-deps.sh installs it); skipped
// without it.
namespace samples {

const std::string kDir = "/usr/share/assimp/models/glTF2/";

#define REQUIRE_SAMPLES()                                                                  \
  if (!std::filesystem::exists(kDir + "glTF-Sample-Models"))                              \
  GTEST_SKIP() << kDir << " is missing: install Debian's assimp-testmodels (scripts/install-deps.sh)"

// The triangles as position triples, rotated to start at the smallest
// corner (orientation kept), sorted: the drawn surface, however stored.
std::vector<std::array<double, 9>> drawn(const MeshData& m) {
  std::vector<std::array<double, 9>> out;
  for (int f = 0; f < m.F.rows(); ++f) {
    std::array<std::array<double, 3>, 3> c;
    for (int k = 0; k < 3; ++k) c[k] = {m.V(m.F(f, k), 0), m.V(m.F(f, k), 1), m.V(m.F(f, k), 2)};
    const int s = static_cast<int>(std::min_element(c.begin(), c.end()) - c.begin());
    std::array<double, 9> t;
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) t[3 * k + d] = c[(s + k) % 3][d];
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(GltfSamples, AssetGeneratorStripsAndFansDrawTheirList) {
  REQUIRE_SAMPLES();
  const std::string d = kDir + "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_";
  // One quad as strip (04), fan (05), list (06), each also indexed (11, 12,
  // 13). The generator splits the fan's quad along the other diagonal, so
  // the fan is compared by what it covers: the same total vector area (both
  // triangles facing +z) over the same corners.
  const MeshData list = read_mesh(d + "06.gltf");
  ASSERT_EQ(list.F.rows(), 2);
  EXPECT_EQ(drawn(read_mesh(d + "04.gltf")), drawn(list));
  EXPECT_EQ(drawn(read_mesh(d + "13.gltf")), drawn(list));
  EXPECT_EQ(drawn(read_mesh(d + "11.gltf")), drawn(read_mesh(d + "04.gltf")));
  EXPECT_EQ(drawn(read_mesh(d + "12.gltf")), drawn(read_mesh(d + "05.gltf")));
  auto vector_area = [](const MeshData& m) {
    Eigen::Vector3d s = Eigen::Vector3d::Zero();
    for (int f = 0; f < m.F.rows(); ++f) {
      const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
      const Eigen::Vector3d n = (b - a).cross(c - a);
      EXPECT_GT(n.z(), 0) << "face " << f << " faces away";
      s += n / 2;
    }
    return s;
  };
  const MeshData fan = read_mesh(d + "05.gltf");
  ASSERT_EQ(fan.F.rows(), 2);
  EXPECT_TRUE(vector_area(fan).isApprox(vector_area(list)));
}

// Real assets (textured box, morph targets with an animation, a skin with
// its animation, cameras, many nodes and meshes) written back with a real
// atlas: valid, everything outside the meshes unchanged, one more TEXCOORD.
TEST(GltfSamples, AtlasWrittenBackIntoSampleModels) {
  REQUIRE_SAMPLES();
  test::TempDir dir;
  int k = 0;
  for (const std::string f : {"BoxTextured-glTF-Binary/BoxTextured.glb",
                              "glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf",
                              "simple_skin/simple_skin.gltf", "cameras/Cameras.gltf",
                              "2CylinderEngine-glTF-Binary/2CylinderEngine.glb", "draco/2CylinderEngine.gltf"}) {
    SCOPED_TRACE(f);
    const MeshFile file = read_mesh_file(kDir + f);
    const MeshData& data = file.mesh;
    const AtlasResult r = atlas(data);
    // No fold and no overlap by `metrics`' count on the faces as written (the
    // engine has vertices where two fans of one chart meet: their corners
    // must not round into each other's triangles).
    const UvAtlasMetrics um = test::measure_atlas(data.V, data.F, r);
    EXPECT_EQ(um.flipped_triangles, 0);
    EXPECT_EQ(um.overlapping_triangles, 0);
    const std::string out = dir / ("out" + std::to_string(k++) + (f.back() == 'b' ? ".glb" : ".gltf"));
    write_atlas_file(out, file, r);
    expect_valid(out);
    if (f.compare(0, 6, "draco/") == 0) {
      // Decoded and written uncompressed: as many triangles as the
      // document's index accessors announce (its encoder dropped the
      // degenerate ones the uncompressed copy still has), in the box of the
      // uncompressed copy of the model (to Draco's quantization).
      const json source = json::parse(test::slurp(kDir + f));
      std::int64_t announced = 0;
      for (const json& m : source["meshes"])
        for (const json& p : m["primitives"])
          if (p.value("mode", 4) == 4) announced += source["accessors"][p["indices"].get<std::size_t>()]["count"].get<std::int64_t>() / 3;
      EXPECT_EQ(data.F.rows(), announced);
      const MeshData plain = read_mesh(kDir + "2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
      const double diagonal = (plain.V.colwise().maxCoeff() - plain.V.colwise().minCoeff()).norm();
      EXPECT_LT((data.V.colwise().maxCoeff() - plain.V.colwise().maxCoeff()).norm(), 1e-3 * diagonal);
      EXPECT_LT((data.V.colwise().minCoeff() - plain.V.colwise().minCoeff()).norm(), 1e-3 * diagonal);
      EXPECT_TRUE(load(out).extensionsRequired.empty());
      continue;  // the source's accessors have no data of their own to compare below
    }
    const tinygltf::Model in = load(kDir + f), got = load(out);
    ASSERT_EQ(got.meshes.size(), in.meshes.size());
    EXPECT_EQ(got.nodes, in.nodes);
    EXPECT_EQ(got.materials, in.materials);
    // Animations and skins as they were, up to the accessors' numbers
    // (renumbered when the old ones are dropped): the same data.
    ASSERT_EQ(got.animations.size(), in.animations.size());
    for (std::size_t i = 0; i < in.animations.size(); ++i) {
      tinygltf::Animation renumbered = in.animations[i];
      ASSERT_EQ(got.animations[i].samplers.size(), renumbered.samplers.size());
      for (std::size_t j = 0; j < renumbered.samplers.size(); ++j) {
        const tinygltf::AnimationSampler &a = renumbered.samplers[j], &b = got.animations[i].samplers[j];
        EXPECT_EQ(accessor_bytes(in, a.input), accessor_bytes(got, b.input));
        EXPECT_EQ(accessor_bytes(in, a.output), accessor_bytes(got, b.output));
        renumbered.samplers[j].input = b.input, renumbered.samplers[j].output = b.output;
      }
      EXPECT_EQ(got.animations[i], renumbered);
    }
    ASSERT_EQ(got.skins.size(), in.skins.size());
    for (std::size_t i = 0; i < in.skins.size(); ++i) {
      tinygltf::Skin renumbered = in.skins[i];
      EXPECT_EQ(accessor_bytes(in, renumbered.inverseBindMatrices), accessor_bytes(got, got.skins[i].inverseBindMatrices));
      renumbered.inverseBindMatrices = got.skins[i].inverseBindMatrices;
      EXPECT_EQ(got.skins[i], renumbered);
    }
    EXPECT_EQ(got.cameras, in.cameras);
    EXPECT_EQ(got.textures, in.textures);
    std::size_t faces = 0;
    for (std::size_t m = 0; m < in.meshes.size(); ++m)
      for (std::size_t p = 0; p < in.meshes[m].primitives.size(); ++p) {
        const auto& a = in.meshes[m].primitives[p].attributes;
        const auto& b = got.meshes[m].primitives[p].attributes;
        EXPECT_EQ(b.size(), a.size() + 1);
        for (const auto& [name, unused] : a) EXPECT_TRUE(b.count(name)) << name;
        faces += got.accessors.at(static_cast<std::size_t>(got.meshes[m].primitives[p].indices)).count / 3;
      }
    EXPECT_EQ(faces, static_cast<std::size_t>(data.F.rows()));
  }
}

TEST(GltfSamples, InvalidSamplesRefused) {
  REQUIRE_SAMPLES();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"IndexOutOfRange/IndexOutOfRange.gltf", "/meshes/0/primitives/0/indices: index 255 out of range (24 vertices)"},
      {"RecursiveNodes/RecursiveNodes.gltf", "node loop"},
      {"MissingBin/BoxTextured.gltf", "/buffers/0/uri: cannot open buffer file"},
      {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "/meshes/0/primitives/0/attributes/POSITION: vertex 0 is not finite"},
  };
  for (const auto& [f, message] : cases) {
    try {
      read_mesh(kDir + f);
      ADD_FAILURE() << f << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input);
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
}

}  // namespace samples
}  // namespace
}  // namespace intrinsic
