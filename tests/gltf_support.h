// What the glTF tests share (test_gltf*.cpp): a document built by hand (JSON
// and one binary buffer), the Khronos validator run on a written file, and
// the output read back with tinygltf's own loader, element by element.
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

// The same configuration as src/io/glb_writer.cpp, which holds the implementation.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include "cli_support.h"
#include "intrinsic/generate.h"
#include "intrinsic/mesh_data.h"
#include "test_support.h"

namespace intrinsic::gltf_test {

using nlohmann::json;

inline std::string b64(const std::string& in) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < in.size(); i += 3) {
    std::uint32_t v = static_cast<unsigned char>(in[i]) << 16;
    if (i + 1 < in.size()) v |= static_cast<unsigned char>(in[i + 1]) << 8;
    if (i + 2 < in.size()) v |= static_cast<unsigned char>(in[i + 2]);
    out += t[v >> 18];
    out += t[(v >> 12) & 63];
    out += i + 1 < in.size() ? t[(v >> 6) & 63] : '=';
    out += i + 2 < in.size() ? t[v & 63] : '=';
  }
  return out;
}

// A document under construction: JSON and one buffer.
struct Doc {
  json j = {{"asset", {{"version", "2.0"}}}};
  std::string bin;

  template <class T>
  int view(const std::vector<T>& data, int target = 0, int stride = 0) {
    while (bin.size() % 4) bin.push_back('\0');
    json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", data.size() * sizeof(T)}};
    if (target) v["target"] = target;
    if (stride) v["byteStride"] = stride;
    bin.append(reinterpret_cast<const char*>(data.data()), data.size() * sizeof(T));
    j["bufferViews"].push_back(v);
    return static_cast<int>(j["bufferViews"].size()) - 1;
  }
  int accessor(json a) {
    j["accessors"].push_back(std::move(a));
    return static_cast<int>(j["accessors"].size()) - 1;
  }
  // A tightly packed accessor of `data` (components of `type`).
  template <class T>
  int add(const std::vector<T>& data, int component, const std::string& type, int count, int target = 34962,
          json extra = json::object()) {
    json a = {{"bufferView", view(data, target)}, {"componentType", component}, {"type", type}, {"count", count}};
    a.update(extra);
    return accessor(a);
  }
  json with_buffer(bool embed) const {
    json out = j;
    json b = {{"byteLength", bin.size()}};
    if (embed) b["uri"] = "data:application/octet-stream;base64," + b64(bin);
    out["buffers"] = json::array({b});
    return out;
  }
  std::string gltf() const { return with_buffer(true).dump(); }
  std::string glb() const {
    std::string text = with_buffer(false).dump();
    while (text.size() % 4) text += ' ';
    std::string data = bin;
    while (data.size() % 4) data += '\0';
    std::string out = "glTF";
    auto u32 = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
    u32(2);
    u32(static_cast<std::uint32_t>(28 + text.size() + data.size()));
    u32(static_cast<std::uint32_t>(text.size()));
    u32(0x4E4F534Au);
    out += text;
    u32(static_cast<std::uint32_t>(data.size()));
    u32(0x004E4942u);
    return out + data;
  }
};

inline std::vector<float> positions(const MeshData& m) {
  std::vector<float> p;
  for (int v = 0; v < m.V.rows(); ++v)
    for (int k = 0; k < 3; ++k) p.push_back(static_cast<float>(m.V(v, k)));
  return p;
}

inline std::vector<std::uint32_t> indices(const MeshData& m) {
  std::vector<std::uint32_t> i;
  for (int f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) i.push_back(static_cast<std::uint32_t>(m.F(f, k)));
  return i;
}

inline json min_max(const std::vector<float>& p, json a) {
  std::vector<float> lo(3, 1e30f), hi(3, -1e30f);
  for (std::size_t i = 0; i < p.size(); ++i) lo[i % 3] = std::min(lo[i % 3], p[i]), hi[i % 3] = std::max(hi[i % 3], p[i]);
  a["min"] = lo;
  a["max"] = hi;
  return a;
}

