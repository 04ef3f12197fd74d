// KHR_draco_mesh_compression (src/io/gltf_draco.cpp): a document is built
// here with Draco's own encoder (no quantization, so the positions must come
// back exactly), read, atlased and written back uncompressed; every
// triangle must be the source's, every output corner must carry the source
// attributes of its position, and a broken stream is refused with its JSON
// path.
#include <gtest/gtest.h>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include <map>
#include <set>

#include "gltf_support.h"
#include "intrinsic/atlas.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/gltf.h"
#include "intrinsic/io.h"

namespace intrinsic {
namespace {

using nlohmann::json;
using namespace gltf_test;

struct DracoDoc {
  MeshData source;
  std::vector<float> texcoord;  // per source vertex
  Doc doc;
  int stream_view = -1;
};

// The torus as a Draco stream (positions and one texture coordinate set per
// vertex) inside a glTF document.
DracoDoc draco_doc() {
  DracoDoc d;
  GenerateOptions g;
  g.rings = 8;
  d.source = generate_torus(g);
  const MeshData& m = d.source;
  for (int v = 0; v < m.V.rows(); ++v) d.texcoord.push_back(0.01f * v), d.texcoord.push_back(1 - 0.02f * v);
  const std::vector<float> p = positions(m);
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(static_cast<int>(m.F.rows()));
  const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int tex = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
  for (int f = 0; f < m.F.rows(); ++f) {
    const auto corner = [&](const std::vector<float>& a, int k, int n) { return &a[static_cast<std::size_t>(m.F(f, k) * n)]; };
    builder.SetAttributeValuesForFace(pos, draco::FaceIndex(f), corner(p, 0, 3), corner(p, 1, 3), corner(p, 2, 3));
    builder.SetAttributeValuesForFace(tex, draco::FaceIndex(f), corner(d.texcoord, 0, 2), corner(d.texcoord, 1, 2),
                                      corner(d.texcoord, 2, 2));
  }
  const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  draco::Encoder encoder;
  encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
  draco::EncoderBuffer out;
  const draco::Status s = encoder.EncodeMeshToBuffer(*mesh, &out);
  EXPECT_TRUE(s.ok()) << s.error_msg_string();
  const int points = static_cast<int>(mesh->num_points());
  Doc& doc = d.doc;
  d.stream_view = doc.view(std::vector<char>(out.data(), out.data() + out.size()));
  const int pa = doc.accessor(min_max(p, {{"componentType", 5126}, {"type", "VEC3"}, {"count", points}}));
  const int ta = doc.accessor({{"componentType", 5126}, {"type", "VEC2"}, {"count", points}});
  const int ia = doc.accessor({{"componentType", 5125}, {"type", "SCALAR"}, {"count", 3 * m.F.rows()}});
  const json draco_ext = {{"bufferView", d.stream_view},
                          {"attributes", {{"POSITION", mesh->attribute(pos)->unique_id()},
                                          {"TEXCOORD_0", mesh->attribute(tex)->unique_id()}}}};
  doc.j["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", pa}, {"TEXCOORD_0", ta}}},
                                                               {"indices", ia},
                                                               {"extensions", {{"KHR_draco_mesh_compression", draco_ext}}}}})}}});
  doc.j["nodes"] = json::array({{{"mesh", 0}}});
  doc.j["scenes"] = json::array({{{"nodes", {0}}}});
  doc.j["scene"] = 0;
  doc.j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  doc.j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  return d;
}

