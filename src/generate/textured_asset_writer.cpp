// Writing the generated textured asset (generate.h): a self-contained
// .glb/.gltf with its PNG embedded, or an OBJ with its .mtl and PNG beside it.
// The texture-transfer tests, bench and picture read these files back like
// any user's asset (docs/textures.md).
#include <cstring>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "intrinsic/error.h"
#include "intrinsic/generate.h"
#include "intrinsic/io.h"
#include "intrinsic/image.h"
#include "io/gltf_document.h"

namespace intrinsic {
namespace {

using nlohmann::json;

struct Bin {
  std::string bytes;
  json views = json::array();
  int add(const void* data, std::size_t size, int target) {
    while (bytes.size() % 4) bytes.push_back('\0');
    json v = {{"buffer", 0}, {"byteOffset", bytes.size()}, {"byteLength", size}};
    if (target) v["target"] = target;
    bytes.append(static_cast<const char*>(data), size);
    views.push_back(v);
    return static_cast<int>(views.size() - 1);
  }
};

std::string glb(const json& j, std::string bin) {
  std::string text = j.dump();
  while (text.size() % 4) text += ' ';
  while (bin.size() % 4) bin += '\0';
  auto u32 = [](std::string& s, std::uint32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); };
  std::string out = "glTF";
  u32(out, 2);
  u32(out, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
  u32(out, static_cast<std::uint32_t>(text.size()));
  u32(out, 0x4E4F534Au);
  out += text;
  u32(out, static_cast<std::uint32_t>(bin.size()));
  u32(out, 0x004E4942u);
  return out + bin;
}

// One glTF vertex per texture coordinate row (each belongs to one chart
// corner, so to one position); the ellipsoid's exact normal.
std::string gltf_bytes(const TexturedAsset& a, bool binary) {
  const MeshData& m = a.mesh;
  const auto nv = static_cast<std::size_t>(m.TC.rows());
  std::vector<int> position(nv, 0);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) position[static_cast<std::size_t>(m.FTC(f, k))] = m.F(f, k);
  std::vector<float> P(nv * 3), N(nv * 3), T(nv * 2);
  std::vector<std::uint32_t> I;
  float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
  const double r2[3] = {1.0, 0.81, 0.64};  // the ellipsoid's squared radii (textured_asset.cpp)
  for (std::size_t v = 0; v < nv; ++v) {
    const Eigen::Vector3d p = m.V.row(position[v]).transpose();
    const Eigen::Vector3d n = Eigen::Vector3d(p.x() / r2[0], p.y() / r2[1], p.z() / r2[2]).normalized();
    for (int q = 0; q < 3; ++q) {
      P[v * 3 + q] = static_cast<float>(p[q]), N[v * 3 + q] = static_cast<float>(n[q]);
      lo[q] = std::min(lo[q], P[v * 3 + q]), hi[q] = std::max(hi[q], P[v * 3 + q]);
    }
    // glTF's texture origin is the top-left corner, the OBJ convention's the bottom-left.
    T[v * 2] = static_cast<float>(m.TC(static_cast<Eigen::Index>(v), 0));
    T[v * 2 + 1] = static_cast<float>(1 - m.TC(static_cast<Eigen::Index>(v), 1));
  }
  for (Eigen::Index f = 0; f < m.FTC.rows(); ++f)
    for (int k = 0; k < 3; ++k) I.push_back(static_cast<std::uint32_t>(m.FTC(f, k)));
  const std::string png = encode_png(a.texture);
  Bin bin;
  auto accessor = [&](int view, int component, const char* type, std::size_t count) {
    return json{{"bufferView", view}, {"componentType", component}, {"type", type}, {"count", count}};
  };
  json acc = json::array();
  acc.push_back(accessor(bin.add(P.data(), P.size() * 4, 34962), 5126, "VEC3", nv));
  acc[0]["min"] = {lo[0], lo[1], lo[2]};
  acc[0]["max"] = {hi[0], hi[1], hi[2]};
  acc.push_back(accessor(bin.add(N.data(), N.size() * 4, 34962), 5126, "VEC3", nv));
  acc.push_back(accessor(bin.add(T.data(), T.size() * 4, 34962), 5126, "VEC2", nv));
  acc.push_back(accessor(bin.add(I.data(), I.size() * 4, 34963), 5125, "SCALAR", I.size()));
  const int image_view = bin.add(png.data(), png.size(), 0);
  json j = {
      {"asset", {{"version", "2.0"}, {"generator", "intrinsic generate textured"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}, {"name", "textured"}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
                                    {"indices", 3},
                                    {"material", 0}}}}}}},
      {"materials", {{{"name", "textured"},
                      {"pbrMetallicRoughness",
                       {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}}}},
      {"samplers", {{{"magFilter", 9729}, {"minFilter", 9729}, {"wrapS", 33071}, {"wrapT", 33071}}}},
      {"textures", {{{"sampler", 0}, {"source", 0}}}},
      {"images", {{{"bufferView", image_view}, {"mimeType", "image/png"}}}},
      {"accessors", acc},
      {"bufferViews", bin.views},
  };
  json buffer = {{"byteLength", bin.bytes.size()}};
  if (binary) {
    j["buffers"] = json::array({buffer});
    return glb(j, bin.bytes);
  }
  buffer["uri"] = "data:application/octet-stream;base64," + gltf::base64_encode(bin.bytes);
  j["buffers"] = json::array({buffer});
  return j.dump(1, '\t');
}

std::string obj_text(const MeshData& m, const std::string& mtl) {
  std::string s = "# intrinsic generate textured\nmtllib " + mtl + "\n";
  char b[96];
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
    std::snprintf(b, sizeof b, "v %.9g %.9g %.9g\n", m.V(v, 0), m.V(v, 1), m.V(v, 2));
    s += b;
  }
  for (Eigen::Index t = 0; t < m.TC.rows(); ++t) {
    std::snprintf(b, sizeof b, "vt %.9g %.9g\n", m.TC(t, 0), m.TC(t, 1));
    s += b;
  }
  s += "usemtl textured\n";
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    std::snprintf(b, sizeof b, "f %d/%d %d/%d %d/%d\n", m.F(f, 0) + 1, m.FTC(f, 0) + 1, m.F(f, 1) + 1,
                  m.FTC(f, 1) + 1, m.F(f, 2) + 1, m.FTC(f, 2) + 1);
    s += b;
  }
  return s;
}

}  // namespace

void write_textured_asset(const std::string& path, const TexturedAsset& a) {
  const std::string ext = mesh_extension(path);
  if (ext == ".glb" || ext == ".gltf") {
    write_file_atomically(path, gltf_bytes(a, ext == ".glb"));
    return;
  }
  if (ext != ".obj" || path.size() < 4 || path.compare(path.size() - 4, 4, ".obj") != 0)
    throw_usage("output '" + path + "': the textured asset is written as .glb, .gltf or .obj");
  const std::filesystem::path p(path);
  const std::string stem = p.stem().string();
  const std::filesystem::path dir = p.parent_path();
  const std::string mtl = stem + ".mtl", png = stem + ".png";
  write_all({{(dir / png).string(), encode_png(a.texture)},
             {(dir / mtl).string(), "newmtl textured\nKa 1 1 1\nKd 1 1 1\nmap_Kd " + png + "\n"},
             {path, obj_text(a.mesh, mtl)}});
}

}  // namespace intrinsic