// A one-primitive document of `m` (indexed triangles), float positions.
inline Doc simple_doc(const MeshData& m) {
  Doc d;
  const std::vector<float> p = positions(m);
  const int pa = d.add(p, 5126, "VEC3", static_cast<int>(m.V.rows()), 34962, min_max(p, json::object()));
  const int ia = d.add(indices(m), 5125, "SCALAR", static_cast<int>(3 * m.F.rows()), 34963);
  d.j["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", pa}}}, {"indices", ia}}})}}});
  d.j["nodes"] = json::array({{{"mesh", 0}}});
  d.j["scenes"] = json::array({{{"nodes", {0}}}});
  d.j["scene"] = 0;
  return d;
}

// Runs the Khronos validator on `path`: no error, and with `all_used` no
// unused accessor or buffer view either; skips the check (with a note) where node or the npm
// package is missing.
inline void expect_valid(const std::string& path, bool all_used = false) {
  const std::string script = std::string(INTRINSIC_SOURCE_DIR) + "/tests/gltf_validator/validate.mjs";
  const std::string out = path + ".validator.txt";
  const int status = std::system(("node " + script + " '" + path + "' >'" + out + "' 2>&1").c_str());
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  const std::string text = test::slurp(out);
  std::filesystem::remove(out);
  if (code == 77 || code == 127) {
    // Only this check is left out; the test's own checks still count.
    std::printf("glTF validator not run on %s: needs node and `npm ci` in tests/gltf_validator\n", path.c_str());
    return;
  }
  EXPECT_EQ(code, 0) << path << ":\n" << text;
  // (An atlas set no material reads is reported unused as well: that one is
  // meant, only unused accessors and views count here.)
  if (all_used) {
    EXPECT_EQ(text.find("UNUSED_OBJECT /accessors/"), std::string::npos) << path << ":\n" << text;
    EXPECT_EQ(text.find("UNUSED_OBJECT /bufferViews/"), std::string::npos) << path << ":\n" << text;
  }
}

inline tinygltf::Model load(const std::string& path) {
  const std::string bytes = test::slurp(path);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  // Images are not decoded (the library is built without an image codec).
  loader.SetImageLoader([](tinygltf::Image*, int, std::string*, std::string*, int, int, const unsigned char*, int,
                           void*) { return true; },
                        nullptr);
  std::string err, warn;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const std::string folder = std::filesystem::path(path).parent_path().string();
  const bool ok = path.size() > 4 && path.compare(path.size() - 4, 4, ".glb") == 0
                      ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, static_cast<unsigned>(bytes.size()), folder)
                      : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned>(bytes.size()), folder);
  EXPECT_TRUE(ok) << err;
  return model;
}

// The raw bytes of element i of a (dense) accessor of the output.
inline std::string element(const tinygltf::Model& m, int accessor, std::size_t i) {
  const tinygltf::Accessor& a = m.accessors.at(static_cast<std::size_t>(accessor));
  const tinygltf::BufferView& v = m.bufferViews.at(static_cast<std::size_t>(a.bufferView));
  const int size = tinygltf::GetComponentSizeInBytes(a.componentType) * tinygltf::GetNumComponentsInType(a.type);
  const std::size_t stride = v.byteStride ? v.byteStride : static_cast<std::size_t>(size);
  const auto* p = m.buffers.at(static_cast<std::size_t>(v.buffer)).data.data() + v.byteOffset + a.byteOffset + i * stride;
  return std::string(reinterpret_cast<const char*>(p), static_cast<std::size_t>(size));
}

// Every element of a (dense) accessor, one after the other.
inline std::string accessor_bytes(const tinygltf::Model& m, int accessor) {
  std::string out;
  for (std::size_t i = 0; i < m.accessors.at(static_cast<std::size_t>(accessor)).count; ++i) out += element(m, accessor, i);
  return out;
}

template <class T>
inline std::string bytes_of(const std::vector<T>& v, std::size_t i, int n) {
  return std::string(reinterpret_cast<const char*>(&v[i * static_cast<std::size_t>(n)]), sizeof(T) * static_cast<std::size_t>(n));
}

inline std::uint32_t index_of(const tinygltf::Model& m, int accessor, std::size_t i) {
  const std::string e = element(m, accessor, i);
  std::uint32_t v = 0;
  std::memcpy(&v, e.data(), e.size());
  return v;
}

// The torus with every kind of attribute, a skin, an animation, a camera
// and a textured material: what a game asset carries.
struct RichAsset {
  MeshData m;
  std::vector<float> normal, texcoord, weights, dpos, dnrm;
  std::vector<std::uint8_t> color, joints;
  Doc doc;
};

