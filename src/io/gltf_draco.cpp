// KHR_draco_mesh_compression on read (docs/formats.md "glTF"): every
// primitive carrying the extension is decoded with Google's Draco library
// and its result written into the document as plain data, one new buffer
// with a view per attribute and one for the indices, the primitive's own
// accessors (which the extension leaves without a bufferView) pointed at
// them. After that the reader and the writer see an ordinary document; the
// writer writes each rewritten primitive uncompressed and drops the
// extension (gltf_writer.cpp), the Draco stream is then unreferenced and
// pruned (gltf_prune.cpp).
#include <draco/compression/decode.h>

#include <cstring>

#include "io/gltf_document.h"

namespace intrinsic::gltf {

using nlohmann::json;

namespace {

// `count` elements of the draco attribute `att`, one per Draco point, as
// the accessor's component type (Draco converts from its own storage type).
template <class T>
std::string values(const draco::PointAttribute& att, std::uint32_t count, int components) {
  std::string out(static_cast<std::size_t>(count) * components * sizeof(T), '\0');
  std::vector<T> v(static_cast<std::size_t>(components));
  for (std::uint32_t p = 0; p < count; ++p) {
    const draco::AttributeValueIndex i = att.mapped_index(draco::PointIndex(p));
    att.ConvertValue<T>(i, static_cast<std::int8_t>(components), v.data());
    std::memcpy(&out[static_cast<std::size_t>(p) * components * sizeof(T)], v.data(), components * sizeof(T));
  }
  return out;
}

std::string attribute_bytes(const draco::PointAttribute& att, std::uint32_t count, int component, int components) {
  switch (component) {
    case 5120: return values<std::int8_t>(att, count, components);
    case 5121: return values<std::uint8_t>(att, count, components);
    case 5122: return values<std::int16_t>(att, count, components);
    case 5123: return values<std::uint16_t>(att, count, components);
    case 5125: return values<std::uint32_t>(att, count, components);
    default: return values<float>(att, count, components);
  }
}

// Draco attributes are scalars or vectors (0: any other accessor type).
int vector_components(const std::string& type) {
  static const std::pair<const char*, int> types[] = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}};
  for (const auto& [t, n] : types)
    if (type == t) return n;
  return 0;
}

// Appends `bytes` to the decoded buffer as a new view; its index.
int add_view(GltfDocument& doc, std::string& buffer, int buffer_index, const std::string& bytes) {
  while (buffer.size() % 4) buffer.push_back('\0');
  doc.json["bufferViews"].push_back({{"buffer", buffer_index}, {"byteOffset", buffer.size()}, {"byteLength", bytes.size()}});
  buffer += bytes;
  return static_cast<int>(doc.json["bufferViews"].size() - 1);
}

// Points accessor `a` (which must have no data of its own) at `bytes`.
void fill_accessor(GltfDocument& doc, std::string& buffer, int buffer_index, int a, const std::string& bytes) {
  json& acc = doc.json["accessors"][static_cast<std::size_t>(a)];
  acc["bufferView"] = add_view(doc, buffer, buffer_index, bytes);
  acc.erase("byteOffset");
}

