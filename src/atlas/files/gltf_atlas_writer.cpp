// Writing the atlas back into the glTF document it was computed on
// (docs/formats.md "glTF"). glTF has one index per vertex for all
// attributes, so a vertex whose corners get different atlas coordinates is
// split: each (source vertex, atlas coordinate) pair becomes one output
// vertex carrying a byte-exact copy of every attribute and morph target
// delta of its source vertex, plus the atlas as one more TEXCOORD set. Each
// rewritten primitive is an indexed TRIANGLES list, faces in their order and
// winding (faces the atlas reoriented keep the document's); its old
// accessors, views and bytes are then dropped (gltf_prune.cpp). Everything
// outside the triangle primitives (nodes, materials, textures, images,
// animations, skins, cameras, extras, extensions) is copied as it was
// (KHR_draco_mesh_compression aside: the rewritten primitives are
// uncompressed); all buffers become one (the GLB binary chunk, or a base64
// data URI in a .gltf).
#include <cstring>
#include <functional>
#include <map>
#include <set>
#include <unordered_map>

#include "intrinsic/atlas_files.h"
#include "intrinsic/gltf.h"
#include "io/gltf_document.h"
#include "io/gltf_images.h"
#include "atlas/files/gltf_write_hook.h"

namespace intrinsic {

using nlohmann::json;

namespace {

using gltf::fail;

// The output's one buffer and the accessors added to it.
struct Output {
  json j;
  std::string bin;

  int add_view(const std::string& bytes, int stride, int target) {
    while (bin.size() % 4) bin.push_back('\0');
    json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}, {"target", target}};
    if (stride) v["byteStride"] = stride;
    bin += bytes;
    j["bufferViews"].push_back(v);
    return static_cast<int>(j["bufferViews"].size() - 1);
  }
  int add_accessor(json a) {
    j["accessors"].push_back(std::move(a));
    return static_cast<int>(j["accessors"].size() - 1);
  }
};

// Old buffers one after the other (16-byte aligned starts keep every
// accessor's alignment), their views moved along.
Output merge_buffers(const GltfDocument& doc) {
  Output out;
  out.j = doc.json;
  std::vector<std::size_t> base;
  for (const std::string& b : doc.buffers) {
    while (out.bin.size() % 16) out.bin.push_back('\0');
    base.push_back(out.bin.size());
    out.bin += b;
  }
  if (!out.j.contains("bufferViews")) out.j["bufferViews"] = json::array();
  if (!out.j.contains("accessors")) out.j["accessors"] = json::array();
  for (json& v : out.j["bufferViews"]) {
    const auto b = static_cast<std::size_t>(v["buffer"].get<std::int64_t>());
    v["buffer"] = 0;
    v["byteOffset"] = base[b] + v.value("byteOffset", std::size_t{0});
  }
  return out;
}

// The texture coordinate sets a material's textures read: every texture
// reference ("...Texture": {"index", "texCoord"}) anywhere in it, extensions
// included, with KHR_texture_transform's texCoord override.
void used_sets(const json& j, std::set<int>& sets) {
  if (j.is_array()) {
    for (const json& e : j) used_sets(e, sets);
    return;
  }
  if (!j.is_object()) return;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const json& v = it.value();
    const std::string& k = it.key();
    if (v.is_object() && v.contains("index") && k.size() >= 7 && k.compare(k.size() - 7, 7, "Texture") == 0) {
      auto set_of = [](const json& o, int fallback) {
        const auto t = o.find("texCoord");
        return t != o.end() && t->is_number_integer() ? t->get<int>() : fallback;
      };
      int set = set_of(v, 0);
      const auto ext = v.find("extensions");
      if (ext != v.end() && ext->is_object()) {
        const auto tt = ext->find("KHR_texture_transform");
        if (tt != ext->end() && tt->is_object()) set = set_of(*tt, set);
      }
      sets.insert(set);
    }
    used_sets(v, sets);
  }
}