inline RichAsset rich_asset() {
  RichAsset a;
  GenerateOptions g;
  g.rings = 8;
  a.m = generate_torus(g);
  const int n = static_cast<int>(a.m.V.rows());
  for (int v = 0; v < n; ++v) {
    const Eigen::Vector3d p = a.m.V.row(v);
    const Eigen::Vector3d u = p.normalized();
    for (int k = 0; k < 3; ++k) a.normal.push_back(static_cast<float>(u[k]));
    a.texcoord.push_back(static_cast<float>(0.1 * v)), a.texcoord.push_back(static_cast<float>(0.5 - 0.01 * v));
    for (int k = 0; k < 4; ++k) a.color.push_back(static_cast<std::uint8_t>((v * 7 + k * 50) % 256));
    a.joints.push_back(0), a.joints.push_back(1), a.joints.push_back(0), a.joints.push_back(0);
    const float w = static_cast<float>(v % 5) / 4;
    a.weights.push_back(w), a.weights.push_back(1 - w), a.weights.push_back(0), a.weights.push_back(0);
    for (int k = 0; k < 3; ++k) a.dpos.push_back(static_cast<float>(0.01 * ((v + k) % 3)));
    for (int k = 0; k < 3; ++k) a.dnrm.push_back(0);
  }
  Doc& d = a.doc;
  const std::vector<float> p = positions(a.m);
  json prim = {{"attributes",
                {{"POSITION", d.add(p, 5126, "VEC3", n, 34962, min_max(p, json::object()))},
                 {"NORMAL", d.add(a.normal, 5126, "VEC3", n)},
                 {"TEXCOORD_0", d.add(a.texcoord, 5126, "VEC2", n)},
                 {"COLOR_0", d.add(a.color, 5121, "VEC4", n, 34962, {{"normalized", true}})},
                 {"JOINTS_0", d.add(a.joints, 5121, "VEC4", n)},
                 {"WEIGHTS_0", d.add(a.weights, 5126, "VEC4", n)}}},
               {"indices", d.add(indices(a.m), 5125, "SCALAR", static_cast<int>(3 * a.m.F.rows()), 34963)},
               {"material", 0},
               {"targets", json::array({{{"POSITION", d.add(a.dpos, 5126, "VEC3", n, 34962, min_max(a.dpos, json::object()))},
                                         {"NORMAL", d.add(a.dnrm, 5126, "VEC3", n)}}})},
               {"extras", {{"note", "kept"}}}};
  d.j["meshes"] = json::array({{{"primitives", json::array({prim})}, {"weights", {0.5}}, {"name", "torus"}}});
  const std::vector<float> ibm = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  const std::vector<float> times = {0, 1}, moves = {0, 0, 0, 0, 1, 0};
  d.j["skins"] = json::array({{{"joints", {1, 2}}, {"inverseBindMatrices", d.add(ibm, 5126, "MAT4", 2, 0)}}});
  d.j["nodes"] = json::array({{{"mesh", 0}, {"skin", 0}, {"name", "body"}},
                              {{"children", {2}}, {"translation", {0, 1, 0}}, {"extras", {{"bone", true}}}},
                              {{"rotation", {0, 0, 0.7071068, 0.7071068}}},
                              {{"camera", 0}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1}}}});
  d.j["scenes"] = json::array({{{"nodes", {0, 1, 3}}}});
  d.j["scene"] = 0;
  d.j["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}});
  d.j["animations"] = json::array(
      {{{"samplers", json::array({{{"input", d.add(times, 5126, "SCALAR", 2, 0, {{"min", {0}}, {"max", {1}}})},
                                   {"output", d.add(moves, 5126, "VEC3", 2, 0)}}})},
        {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}}})}}});
  // A 1x1 PNG.
  d.j["images"] = json::array({{{"uri", "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNk+M9QDwADhgGAWjR9awAAAABJRU5ErkJggg=="}}});
  d.j["samplers"] = json::array({{{"magFilter", 9729}}});
  d.j["textures"] = json::array({{{"source", 0}, {"sampler", 0}}});
  d.j["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.25}}},
                                   {"doubleSided", true}, {"name", "skin"}}});
  d.j["extras"] = {{"author", "test"}};
  return a;
}

}  // namespace intrinsic::gltf_test
