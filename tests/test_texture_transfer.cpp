// Texture transfer for whole assets (docs/textures.md): re-atlasing the
// generated fragmented asset, whose texture is a known function of the
// surface point, must give a texture that is that function in the new layout
// (texel by texel), must look the same rendered before and after, must be a
// valid glTF; bad images and samplers are refused with nothing written.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>

#include "cli_support.h"
#include "intrinsic/atlas.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/generate.h"
#include "intrinsic/gltf.h"
#include "intrinsic/io.h"
#include "intrinsic/texture_transfer.h"
#include "test_texture_transfer_support.h"

namespace intrinsic {
namespace {

using test::Drawn;
using test::TempDir;
using nlohmann::json;

constexpr double kLipschitz = 0.75;  // textured_asset_colour's bound per unit of length (generate.h)

TexturedAssetOptions small_asset() {
  TexturedAssetOptions o;
  o.cells = 16;
  o.chart_cells = 1;  // 1,536 charts of two triangles
  o.texture_size = 1024;
  return o;
}

// Re-atlases `input` into `output` (set 0 replaced, textures baked).
TextureTransferReport transfer(const std::string& input, const std::string& output, int size = 512) {
  const MeshFile m = read_mesh_file(input);
  const AtlasResult r = atlas(m, AtlasOptions{});
  GltfWriteOptions g;
  g.texcoord_set = 0;
  TextureTransferOptions t;
  t.enabled = true;
  t.size = size;
  return write_atlas_with_textures(output, m, r, g, t);
}

// Frobenius norm of the map from texel space to the surface over triangle f
// (texels of a size x size image): how far one texel step moves on the surface.
double texel_step(const Drawn& d, int f, int size) {
  Eigen::Matrix<double, 3, 2> E;
  Eigen::Matrix2d T;
  for (int k = 0; k < 2; ++k) {
    E.col(k) = (d.V.row(d.F(f, k + 1)) - d.V.row(d.F(f, 0))).transpose();
    T.col(k) = (d.UV.row(d.F(f, k + 1)) - d.UV.row(d.F(f, 0))).transpose() * size;
  }
  return std::abs(T.determinant()) < 1e-12 ? 0 : (E * T.inverse()).norm();
}

// Every texel whose centre lies inside a triangle of the new layout holds
// the asset's colour at the surface point of that centre, to within what
// sampling both images can change it by: 8-bit rounding twice (3 codes),
// plus the colour's change over a texel of the new image (supersampling)
// and two texels of the old one (bilinear lookup reaching the neighbours).
TEST(AssetTextureTransfer, BakedTexelsAreTheAnalyticColourOfTheirSurfacePoint) {
  TempDir dir;
  const TexturedAsset asset = generate_textured_asset(small_asset());
  write_textured_asset(dir / "in.glb", asset);
  const TextureTransferReport rep = transfer(dir / "in.glb", dir / "out.glb");
  ASSERT_EQ(rep.baked.size(), 1u);
  EXPECT_EQ(rep.baked[0].slot, "pbrMetallicRoughness/baseColorTexture");
  const Drawn before = test::drawn(dir / "in.glb"), after = test::drawn(dir / "out.glb");
  ASSERT_EQ(after.texture.width, 512);
  double old_step = 0;
  for (int f = 0; f < before.F.rows(); ++f) old_step = std::max(old_step, texel_step(before, f, 1024));
  const int W = after.texture.width, H = after.texture.height;
  long checked = 0;
  double worst = 0;  // error over allowance
  for (int f = 0; f < after.F.rows(); ++f) {
    const double allowance = 3.0 / 255 + kLipschitz * std::sqrt(3.0) * (texel_step(after, f, W) + 2 * old_step);
    Eigen::Vector2d t[3];
    for (int k = 0; k < 3; ++k) t[k] = Eigen::Vector2d(after.UV(after.F(f, k), 0) * W, (1 - after.UV(after.F(f, k), 1)) * H);
    const double area = (t[1] - t[0]).x() * (t[2] - t[0]).y() - (t[1] - t[0]).y() * (t[2] - t[0]).x();
    if (std::abs(area) < 1e-12) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({t[0].x(), t[1].x(), t[2].x()}))));
    const int x1 = std::min(W - 1, static_cast<int>(std::ceil(std::max({t[0].x(), t[1].x(), t[2].x()}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({t[0].y(), t[1].y(), t[2].y()}))));
    const int y1 = std::min(H - 1, static_cast<int>(std::ceil(std::max({t[0].y(), t[1].y(), t[2].y()}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2d c(x + 0.5, y + 0.5);
        double b[3];
        for (int k = 0; k < 3; ++k) {
          const Eigen::Vector2d p = t[(k + 1) % 3], q = t[(k + 2) % 3];
          b[k] = ((q - p).x() * (c - p).y() - (q - p).y() * (c - p).x()) / area;
        }
        if (std::min({b[0], b[1], b[2]}) < 0) continue;
        Eigen::Vector3d point = Eigen::Vector3d::Zero();
        for (int k = 0; k < 3; ++k) point += b[k] * after.V.row(after.F(f, k)).transpose();
        const Eigen::Vector3d want = textured_asset_colour(point);
        for (int q = 0; q < 3; ++q)
          worst = std::max(worst, std::abs(after.texture.pixel(x, y)[q] / 255.0 - want[q]) - allowance);
        ++checked;
      }
  }
  EXPECT_GT(checked, 0.8 * rep.baked[0].texels_covered);
  EXPECT_LE(worst, 0.0) << "a texel differs from the analytic colour by more than its allowance";
}

TEST(AssetTextureTransfer, GeneratedAssetLooksTheSameBeforeAndAfter) {
  TempDir dir;
  write_textured_asset(dir / "in.glb", generate_textured_asset(small_asset()));
  transfer(dir / "in.glb", dir / "out.glb", 1024);
  const test::LookDifference d = test::look_difference(test::drawn(dir / "in.glb"), test::drawn(dir / "out.glb"), 400);
  EXPECT_GT(d.pixels_away, d.pixels / 4);
  EXPECT_LT(d.mean, 0.02);
  EXPECT_LT(d.mean_away, 0.01);
}

// A real textured sample (Khronos BoxTextured, its PNG in a file beside the
// .gltf): one material, six charts.
TEST(AssetTextureTransfer, KhronosBoxLooksTheSameBeforeAndAfter) {
  const std::string box = "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf";
  if (!std::filesystem::exists(box)) GTEST_SKIP() << box << " is absent (Debian package assimp-testmodels)";
  TempDir dir;
  const TextureTransferReport rep = transfer(box, dir / "out.glb", 512);
  ASSERT_EQ(rep.baked.size(), 1u);
  EXPECT_EQ(rep.baked[0].material_name, "Texture");
  // The box's u runs over [0, 6] through a MIRRORED_REPEAT sampler, the
  // renderer only repeats: the reference gets the six mirrored copies side by
  // side and u / 6.
  Drawn before = test::drawn(box);
  ASSERT_LE(before.UV.col(0).maxCoeff(), 6.0);
  ASSERT_GE(before.UV.col(0).minCoeff(), 0.0);
  const Image& src = before.texture;
  Image wide(6 * src.width, src.height);
  for (int y = 0; y < src.height; ++y)
    for (int x = 0; x < wide.width; ++x) {
      const int k = x / src.width, sx = k % 2 ? src.width - 1 - x % src.width : x % src.width;
      std::copy_n(src.pixel(sx, y), 3, wide.pixel(x, y));
    }
  before.texture = wide;
  before.UV.col(0) /= 6;
  const test::LookDifference d = test::look_difference(before, test::drawn(dir / "out.glb"), 400);
  EXPECT_LT(d.mean, 0.02);
  EXPECT_LT(d.mean_away, 0.01);
}

// The written document is valid glTF; the report names the bake; the old
// transform extension is gone from the slot.
TEST(AssetTextureTransfer, CliWritesAValidDocumentAndReportsTheBake) {
  TempDir dir;
  write_textured_asset(dir / "in.glb", generate_textured_asset(small_asset()));
  const auto r = test::run_cli("atlas " + (dir / "in.glb") + " -o " + (dir / "out.glb") +
                                   " --uv-set 0 --transfer-textures --texture-size 256 -q --report " + (dir / "r.json"),
                               dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(test::slurp(dir / "r.json"));
  ASSERT_EQ(j["textures"]["baked"].size(), 1u);
  EXPECT_EQ(j["textures"]["baked"][0]["width"], 256);
  EXPECT_GT(j["textures"]["baked"][0]["texels_covered"].get<long>(), 256 * 256 / 4);
  const tinygltf::Model m = gltf_test::load(dir / "out.glb");
  const int tex = m.materials.at(0).pbrMetallicRoughness.baseColorTexture.index;
  EXPECT_EQ(m.samplers.at(static_cast<std::size_t>(m.textures.at(static_cast<std::size_t>(tex)).sampler)).wrapS, 33071);
  gltf_test::expect_valid(dir / "out.glb");
}

TEST(AssetTextureTransfer, ReplacingAUsedSetWithoutTransferNamesTheFlag) {
  TempDir dir;
  write_textured_asset(dir / "in.glb", generate_textured_asset(small_asset()));
  const auto r = test::run_cli("atlas " + (dir / "in.glb") + " -o " + (dir / "out.glb") + " --uv-set 0", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--transfer-textures"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.glb"));
}

// The generated asset as a .gltf whose JSON `edit` changes.
void write_edited(const std::string& path, const std::function<void(json&)>& edit) {
  TempDir tmp;
  write_textured_asset(tmp / "a.gltf", generate_textured_asset(small_asset()));
  json j = json::parse(test::slurp(tmp / "a.gltf"));
  edit(j);
  test::write_text(path, j.dump());
}

TEST(AssetTextureTransfer, UnreadableImageIsRefusedNamingImageAndMaterial) {
  TempDir dir;
  write_edited(dir / "in.gltf", [](json& j) {
    j["images"][0] = {{"uri", "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAA"}, {"name", "broken"}};
  });
  const auto r = test::run_cli("atlas " + (dir / "in.gltf") + " -o " + (dir / "out.gltf") +
                                   " --uv-set 0 --transfer-textures --report " + (dir / "r.json"),
                               dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("image 0 'broken'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("material 0 'textured'"), std::string::npos) << r.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{"in.gltf"});
}

TEST(AssetTextureTransfer, MissingImageFileIsRefused) {
  TempDir dir;
  write_edited(dir / "in.gltf", [](json& j) { j["images"][0] = {{"uri", "absent.png"}}; });
  const auto r = test::run_cli("atlas " + (dir / "in.gltf") + " -o " + (dir / "out.gltf") + " --uv-set 0 --transfer-textures", dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("absent.png"), std::string::npos) << r.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{"in.gltf"});
}

TEST(AssetTextureTransfer, UnknownWrapModeIsRefused) {
  TempDir dir;
  write_edited(dir / "in.gltf", [](json& j) { j["samplers"][0]["wrapS"] = 1234; });
  const auto r = test::run_cli("atlas " + (dir / "in.gltf") + " -o " + (dir / "out.gltf") + " --uv-set 0 --transfer-textures", dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("/samplers/0/wrapS"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("material 0"), std::string::npos) << r.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{"in.gltf"});
}

TEST(AssetTextureTransfer, MaterialWithoutTextureOnTheSetGetsANote) {
  TempDir dir;
  write_edited(dir / "in.gltf", [](json& j) {
    j["materials"][0]["pbrMetallicRoughness"].erase("baseColorTexture");
    for (const char* k : {"images", "textures", "samplers"}) j.erase(k);
    j["bufferViews"].erase(j["bufferViews"].size() - 1);  // the image's, the last one
  });
  const TextureTransferReport rep = transfer(dir / "in.gltf", dir / "out.gltf");
  gltf_test::expect_valid(dir / "out.gltf");  // no empty images or textures array
  EXPECT_TRUE(rep.baked.empty());
  ASSERT_EQ(rep.notes.size(), 1u);
  EXPECT_NE(rep.notes[0].find("no texture on TEXCOORD_0"), std::string::npos) << rep.notes[0];
  EXPECT_TRUE(std::filesystem::exists(dir / "out.gltf"));
}

TEST(AssetTextureTransfer, TransferNeedsTheUvSet) {
  TempDir dir;
  write_textured_asset(dir / "in.glb", generate_textured_asset(small_asset()));
  const auto r = test::run_cli("atlas " + (dir / "in.glb") + " -o " + (dir / "out.glb") + " --transfer-textures", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--uv-set"), std::string::npos) << r.err;
}

// A flat normal map (0.5, 0.5, 1 everywhere) says "the surface normal" in any
// tangent frame, so it must stay flat in the new layout; the new frame is
// written as TANGENT: unit, perpendicular to NORMAL, along the direction in
// which the new u grows (glTF's tangent), and the document stays valid.
TEST(AssetTextureTransfer, NormalMapStaysFlatAndTangentsFollowTheNewU) {
  TempDir dir;
  Image flat(16, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) flat.pixel(x, y)[0] = 128, flat.pixel(x, y)[1] = 128, flat.pixel(x, y)[2] = 255;
  test::write_text(dir / "flat.png", encode_png(flat));
  write_edited(dir / "in.gltf", [](json& j) {
    j["images"].push_back({{"uri", "flat.png"}});
    j["textures"].push_back({{"source", 1}, {"sampler", 0}});
    j["materials"][0]["normalTexture"] = {{"index", 1}};
  });
  const TextureTransferReport rep = transfer(dir / "in.gltf", dir / "out.glb", 256);
  ASSERT_EQ(rep.baked.size(), 2u);
  const tinygltf::Model m = gltf_test::load(dir / "out.glb");
  const tinygltf::Primitive& p = m.meshes.at(0).primitives.at(0);
  const int normal_texture = m.materials.at(0).normalTexture.index;
  const Image baked = decode_png(test::image_bytes(m, m.textures.at(static_cast<std::size_t>(normal_texture)).source, ""));
  long covered = 0;
  for (int y = 0; y < baked.height; ++y)
    for (int x = 0; x < baked.width; ++x) {
      const std::uint8_t* t = baked.pixel(x, y);
      if (t[0] == 0 && t[1] == 0 && t[2] == 0) continue;  // outside every chart and its padding
      ++covered;
      EXPECT_NEAR(t[0], 128, 2);
      EXPECT_NEAR(t[1], 128, 2);
      EXPECT_GE(t[2], 253);
    }
  EXPECT_GT(covered, 256 * 256 / 4);
  ASSERT_TRUE(p.attributes.count("TANGENT"));
  int c = 0;
  const std::vector<double> T = test::read_values(m, p.attributes.at("TANGENT"), c), N = test::read_values(m, p.attributes.at("NORMAL"), c);
  const Drawn after = test::drawn(dir / "out.glb");
  for (Eigen::Index v = 0; v < after.V.rows(); ++v) {
    const Eigen::Vector3d t(T[4 * v], T[4 * v + 1], T[4 * v + 2]), n(N[3 * v], N[3 * v + 1], N[3 * v + 2]);
    EXPECT_NEAR(t.norm(), 1, 1e-5);
    EXPECT_NEAR(std::abs(T[4 * v + 3]), 1, 0);
    EXPECT_LT(std::abs(t.dot(n)), 1e-3);
  }
  long along = 0, up = 0;
  for (int f = 0; f < after.F.rows(); ++f) {
    Eigen::Matrix<double, 3, 2> E;
    Eigen::Matrix2d U;
    for (int k = 0; k < 2; ++k) {
      E.col(k) = (after.V.row(after.F(f, k + 1)) - after.V.row(after.F(f, 0))).transpose();
      U.col(k) = (after.UV.row(after.F(f, k + 1)) - after.UV.row(after.F(f, 0))).transpose();
    }
    // after.UV has v up: glTF's bitangent points up the image.
    const Eigen::Vector3d dpdu = (E * U.inverse()).col(0).normalized(), dpdv = (E * U.inverse()).col(1).normalized();
    Eigen::Vector3d t = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const int v = after.F(f, k);
      const Eigen::Vector3d tv(T[4 * v], T[4 * v + 1], T[4 * v + 2]), nv(N[3 * v], N[3 * v + 1], N[3 * v + 2]);
      t += tv, b += T[4 * v + 3] * nv.cross(tv);
    }
    along += t.normalized().dot(dpdu) > 0.7;
    up += b.normalized().dot(dpdv) > 0.7;
  }
  EXPECT_GT(along, 0.95 * after.F.rows());
  EXPECT_GT(up, 0.95 * after.F.rows());
  gltf_test::expect_valid(dir / "out.glb");
}

// A KHR_texture_transform on the slot is baked in: the slot loses it (and
// the document its declaration) and the look through the transform is kept.
TEST(AssetTextureTransfer, TextureTransformIsBakedIn) {
  TempDir dir;
  write_edited(dir / "in.gltf", [](json& j) {
    j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
        {"KHR_texture_transform", {{"offset", {0.2, 0.1}}, {"scale", {0.6, 0.7}}, {"texCoord", 0}}}};
    j["extensionsUsed"] = {"KHR_texture_transform"};
  });
  transfer(dir / "in.gltf", dir / "out.glb", 1024);
  const json out = json::parse(test::slurp(dir / "in.gltf"));  // the input still has it
  ASSERT_TRUE(out.contains("extensionsUsed"));
  const tinygltf::Model m = gltf_test::load(dir / "out.glb");
  EXPECT_TRUE(m.extensionsUsed.empty());
  EXPECT_TRUE(m.materials.at(0).pbrMetallicRoughness.baseColorTexture.extensions.empty());
  Drawn before = test::drawn(dir / "in.gltf");
  for (Eigen::Index v = 0; v < before.UV.rows(); ++v) {
    // glTF's transform acts on v down: u' = 0.6 u + 0.2, v' = 0.7 v + 0.1.
    const double u = before.UV(v, 0), vd = 1 - before.UV(v, 1);
    before.UV.row(v) << 0.6 * u + 0.2, 1 - (0.7 * vd + 0.1);
  }
  const test::LookDifference d = test::look_difference(before, test::drawn(dir / "out.glb"), 400);
  EXPECT_LT(d.mean, 0.02);
  EXPECT_LT(d.mean_away, 0.01);
}

// Two materials sharing image, sampler and transform on different triangles
// (two primitives): one image baked over the union, both slots point at it.
TEST(AssetTextureTransfer, MaterialsSharingAnImageGetOneBakeOverTheirUnion) {
  TempDir dir;
  write_edited(dir / "in.gltf", [](json& j) {
    json& prim = j["meshes"][0]["primitives"][0];
    const int indices = prim["indices"];
    json first = j["accessors"][indices], second = first;
    const int count = first["count"].get<int>() / 6 * 3;  // a multiple of 3
    first["count"] = count;
    second["count"] = j["accessors"][indices]["count"].get<int>() - count;
    second["byteOffset"] = count * 4;
    j["accessors"].push_back(first);
    j["accessors"].push_back(second);
    json other = prim;
    prim["indices"] = j["accessors"].size() - 2;
    other["indices"] = j["accessors"].size() - 1;
    other["material"] = 1;
    j["meshes"][0]["primitives"].push_back(other);
    json m = j["materials"][0];
    m["name"] = "second";
    j["materials"].push_back(m);
  });
  const TextureTransferReport rep = transfer(dir / "in.gltf", dir / "out.glb", 512);
  ASSERT_EQ(rep.baked.size(), 2u);
  EXPECT_EQ(rep.baked[0].output, rep.baked[1].output);
  EXPECT_EQ(rep.baked[0].texels_covered, rep.baked[1].texels_covered);
  EXPECT_NE(rep.baked[0].material, rep.baked[1].material);
  const tinygltf::Model m = gltf_test::load(dir / "out.glb");
  EXPECT_EQ(m.materials.at(0).pbrMetallicRoughness.baseColorTexture.index,
            m.materials.at(1).pbrMetallicRoughness.baseColorTexture.index);
  ASSERT_EQ(m.images.size(), 1u);  // the one bake (the image it replaced is dropped)
  EXPECT_EQ(rep.baked[0].output, "image 0");
  gltf_test::expect_valid(dir / "out.glb");
}

std::vector<std::string> files_in(const std::string& folder) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(folder)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

// An OBJ (vt v up) as the renderer draws it: one vertex per (v, vt) pair,
// so charts stay connected; the texture from `png`.
Drawn drawn_obj(const std::string& obj, const std::string& png) {
  const MeshData m = read_mesh(obj);
  Drawn d;
  std::map<std::pair<int, int>, int> id;
  std::vector<Eigen::Vector3d> V;
  std::vector<Eigen::Vector2d> UV;
  d.F.resize(m.F.rows(), 3);
  for (int f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto [it, fresh] = id.emplace(std::make_pair(m.F(f, k), m.FTC(f, k)), static_cast<int>(V.size()));
      if (fresh) V.push_back(m.V.row(m.F(f, k)).transpose()), UV.push_back(m.TC.row(m.FTC(f, k)).transpose());
      d.F(f, k) = it->second;
    }
  d.V.resize(static_cast<Eigen::Index>(V.size()), 3);
  d.UV.resize(d.V.rows(), 2);
  for (std::size_t v = 0; v < V.size(); ++v) d.V.row(v) = V[v].transpose(), d.UV.row(v) = UV[v].transpose();
  d.texture = decode_png(test::slurp(png));
  return d;
}

TEST(AssetTextureTransfer, ObjMtlPngRoundTripKeepsTheLook) {
  TempDir dir;
  write_textured_asset(dir / "in.obj", generate_textured_asset(small_asset()));
  std::filesystem::create_directory(dir / "out");
  const auto r = test::run_cli("atlas " + (dir / "in.obj") + " -o " + (dir / "out/atlas.obj") +
                                   " --transfer-textures --texture-size 1024 -q --report " + (dir / "r.json"),
                               dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(files_in(dir / "out"), (std::vector<std::string>{"atlas.mtl", "atlas.obj", "atlas_textured_Kd.png"}));
  const std::string mtl = test::slurp(dir / "out/atlas.mtl");
  EXPECT_NE(mtl.find("map_Kd atlas_textured_Kd.png\n"), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("newmtl textured\n"), std::string::npos) << mtl;
  EXPECT_NE(test::slurp(dir / "out/atlas.obj").find("mtllib atlas.mtl\n"), std::string::npos);
  const json j = json::parse(test::slurp(dir / "r.json"));
  EXPECT_EQ(j["textures"]["baked"][0]["slot"], "map_Kd");
  const test::LookDifference d = test::look_difference(drawn_obj(dir / "in.obj", dir / "in.png"),
                                                       drawn_obj(dir / "out/atlas.obj", dir / "out/atlas_textured_Kd.png"), 400);
  EXPECT_GT(d.pixels_away, d.pixels / 4);
  EXPECT_LT(d.mean, 0.02);
  EXPECT_LT(d.mean_away, 0.01);
}

TEST(AssetTextureTransfer, ObjWithAMissingMapIsRefusedAndWritesNothing) {
  TempDir dir;
  write_textured_asset(dir / "in.obj", generate_textured_asset(small_asset()));
  std::filesystem::remove(dir / "in.png");
  std::filesystem::create_directory(dir / "out");
  const auto r = test::run_cli("atlas " + (dir / "in.obj") + " -o " + (dir / "out/atlas.obj") + " --transfer-textures", dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("in.mtl:4 (material 'textured', map_Kd)"), std::string::npos) << r.err;
  EXPECT_TRUE(files_in(dir / "out").empty());
}

}  // namespace
}  // namespace intrinsic