// The TEXCOORD set the atlas goes to in this primitive.
int choose_set(const GltfDocument& doc, const json& prim, const std::string& path, const GltfWriteOptions& o) {
  int existing = 0;
  while (prim["attributes"].contains("TEXCOORD_" + std::to_string(existing))) ++existing;
  if (o.texcoord_set < 0) return existing;
  if (o.texcoord_set > existing)
    throw_usage(doc.name + ": " + path + ": TEXCOORD_" + std::to_string(o.texcoord_set) + " would leave a gap after " +
                (existing ? "TEXCOORD_" + std::to_string(existing - 1) : std::string("no texture coordinates")));
  if (o.texcoord_set < existing && !o.replace_used_set && prim.contains("material")) {
    const json& materials = gltf::array_at(doc.json, "materials", doc.name, "");
    const int m = gltf::index_at(prim, "material", materials.size(), doc.name, path);
    std::set<int> sets;
    used_sets(materials[static_cast<std::size_t>(m)], sets);
    if (sets.count(o.texcoord_set))
      throw_usage(doc.name + ": " + path + ": TEXCOORD_" + std::to_string(o.texcoord_set) + " is read by a texture of material " +
                  std::to_string(m) + " (" + option_label("transfer_textures", o.spelling) +
                  " to bake the textures into the atlas, or " + option_label("replace_used_set", o.spelling) +
                  " to replace it anyway)");
  }
  return o.texcoord_set;
}

// Per output vertex: its source vertex and atlas coordinate; per corner: the
// output vertex.
struct Split {
  std::vector<int> source, uv;
  std::vector<std::uint32_t> index;
};

// The atlas corner of input corner k of face f: the atlas lists a face it
// reoriented as 0, 2, 1; the document keeps its own winding (what it draws,
// with back faces culled, must not change).
int atlas_corner(const MeshData& data, const AtlasResult& r, int f, int k, const std::string& name) {
  if (r.F.row(f) == data.F.row(f)) return k;
  if (r.F(f, 0) == data.F(f, 0) && r.F(f, 1) == data.F(f, 2) && r.F(f, 2) == data.F(f, 1)) return k == 0 ? 0 : 3 - k;
  throw_input(name + ": the atlas does not belong to this document (face " + std::to_string(f) + ")");
}

Split split_primitive(const GltfDocument& doc, const GltfDocument::Primitive& p, const MeshData& data,
                      const AtlasResult& r) {
  Split s;
  std::unordered_map<std::uint64_t, std::uint32_t> seen;
  for (int f = p.first_face; f < p.first_face + p.face_count; ++f)
    for (int k = 0; k < 3; ++k) {
      const int c = atlas_corner(data, r, f, k, doc.name);
      const int v = r.F(f, c), t = r.FUV(f, c);
      if (v < p.first_vertex || v >= p.first_vertex + p.vertex_count || t < 0 || t >= r.UV.rows())
        throw_input(doc.name + ": the atlas does not belong to this document (face " + std::to_string(f) + ")");
      const int src = doc.vertex_source[static_cast<std::size_t>(v)];
      const std::uint64_t key = static_cast<std::uint64_t>(src) << 32 | static_cast<std::uint32_t>(t);
      const auto [it, fresh] = seen.emplace(key, static_cast<std::uint32_t>(s.source.size()));
      if (fresh) s.source.push_back(src), s.uv.push_back(t);
      s.index.push_back(it->second);
    }
  return s;
}

// A new accessor holding source elements `s.source` of `a`, byte for byte;
// elements padded to 4 bytes (glTF's vertex alignment) with a byteStride.
int gather(Output& out, const gltf::Accessor& a, const json& source_json, bool position, const Split& s) {
  const int size = a.element_size();
  const int stride = (size + 3) / 4 * 4;
  std::string bytes(s.source.size() * static_cast<std::size_t>(stride), '\0');
  for (std::size_t i = 0; i < s.source.size(); ++i)
    std::memcpy(&bytes[i * stride], &a.bytes[static_cast<std::size_t>(s.source[i]) * size], static_cast<std::size_t>(size));
  json acc = {{"bufferView", out.add_view(bytes, stride == size ? 0 : stride, 34962)},
              {"componentType", a.component},
              {"type", a.type},
              {"count", s.source.size()}};
  if (a.normalized) acc["normalized"] = true;
  if (position || source_json.contains("min") || source_json.contains("max")) {
    json lo = json::array(), hi = json::array();
    for (int k = 0; k < a.components; ++k) {
      double mn = a.raw(s.source[0], k), mx = mn;
      for (const int v : s.source) mn = std::min(mn, a.raw(v, k)), mx = std::max(mx, a.raw(v, k));
      lo.push_back(mn);
      hi.push_back(mx);
    }
    acc["min"] = lo;
    acc["max"] = hi;
  }
  return out.add_accessor(std::move(acc));
}

using AccessorCache = std::map<int, gltf::Accessor>;

