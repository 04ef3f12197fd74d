// The glTF writer drops what the rewritten document no longer references
// (src/io/gltf_prune.cpp): sizes are checked against what the new data alone
// must take (counted here from the atlas), a second round trip must not grow
// the file, every kept object must still be what it was (bytes read back
// through the output's own references), and a document with an extension the
// writer does not know is kept whole.
#include <gtest/gtest.h>

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

// A GLB file's JSON and binary chunk.
struct Glb {
  json j;
  std::string bin;
};

Glb split_glb(const std::string& file) {
  std::uint32_t json_length = 0, bin_length = 0;
  std::memcpy(&json_length, &file[12], 4);
  Glb g;
  g.j = json::parse(file.substr(20, json_length));
  if (file.size() > 20 + json_length + 8) {
    std::memcpy(&bin_length, &file[20 + json_length], 4);
    g.bin = file.substr(28 + json_length, bin_length);
  }
  return g;
}

// The bytes of buffer view v of a GLB.
std::string view_bytes(const Glb& g, int v) {
  const json& view = g.j["bufferViews"][static_cast<std::size_t>(v)];
  return g.bin.substr(view.value("byteOffset", std::size_t{0}), view["byteLength"].get<std::size_t>());
}

// The 1x1 PNG of rich_asset's image, as bytes.
std::string png_bytes() {
  const std::string text = "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNk+M9QDwADhgGAWjR9awAAAABJRU5ErkJggg==";
  const std::string t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (const char c : text) {
    if (c == '=') break;
    acc = acc << 6 | static_cast<std::uint32_t>(t.find(c));
    if ((bits += 6) >= 8) out += static_cast<char>(acc >> (bits -= 8) & 0xFF);
  }
  return out;
}

// Distinct (vertex, atlas coordinate) pairs over the faces: the output's
// vertex count.
std::size_t split_vertices(const AtlasResult& r) {
  std::set<std::pair<int, int>> pairs;
  for (int f = 0; f < r.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) pairs.insert({r.F(f, k), r.FUV(f, k)});
  return pairs.size();
}

// A disk has no seam: the output is the input plus one float VEC2 per
// vertex, and writing the output's atlas into itself again keeps its size.
TEST(GltfPrune, RoundTripGrowsOnlyByTheNewSet) {
  GenerateOptions g;
  g.rings = 8;
  const MeshData disk = generate_flat_disk(g);
  test::TempDir dir;
  test::write_text(dir / "in.glb", simple_doc(disk).glb());
  const MeshFile data = read_mesh_file(dir / "in.glb");
  const AtlasResult r = atlas(data);
  const std::size_t n = split_vertices(r);
  const GltfWriteResult w = write_gltf_atlas(dir / "out.glb", data, r);
  EXPECT_TRUE(w.pruned);
  EXPECT_EQ(w.accessors_dropped, 2);  // the old positions and indices
  EXPECT_EQ(w.views_dropped, 2);
  EXPECT_TRUE(w.note.empty());
  expect_valid(dir / "out.glb", true);
  const Glb in = split_glb(test::slurp(dir / "in.glb")), out = split_glb(test::slurp(dir / "out.glb"));
  // Positions (12 bytes), the atlas (8 bytes) per output vertex, 4-byte
  // indices per corner; at most 3 bytes of alignment before each of the
  // three views.
  const std::size_t needed = n * (12 + 8) + static_cast<std::size_t>(disk.F.rows()) * 3 * 4;
  EXPECT_GE(out.bin.size(), needed);
  EXPECT_LE(out.bin.size(), needed + 3 * 3);
  EXPECT_EQ(out.j["accessors"].size(), 3u);
  EXPECT_EQ(out.j["bufferViews"].size(), 3u);
  if (n == static_cast<std::size_t>(disk.V.rows())) EXPECT_LE(out.bin.size(), in.bin.size() + 8 * n + 3 * 3);
  // The atlas written into its own set again: the same size, not more.
  const MeshFile again = read_mesh_file(dir / "out.glb");
  GltfWriteOptions o;
  o.texcoord_set = 0;
  write_gltf_atlas(dir / "again.glb", again, atlas(again), o);
  expect_valid(dir / "again.glb", true);
  EXPECT_EQ(test::slurp(dir / "again.glb").size(), test::slurp(dir / "out.glb").size());
}

