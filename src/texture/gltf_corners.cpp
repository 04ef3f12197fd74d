// Per-corner data of a written glTF primitive for the texture transfer
// (gltf_textures.h): read from the document's accessors through the split
// the writer made, and the new TANGENT attribute written back per vertex.
#include <cmath>
#include <cstring>

#include "texture/gltf_textures.h"

namespace intrinsic::gltf_textures {
namespace {

const gltf::Accessor* attribute(const GltfDocument& doc, const json& attributes, const std::string& key,
                                AccessorCache& cache) {
  const auto it = attributes.find(key);
  if (it == attributes.end() || !it->is_number_integer()) return nullptr;
  const int i = it->get<int>();
  auto c = cache.find(i);
  if (c == cache.end()) c = cache.emplace(i, gltf::read_accessor(doc, i, INT64_MAX)).first;
  return &c->second;
}

// A unit tangent perpendicular to n and w = +-1, whatever came in: glTF
// refuses anything else, and a degenerate UV triangle gives no direction.
Eigen::Vector4d sane_tangent(const Eigen::Vector4d& t, const Eigen::Vector3d& n) {
  Eigen::Vector3d x = t.head<3>();
  if (x.allFinite() && n.allFinite()) x -= n.dot(x) * n;
  if (!x.allFinite() || x.norm() < 1e-12) {
    x = n.unitOrthogonal();
    if (!x.allFinite()) x = Eigen::Vector3d::UnitX();
  }
  x.normalize();
  return {x.x(), x.y(), x.z(), t.w() < 0 ? -1.0 : 1.0};
}

}  // namespace

Corners gather_corners(const GltfDocument& doc, const GltfWrittenPrimitive& w, const AtlasResult& r,
                       AccessorCache& cache) {
  const GltfDocument::Primitive& p = *w.source;
  const json& attributes =
      doc.json["meshes"][static_cast<std::size_t>(p.mesh)]["primitives"][static_cast<std::size_t>(p.primitive)]["attributes"];
  const gltf::Accessor* pos = attribute(doc, attributes, "POSITION", cache);
  const gltf::Accessor* nor = attribute(doc, attributes, "NORMAL", cache);
  const gltf::Accessor* tex = attribute(doc, attributes, "TEXCOORD_" + std::to_string(w.set), cache);
  const gltf::Accessor* tan = attribute(doc, attributes, "TANGENT", cache);
  const auto n = static_cast<Eigen::Index>(w.index.size());
  Corners c;
  c.position.resize(n, 3), c.normal.resize(n, 3), c.new_uv.resize(n, 2);
  if (tex) c.old_uv.resize(n, 2);
  if (tan && nor) c.old_tangent.resize(n, 4);
  c.has_normal = nor != nullptr;
  for (Eigen::Index k = 0; k < n; ++k) {
    const std::uint32_t out = w.index[static_cast<std::size_t>(k)];
    const int v = w.vertex_source[out], t = w.vertex_uv[out];
    for (int q = 0; q < 3; ++q) c.position(k, q) = pos->value(v, q);
    if (nor)
      for (int q = 0; q < 3; ++q) c.normal(k, q) = nor->value(v, q);
    if (tex) c.old_uv.row(k) << tex->value(v, 0), tex->value(v, 1);
    if (tan && nor)
      for (int q = 0; q < 4; ++q) c.old_tangent(k, q) = tan->value(v, q);
    // The atlas is in our convention (v up), glTF images have v down.
    c.new_uv.row(k) << r.UV(t, 0), 1 - r.UV(t, 1);
  }
  for (Eigen::Index f = 0; f + 2 < n; f += 3) {
    // No NORMAL: glTF's flat normals.
    const Eigen::Vector3d a = c.position.row(f), b = c.position.row(f + 1), d = c.position.row(f + 2);
    const Eigen::Vector3d face = (b - a).cross(d - a).normalized();
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d v = nor ? Eigen::Vector3d(c.normal.row(f + k)) : face;
      if (!(v.norm() > 1e-20)) v = face;
      c.normal.row(f + k) = v.normalized();
    }
  }
  if (c.old_tangent.rows())
    for (Eigen::Index k = 0; k < n; ++k)
      c.old_tangent.row(k) = sane_tangent(c.old_tangent.row(k), c.normal.row(k)).transpose();
  return c;
}

Eigen::MatrixX2d transformed(const Eigen::MatrixX2d& uv, const TextureTransform& t) {
  const double cr = std::cos(t.rotation), sr = std::sin(t.rotation);
  Eigen::MatrixX2d out(uv.rows(), 2);
  for (Eigen::Index i = 0; i < uv.rows(); ++i) {
    const double u = uv(i, 0) * t.scale_u, v = uv(i, 1) * t.scale_v;
    out.row(i) << cr * u + sr * v + t.offset_u, -sr * u + cr * v + t.offset_v;
  }
  return out;
}

int add_view(json& out, std::string& bin, const std::string& bytes, int target) {
  while (bin.size() % 4) bin.push_back('\0');
  json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}};
  if (target) v["target"] = target;
  bin += bytes;
  out["bufferViews"].push_back(v);
  return static_cast<int>(out["bufferViews"].size() - 1);
}

void write_tangents(json& out, std::string& bin, const GltfWrittenPrimitive& w, const Eigen::MatrixX4d& tangent) {
  const std::size_t count = w.vertex_source.size();
  std::vector<float> values(count * 4, 0.0f);
  std::vector<char> done(count, 0);
  for (std::size_t k = 0; k < w.index.size(); ++k) {
    const std::uint32_t v = w.index[k];
    if (done[v]) continue;
    done[v] = 1;
    for (int q = 0; q < 4; ++q) values[v * 4 + q] = static_cast<float>(tangent(static_cast<Eigen::Index>(k), q));
  }
  for (std::size_t v = 0; v < count; ++v)
    if (!done[v]) values[v * 4] = 1, values[v * 4 + 3] = 1;  // unused vertex: any valid tangent
  std::string bytes(values.size() * 4, '\0');
  std::memcpy(&bytes[0], values.data(), bytes.size());
  const json acc = {{"bufferView", add_view(out, bin, bytes, 34962)},
                    {"componentType", 5126},
                    {"type", "VEC4"},
                    {"count", count}};
  out["accessors"].push_back(acc);
  const GltfDocument::Primitive& p = *w.source;
  out["meshes"][static_cast<std::size_t>(p.mesh)]["primitives"][static_cast<std::size_t>(p.primitive)]["attributes"]
     ["TANGENT"] = out["accessors"].size() - 1;
}

Eigen::MatrixX4d sane_tangents(const Eigen::MatrixX4d& t, const Eigen::MatrixX3d& n) {
  Eigen::MatrixX4d out(t.rows(), 4);
  for (Eigen::Index k = 0; k < t.rows(); ++k) out.row(k) = sane_tangent(t.row(k), n.row(k)).transpose();
  return out;
}

}  // namespace intrinsic::gltf_textures