// The primitive rewritten: the same JSON object with new accessors for
// indices, attributes, morph targets and the atlas set.
json rewrite_primitive(Output& out, const GltfDocument& doc, const GltfDocument::Primitive& p, const Split& s,
                       const AtlasResult& r, int set, AccessorCache& cache) {
  const json& prim = doc.json["meshes"][static_cast<std::size_t>(p.mesh)]["primitives"][static_cast<std::size_t>(p.primitive)];
  auto accessor = [&](int i) -> const gltf::Accessor& {
    auto it = cache.find(i);
    if (it == cache.end()) it = cache.emplace(i, gltf::read_accessor(doc, i, INT64_MAX)).first;
    return it->second;
  };
  auto copy_set = [&](const json& set_in) {
    json set_out = json::object();
    for (auto it = set_in.begin(); it != set_in.end(); ++it) {
      const int i = it.value().get<int>();
      set_out[it.key()] = gather(out, accessor(i), doc.json["accessors"][static_cast<std::size_t>(i)],
                                 it.key() == "POSITION", s);
    }
    return set_out;
  };
  json np = prim;
  np.erase("mode");
  np["attributes"] = copy_set(prim["attributes"]);
  if (prim.contains("targets"))
    for (std::size_t t = 0; t < prim["targets"].size(); ++t) np["targets"][t] = copy_set(prim["targets"][t]);
  std::string uv(s.uv.size() * 8, '\0');
  for (std::size_t i = 0; i < s.uv.size(); ++i) {
    // glTF's texture origin is the top-left corner, ours the bottom-left.
    const float c[2] = {static_cast<float>(r.UV(s.uv[i], 0)), static_cast<float>(1 - r.UV(s.uv[i], 1))};
    std::memcpy(&uv[i * 8], c, 8);
  }
  np["attributes"]["TEXCOORD_" + std::to_string(set)] = out.add_accessor(
      {{"bufferView", out.add_view(uv, 0, 34962)}, {"componentType", 5126}, {"type", "VEC2"}, {"count", s.uv.size()}});
  std::string idx(s.index.size() * 4, '\0');
  std::memcpy(&idx[0], s.index.data(), idx.size());
  np["indices"] = out.add_accessor({{"bufferView", out.add_view(idx, 0, 34963)},
                                    {"componentType", 5125},
                                    {"type", "SCALAR"},
                                    {"count", s.index.size()}});
  // An optional Draco stream would now describe other vertices; the plain
  // attributes above are the data.
  if (np.contains("extensions") && np["extensions"].is_object()) {
    np["extensions"].erase("KHR_draco_mesh_compression");
    if (np["extensions"].empty()) np.erase("extensions");
  }
  return np;
}

// Rewritten primitives are written uncompressed: once no primitive keeps a
// Draco stream, the document no longer uses (or requires) the extension.
void drop_unused_draco(json& j) {
  const char* draco = "KHR_draco_mesh_compression";
  if (j.contains("meshes"))
    for (const json& m : j["meshes"])
      if (m.is_object() && m.contains("primitives") && m["primitives"].is_array())
        for (const json& p : m["primitives"])
          if (p.is_object() && p.contains("extensions") && p["extensions"].is_object() && p["extensions"].contains(draco))
            return;
  for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
    if (!j.contains(list) || !j[list].is_array()) continue;
    json kept = json::array();
    for (const json& e : j[list])
      if (e != draco) kept.push_back(e);
    if (kept.empty()) j.erase(list);
    else j[list] = kept;
  }
}

std::string glb_bytes(const json& j, const std::string& bin) {
  std::string text = j.dump();
  while (text.size() % 4) text += ' ';
  std::string data = bin;
  while (data.size() % 4) data += '\0';
  auto u32 = [](std::string& s, std::uint32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); };
  std::string out = "glTF";
  u32(out, 2);
  u32(out, static_cast<std::uint32_t>(12 + 8 + text.size() + (data.empty() ? 0 : 8 + data.size())));
  u32(out, static_cast<std::uint32_t>(text.size()));
  u32(out, 0x4E4F534Au);
  out += text;
  if (!data.empty()) {
    u32(out, static_cast<std::uint32_t>(data.size()));
    u32(out, 0x004E4942u);
    out += data;
  }
  return out;
}