// Objects outside the primitives keep their data through the renumbering:
// the skin's matrices, the animation's sampler (its output sparse, with
// three views of its own), an image stored in a buffer view.
TEST(GltfPrune, EveryKeptObjectKeepsItsBytes) {
  RichAsset a = rich_asset();
  Doc& d = a.doc;
  const std::string png = png_bytes();
  const int image_view = d.view(std::vector<char>(png.begin(), png.end()));
  d.j["images"] = json::array({{{"bufferView", image_view}, {"mimeType", "image/png"}}});
  const std::vector<float> base = {0, 0, 0, 0, 0, 0}, moved = {0, 2, 0};
  const std::vector<std::uint8_t> which = {1};
  const int out_acc = d.accessor({{"bufferView", d.view(base)}, {"componentType", 5126}, {"type", "VEC3"}, {"count", 2},
                                  {"sparse", {{"count", 1},
                                              {"indices", {{"bufferView", d.view(which)}, {"componentType", 5121}}},
                                              {"values", {{"bufferView", d.view(moved)}}}}}});
  d.j["animations"][0]["samplers"][0]["output"] = out_acc;
  test::TempDir dir;
  test::write_text(dir / "in.glb", d.glb());
  expect_valid(dir / "in.glb");
  const MeshFile data = read_mesh_file(dir / "in.glb");
  const GltfWriteResult w = write_gltf_atlas(dir / "out.glb", data, atlas(data));
  ASSERT_TRUE(w.pruned);
  // 6 attributes, indices, 2 target attributes, and the animation's old output.
  EXPECT_EQ(w.accessors_dropped, 10);
  EXPECT_EQ(w.views_dropped, 10);
  expect_valid(dir / "out.glb", true);
  const Glb g = split_glb(test::slurp(dir / "out.glb"));
  EXPECT_EQ(view_bytes(g, g.j["images"][0]["bufferView"].get<int>()), png);
  const json& ibm = g.j["accessors"][g.j["skins"][0]["inverseBindMatrices"].get<std::size_t>()];
  const std::vector<float> identity2 = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  EXPECT_EQ(view_bytes(g, ibm["bufferView"].get<int>()).substr(0, 64 * 2),
            std::string(reinterpret_cast<const char*>(identity2.data()), 128));
  const json& sampler = g.j["animations"][0]["samplers"][0];
  const json& input = g.j["accessors"][sampler["input"].get<std::size_t>()];
  const std::vector<float> times = {0, 1};
  EXPECT_EQ(view_bytes(g, input["bufferView"].get<int>()), std::string(reinterpret_cast<const char*>(times.data()), 8));
  const json& output = g.j["accessors"][sampler["output"].get<std::size_t>()];
  EXPECT_EQ(view_bytes(g, output["bufferView"].get<int>()), std::string(reinterpret_cast<const char*>(base.data()), 24));
  EXPECT_EQ(view_bytes(g, output["sparse"]["indices"]["bufferView"].get<int>()), std::string(1, '\1'));
  EXPECT_EQ(view_bytes(g, output["sparse"]["values"]["bufferView"].get<int>()),
            std::string(reinterpret_cast<const char*>(moved.data()), 12));
}

// An extension the writer does not know may reference accessors or views
// where the walk does not look: nothing is dropped, and the result says why.
TEST(GltfPrune, UnknownExtensionKeepsEverything) {
  RichAsset a = rich_asset();
  a.doc.j["extensionsUsed"] = {"EXT_example_refs"};
  a.doc.j["nodes"][0]["extensions"] = {{"EXT_example_refs", {{"accessor", 3}}}};
  test::TempDir dir;
  test::write_text(dir / "in.glb", a.doc.glb());
  const MeshFile data = read_mesh_file(dir / "in.glb");
  const GltfWriteResult w = write_gltf_atlas(dir / "out.glb", data, atlas(data));
  EXPECT_FALSE(w.pruned);
  EXPECT_NE(w.note.find("EXT_example_refs"), std::string::npos) << w.note;
  expect_valid(dir / "out.glb");
  const Glb g = split_glb(test::slurp(dir / "out.glb"));
  // The old accessors stay at their indices, the new ones come after them.
  ASSERT_GT(g.j["accessors"].size(), a.doc.j["accessors"].size());
  for (std::size_t i = 0; i < a.doc.j["accessors"].size(); ++i)
    EXPECT_EQ(g.j["accessors"][i]["count"], a.doc.j["accessors"][i]["count"]) << i;
  // Asked not to prune: the same.
  GltfWriteOptions o;
  o.prune = false;
  RichAsset plain = rich_asset();
  test::write_text(dir / "plain.glb", plain.doc.glb());
  const MeshFile pd = read_mesh_file(dir / "plain.glb");
  const GltfWriteResult kept = write_gltf_atlas(dir / "kept.glb", pd, atlas(pd), o);
  EXPECT_FALSE(kept.pruned);
  EXPECT_TRUE(kept.note.empty());
  EXPECT_GT(split_glb(test::slurp(dir / "kept.glb")).j["accessors"].size(), plain.doc.j["accessors"].size());
}

}  // namespace
}  // namespace intrinsic