// A triangle as its three corner positions, starting at the smallest
// (rotation kept, so the winding counts).
using Corners = std::array<std::array<float, 3>, 3>;
std::vector<Corners> triangles(const MeshData& m) {
  std::vector<Corners> out;
  for (int f = 0; f < m.F.rows(); ++f) {
    Corners c;
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) c[k][i] = static_cast<float>(m.V(m.F(f, k), i));
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    out.push_back(c);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(GltfDraco, DecodedAtlasedAndWrittenUncompressed) {
  DracoDoc d = draco_doc();
  test::TempDir dir;
  test::write_text(dir / "in.glb", d.doc.glb());
  expect_valid(dir / "in.glb");
  const MeshFile file = read_mesh_file(dir / "in.glb");
  const MeshData& data = file.mesh;
  ASSERT_EQ(data.F.rows(), d.source.F.rows());
  EXPECT_EQ(triangles(data), triangles(d.source));  // no quantization: exact as floats
  const AtlasResult r = atlas(data);
  const GltfWriteResult w = write_gltf_atlas(dir / "out.glb", file, r);
  EXPECT_TRUE(w.pruned);
  expect_valid(dir / "out.glb", true);
  const tinygltf::Model m = load(dir / "out.glb");
  EXPECT_TRUE(m.extensionsUsed.empty());
  EXPECT_TRUE(m.extensionsRequired.empty());
  const tinygltf::Primitive& p = m.meshes.at(0).primitives.at(0);
  EXPECT_TRUE(p.extensions.empty());
  ASSERT_TRUE(p.attributes.count("TEXCOORD_1"));
  // Every output corner: the source's texture coordinate of the vertex at
  // its position (the torus's vertices are all apart).
  std::map<std::string, std::string> texcoord_at;
  const std::vector<float> source_positions = positions(d.source);
  for (int v = 0; v < d.source.V.rows(); ++v)
    texcoord_at[bytes_of(source_positions, static_cast<std::size_t>(v), 3)] = bytes_of(d.texcoord, static_cast<std::size_t>(v), 2);
  const std::size_t corners = m.accessors.at(static_cast<std::size_t>(p.indices)).count;
  ASSERT_EQ(corners, static_cast<std::size_t>(3 * d.source.F.rows()));
  for (std::size_t c = 0; c < corners; ++c) {
    const std::uint32_t o = index_of(m, p.indices, c);
    const std::string pos = element(m, p.attributes.at("POSITION"), o);
    ASSERT_TRUE(texcoord_at.count(pos)) << c;
    EXPECT_EQ(element(m, p.attributes.at("TEXCOORD_0"), o), texcoord_at[pos]) << c;
  }
  // No byte of the Draco stream (nor of its decoded copy) is left: the
  // output holds per vertex a position and two float pairs, per corner a
  // 4-byte index, and at most 3 bytes of alignment before each of 4 views.
  std::set<std::pair<int, int>> split;
  for (int f = 0; f < r.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) split.insert({r.F(f, k), r.FUV(f, k)});
  const std::size_t needed = split.size() * (12 + 8 + 8) + corners * 4;
  ASSERT_EQ(m.buffers.size(), 1u);
  EXPECT_GE(m.buffers[0].data.size(), needed);
  EXPECT_LE(m.buffers[0].data.size(), needed + 4 * 3 + 3);
}

TEST(GltfDraco, BrokenStreamRefusedWithItsJsonPath) {
  const std::string at = "/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression";
  auto refused = [&](const Doc& doc, const std::string& where) {
    try {
      read_gltf_from_memory(doc.glb(), "bad.glb");
      ADD_FAILURE() << "not refused: " << where;
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input);
      EXPECT_NE(std::string(e.what()).find("bad.glb: " + where), std::string::npos) << e.what();
    }
  };
  DracoDoc d = draco_doc();
  const json& view = d.doc.j["bufferViews"][static_cast<std::size_t>(d.stream_view)];
  Doc garbled = d.doc;
  for (std::size_t i = 8; i < view["byteLength"].get<std::size_t>(); ++i)
    garbled.bin[view["byteOffset"].get<std::size_t>() + i] = static_cast<char>(0xA5 ^ i);
  refused(garbled, at + ": not a Draco mesh");
  Doc wrong_id = d.doc;
  wrong_id.j["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["TEXCOORD_0"] = 99;
  refused(wrong_id, at + "/attributes/TEXCOORD_0: no Draco attribute with id 99");
  Doc wrong_count = d.doc;
  wrong_count.j["accessors"][2]["count"] = 3;
  refused(wrong_count, "/meshes/0/primitives/0/indices");
}

}  // namespace
}  // namespace intrinsic