GltfWriteResult write_document(const std::string& path, const MeshFile& input, const AtlasResult& r,
                               const GltfWriteOptions& o, const GltfWriteHook& hook) {
  const MeshData& data = input.mesh;
  const std::string ext = mesh_extension(path);
  if (ext != ".glb" && ext != ".gltf") throw_usage("output '" + path + "': a glTF document is written as .glb or .gltf");
  if (!input.document.gltf) throw_usage("output '" + path + "': " + data.path + " was not read from a glTF document");
  const GltfDocument& doc = *input.document.gltf;
  if (r.F.rows() != static_cast<Eigen::Index>(doc.face_primitive.size()) || r.FUV.rows() != r.F.rows() ||
      data.F.rows() != r.F.rows() ||
      data.V.rows() != static_cast<Eigen::Index>(doc.vertex_source.size()))
    throw_input(doc.name + ": the atlas does not belong to this document (face or vertex counts differ)");
  Output out = merge_buffers(doc);
  AccessorCache cache;
  std::vector<GltfWrittenPrimitive> written;
  for (const GltfDocument::Primitive& p : doc.primitives) {
    if (p.face_count == 0) continue;  // nothing drawn: left as it was
    const std::string where = "/meshes/" + std::to_string(p.mesh) + "/primitives/" + std::to_string(p.primitive);
    const json& prim = doc.json["meshes"][static_cast<std::size_t>(p.mesh)]["primitives"][static_cast<std::size_t>(p.primitive)];
    const int set = choose_set(doc, prim, where, o);
    Split s = split_primitive(doc, p, data, r);
    out.j["meshes"][static_cast<std::size_t>(p.mesh)]["primitives"][static_cast<std::size_t>(p.primitive)] =
        rewrite_primitive(out, doc, p, s, r, set, cache);
    if (hook) written.push_back({&p, set, std::move(s.source), std::move(s.uv), std::move(s.index)});
  }
  // The hook (texture transfer) adds images and their buffer views before
  // pruning, so they count as referenced.
  if (hook) hook(out.j, out.bin, written);
  drop_unused_draco(out.j);
  GltfWriteResult result;
  if (o.prune) {
    const gltf::PruneOutcome p = gltf::prune_unreferenced(out.j, out.bin);
    result.pruned = p.pruned;
    result.accessors_dropped = p.accessors_dropped;
    result.views_dropped = p.views_dropped;
    result.bytes_dropped = p.bytes_dropped;
    if (!p.pruned)
      result.note = doc.name + ": extension " + p.kept_because +
                    " could reference accessors or buffer views: unused data kept, not pruned";
    // Images a texture transfer replaced go with their views (pruned again).
    if (p.pruned) result.image_index = gltf::prune_replaced_textures(doc.json, out.j);
    if (!result.image_index.empty()) {
      const gltf::PruneOutcome again = gltf::prune_unreferenced(out.j, out.bin);
      result.views_dropped += again.views_dropped;
      result.bytes_dropped += again.bytes_dropped;
    }
  }
  gltf::PortableImages images = gltf::make_images_portable(out.j, out.bin, doc, path, o.allow_missing_images);
  result.missing_images = images.missing;
  if (out.bin.size() > 0xFFFFFFF0u) throw_output(path + ": more than 4 GiB of buffer data (GLB's limit)");
  json buffer = {{"byteLength", out.bin.size()}};
  if (ext == ".gltf") buffer["uri"] = "data:application/octet-stream;base64," + gltf::base64_encode(out.bin);
  out.j["buffers"] = json::array({buffer});
  // The images beside a .gltf first, the document last: a failure on the way
  // removes what this call wrote.
  for (const auto& [file, bytes] : images.beside) result.files.push_back(file);
  images.beside.emplace_back(path, ext == ".gltf" ? out.j.dump(1, '\t') : glb_bytes(out.j, out.bin));
  write_all(images.beside);
  return result;
}

}  // namespace

GltfWriteResult write_gltf_atlas(const std::string& path, const MeshFile& input, const AtlasResult& r,
                                 const GltfWriteOptions& o) {
  return write_gltf_atlas_hooked(path, input, r, o, {});
}

GltfWriteResult write_gltf_atlas_hooked(const std::string& path, const MeshFile& input, const AtlasResult& r,
                                        const GltfWriteOptions& o, const GltfWriteHook& hook) {
  // Every JSON access above checks its type first; should one have been
  // missed, the document is refused, not the program ended.
  try {
    return write_document(path, input, r, o, hook);
  } catch (const nlohmann::json::exception& e) {
    const GltfDocument* doc = input.document.gltf.get();
    throw_input((doc ? doc->name : path) + ": unexpected JSON in the document: " + e.what());
  }
}

}  // namespace intrinsic