void decode_primitive(GltfDocument& doc, json& prim, const std::string& path, std::string& buffer, int buffer_index) {
  const std::string& name = doc.name;
  const std::string at = path + "/extensions/KHR_draco_mesh_compression";
  const json& ext = prim["extensions"]["KHR_draco_mesh_compression"];
  if (!ext.is_object()) fail(name, at, "expected an object");
  const json& views = array_at(doc.json, "bufferViews", name, "");
  const int view = index_at(ext, "bufferView", views.size(), name, at);
  const json& v = views[static_cast<std::size_t>(view)];
  const std::string& source = doc.buffers[static_cast<std::size_t>(v["buffer"].get<std::int64_t>())];
  draco::DecoderBuffer stream;
  stream.Init(source.data() + v.value("byteOffset", std::int64_t{0}), static_cast<std::size_t>(v["byteLength"].get<std::int64_t>()));
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&stream);
  if (!decoded.ok()) fail(name, at, "not a Draco mesh: " + decoded.status().error_msg_string());
  const draco::Mesh& mesh = *decoded.value();
  const std::size_t naccessors = array_at(doc.json, "accessors", name, "").size();
  const json& attributes = ext.contains("attributes") ? ext["attributes"] : json::object();
  if (!attributes.is_object()) fail(name, at + "/attributes", "expected an object");
  for (auto it = attributes.begin(); it != attributes.end(); ++it) {
    const std::string ap = at + "/attributes/" + it.key();
    const std::int64_t id = integer(it.value(), name, ap);
    const draco::PointAttribute* att = id < 0 || id > UINT32_MAX ? nullptr : mesh.GetAttributeByUniqueId(static_cast<std::uint32_t>(id));
    if (!att) fail(name, ap, "no Draco attribute with id " + std::to_string(id));
    const int a = index_at(prim["attributes"], it.key().c_str(), naccessors, name, path + "/attributes");
    const json& acc = doc.json["accessors"][static_cast<std::size_t>(a)];
    const int components = vector_components(acc.value("type", std::string()));
    if (components == 0 || integer(acc.value("count", json(0)), name, "/accessors/" + std::to_string(a) + "/count") != mesh.num_points())
      fail(name, ap, "Draco attribute " + std::to_string(id) + " has " + std::to_string(mesh.num_points()) +
                         " points, accessor " + std::to_string(a) + " wants " + acc.value("count", json(0)).dump() + " of type " +
                         acc.value("type", json("?")).dump());
    const int component = static_cast<int>(integer(acc.value("componentType", json(5126)), name, "/accessors/" + std::to_string(a) + "/componentType"));
    fill_accessor(doc, buffer, buffer_index, a, attribute_bytes(*att, mesh.num_points(), component, components));
  }
  std::string idx(static_cast<std::size_t>(mesh.num_faces()) * 12, '\0');
  for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t p = mesh.face(f)[k].value();
      std::memcpy(&idx[(f.value() * 3 + k) * 4], &p, 4);
    }
  const int ia = index_at(prim, "indices", naccessors, name, path, true);
  if (ia < 0) fail(name, path + "/indices", "missing (a Draco primitive is indexed)");
  // The decoded indices are unsigned ints whatever the accessor said.
  json& acc = doc.json["accessors"][static_cast<std::size_t>(ia)];
  if (integer(acc.value("count", json(0)), name, "/accessors/" + std::to_string(ia) + "/count") != 3 * static_cast<std::int64_t>(mesh.num_faces()))
    fail(name, path + "/indices", "Draco mesh has " + std::to_string(mesh.num_faces()) + " triangles, accessor " +
                                      std::to_string(ia) + " wants " + acc.value("count", json(0)).dump() + " indices");
  acc["componentType"] = 5125;
  fill_accessor(doc, buffer, buffer_index, ia, idx);
}

}  // namespace

void decode_draco(GltfDocument& doc) {
  const json& meshes = array_at(doc.json, "meshes", doc.name, "");
  std::string buffer;
  const int buffer_index = static_cast<int>(doc.buffers.size());
  if (!doc.json.contains("bufferViews")) doc.json["bufferViews"] = json::array();
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const std::string path = "/meshes/" + std::to_string(m);
    const json& prims = array_at(meshes[m], "primitives", doc.name, path);
    for (std::size_t p = 0; p < prims.size(); ++p) {
      json& prim = doc.json["meshes"][m]["primitives"][p];
      if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object() ||
          !prim["extensions"].contains("KHR_draco_mesh_compression") || !prim.contains("attributes"))
        continue;
      // Points and lines are not read, nor rewritten: their stream stays.
      const json mode = prim.value("mode", json(4));
      if (!mode.is_number_integer() || mode.get<int>() < 4) continue;
      decode_primitive(doc, prim, path + "/primitives/" + std::to_string(p), buffer, buffer_index);
    }
  }
  if (buffer.empty()) return;
  doc.json["buffers"].push_back({{"byteLength", buffer.size()}});
  doc.buffers.push_back(std::move(buffer));
}

}  // namespace intrinsic::gltf
