// The glTF side of the texture transfer (docs/textures.md): when the atlas
// replaces the TEXCOORD set materials' textures read, every such texture
// slot is baked anew in the new layout. Slots sharing image, sampler,
// transform and role are baked once over the union of their triangles; the
// baked PNG is embedded (a buffer view), a new texture with a clamping
// sampler points at it (the new atlas lies inside [0,1]: repeating would
// bleed the opposite border into edge charts), and the slot reads the
// replaced set with its KHR_texture_transform baked in. Normal maps are
// re-expressed in the new tangent frame, which is written as TANGENT.
#include <algorithm>
#include <cmath>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <set>

#include "intrinsic/error.h"
#include "texture/gltf_textures.h"

#include "io/gltf_images.h"
#include "texture/texture_internal.h"

namespace intrinsic::gltf_textures {
namespace {

struct Slot {
  std::string pointer;  // inside the material, e.g. "/pbrMetallicRoughness/baseColorTexture"
  TextureRole role = TextureRole::Color;
};

TextureRole role_of(const std::string& key) {
  if (key == "normalTexture" || key == "clearcoatNormalTexture") return TextureRole::TangentNormal;
  static const std::set<std::string> colour = {"baseColorTexture",  "emissiveTexture",      "diffuseTexture",
                                               "specularGlossinessTexture", "sheenColorTexture",
                                               "specularColorTexture"};
  return colour.count(key) ? TextureRole::Color : TextureRole::Data;
}

// Every textureInfo ("...Texture": {"index", ...}) in a material, extensions included.
void find_slots(const json& j, const std::string& pointer, std::vector<Slot>& slots) {
  if (!j.is_object()) return;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& k = it.key();
    const std::string here = pointer + "/" + k;
    if (it->is_object() && it->contains("index") && k.size() >= 7 && k.compare(k.size() - 7, 7, "Texture") == 0)
      slots.push_back({here, role_of(k)});
    else find_slots(*it, here, slots);
  }
}

const json* texture_transform(const json& info) {
  const auto ext = info.find("extensions");
  if (ext == info.end() || !ext->is_object()) return nullptr;
  const auto t = ext->find("KHR_texture_transform");
  return t != ext->end() && t->is_object() ? &*t : nullptr;
}

int slot_set(const json& info) {
  int set = info.contains("texCoord") && info["texCoord"].is_number_integer() ? info["texCoord"].get<int>() : 0;
  if (const json* t = texture_transform(info))
    if (t->contains("texCoord") && (*t)["texCoord"].is_number_integer()) set = (*t)["texCoord"].get<int>();
  return set;
}

TextureTransform transform_of(const json& info, const std::string& name, const std::string& path) {
  TextureTransform t;
  const json* j = texture_transform(info);
  if (!j) return t;
  auto pair = [&](const char* key, double& a, double& b) {
    if (!j->contains(key)) return;
    const json& v = (*j)[key];
    if (!v.is_array() || v.size() != 2) gltf::fail(name, path + "/extensions/KHR_texture_transform/" + key, "expected two numbers");
    a = gltf::number(v[0], name, path), b = gltf::number(v[1], name, path);
  };
  pair("offset", t.offset_u, t.offset_v);
  pair("scale", t.scale_u, t.scale_v);
  if (j->contains("rotation")) t.rotation = gltf::number((*j)["rotation"], name, path);
  return t;
}

// One bake: a source image seen through one sampler and transform, in one
// role, over the triangles of every primitive whose material reads it.
struct Group {
  int image = -1, sampler = -1;
  TextureRole role = TextureRole::Color;
  TextureSampler sampling;
  std::vector<int> written;                            // indices into the written primitives
  std::vector<std::pair<int, std::string>> slots;      // (material, slot pointer)
};

TextureSampler sampler_of(const GltfDocument& doc, int sampler, const std::string& where) {
  TextureSampler s;
  if (sampler < 0) return s;
  const json& j = doc.json["samplers"][static_cast<std::size_t>(sampler)];
  const std::string path = "/samplers/" + std::to_string(sampler);
  for (const char* key : {"wrapS", "wrapT"}) {
    if (!j.contains(key)) continue;
    const auto code = gltf::integer(j[key], doc.name, path + "/" + key);
    if (code != 10497 && code != 33071 && code != 33648)
      gltf::fail(doc.name, path + "/" + key, "wrap mode " + std::to_string(code) + " is not one glTF defines (" +
                                                  where + "): cannot bake the texture");
    (key[4] == 'S' ? s.wrap_u : s.wrap_v) = texture_wrap_from_gltf(static_cast<int>(code));
  }
  if (j.contains("magFilter"))
    s.filter = texture_filter_from_gltf(static_cast<int>(gltf::integer(j["magFilter"], doc.name, path + "/magFilter")));
  return s;
}

std::string material_label(const json& materials, int m) {
  const json& mat = materials[static_cast<std::size_t>(m)];
  std::string s = "material " + std::to_string(m);
  if (mat.contains("name") && mat["name"].is_string()) s += " '" + mat["name"].get<std::string>() + "'";
  return s;
}

std::string image_label(const GltfDocument& doc, int image) {
  const json& img = doc.json["images"][static_cast<std::size_t>(image)];
  std::string s = "image " + std::to_string(image);
  if (img.contains("name") && img["name"].is_string()) s += " '" + img["name"].get<std::string>() + "'";
  else if (img.contains("uri") && img["uri"].is_string() && img["uri"].get<std::string>().rfind("data:", 0) != 0)
    s += " '" + img["uri"].get<std::string>() + "'";
  return s;
}

// The bytes of an image file beside the document (the errno kept for the message).
std::string read_image_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw_input_file("cannot open '" + path + "': " + std::strerror(errno), errno);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// The image decoded from its buffer view, data URI or file beside the document.
Texture decode_image(const GltfDocument& doc, int image, const std::string& where) {
  const std::string path = "/images/" + std::to_string(image);
  const json& img = doc.json["images"][static_cast<std::size_t>(image)];
  const std::string label = doc.name + ": " + image_label(doc, image) + " (" + where + ")";
  try {
    if (img.contains("bufferView")) {
      const json& views = gltf::array_at(doc.json, "bufferViews", doc.name, "");
      const int v = gltf::index_at(img, "bufferView", views.size(), doc.name, path);
      const json& view = views[static_cast<std::size_t>(v)];
      const auto b = static_cast<std::size_t>(gltf::integer(view["buffer"], doc.name, "/bufferViews"));
      const auto offset = static_cast<std::size_t>(view.value("byteOffset", std::int64_t{0}));
      const auto length = static_cast<std::size_t>(gltf::integer(view["byteLength"], doc.name, "/bufferViews"));
      return decode_texture(doc.buffers.at(b).substr(offset, length), label);
    }
    if (!img.contains("uri") || !img["uri"].is_string()) gltf::fail(doc.name, path, "neither bufferView nor uri");
    const std::string& uri = img["uri"].get_ref<const std::string&>();
    if (uri.rfind("data:", 0) == 0) {
      const auto comma = uri.find(";base64,");
      if (comma == std::string::npos) gltf::fail(doc.name, path + "/uri", "data URI that is not base64");
      return decode_texture(gltf::base64_decode(uri, comma + 8, doc.name, path + "/uri"), label);
    }
    const std::string file = gltf::image_file(doc, uri);
    if (file.empty()) throw_input("'" + uri + "' not found beside the document");
    return decode_texture(read_image_file(file), label);
  } catch (const Error& e) {
    throw Error(ErrorKind::Input, label + ": cannot use the image: " + e.what(), e.os_error());
  }
}


std::string group_key(int image, int sampler, TextureRole role, const TextureTransform& t) {
  char b[256];
  std::snprintf(b, sizeof b, "%d/%d/%d/%.17g/%.17g/%.17g/%.17g/%.17g", image, sampler, static_cast<int>(role), t.offset_u,
                t.offset_v, t.rotation, t.scale_u, t.scale_v);
  return b;
}

// The slots of `material` that read `set`, added to their groups (one per
// image, sampler, role and transform) with the material's primitives.
bool add_slots(const GltfDocument& doc, int material, int set, const std::vector<int>& prims,
               std::map<std::string, std::size_t>& index, std::vector<Group>& groups) {
  const json& materials = doc.json["materials"];
  const json& textures = gltf::array_at(doc.json, "textures", doc.name, "");
  const json& images = gltf::array_at(doc.json, "images", doc.name, "");
  const json& samplers = gltf::array_at(doc.json, "samplers", doc.name, "");
  std::vector<Slot> slots;
  find_slots(materials[static_cast<std::size_t>(material)], "", slots);
  bool any = false;
  for (const Slot& s : slots) {
    const std::string path = "/materials/" + std::to_string(material) + s.pointer;
    const json& info = materials[static_cast<std::size_t>(material)].at(json::json_pointer(s.pointer));
    if (slot_set(info) != set) continue;
    any = true;
    const std::string where = material_label(materials, material) + ", " + s.pointer.substr(1);
    const int t = gltf::index_at(info, "index", textures.size(), doc.name, path);
    const json& tex = textures[static_cast<std::size_t>(t)];
    const std::string tpath = "/textures/" + std::to_string(t);
    if (!tex.contains("source"))
      gltf::fail(doc.name, tpath, "no PNG or JPEG source (" + where + "): an image given only through an extension cannot be baked");
    const int image = gltf::index_at(tex, "source", images.size(), doc.name, tpath);
    const int sampler = gltf::index_at(tex, "sampler", samplers.size(), doc.name, tpath, true);
    TextureSampler sampling = sampler_of(doc, sampler, where);
    sampling.transform = transform_of(info, doc.name, path);
    const auto [it, fresh] = index.emplace(group_key(image, sampler, s.role, sampling.transform), groups.size());
    if (fresh) groups.push_back({image, sampler, s.role, sampling, {}, {}});
    Group& g = groups[it->second];
    for (const int p : prims)
      if (std::find(g.written.begin(), g.written.end(), p) == g.written.end()) g.written.push_back(p);
    g.slots.emplace_back(material, s.pointer);
  }
  return any;
}

// The groups of every material a written primitive uses; a note for each
// material with no texture on the replaced set.
std::vector<Group> collect_groups(const GltfDocument& doc, const std::vector<GltfWrittenPrimitive>& written,
                                  TextureTransferReport& report) {
  const json& materials = gltf::array_at(doc.json, "materials", doc.name, "");
  std::map<int, std::vector<int>> by_material;
  for (std::size_t i = 0; i < written.size(); ++i) {
    const GltfDocument::Primitive& p = *written[i].source;
    const json& prim = doc.json["meshes"][static_cast<std::size_t>(p.mesh)]["primitives"][static_cast<std::size_t>(p.primitive)];
    const std::string path = "/meshes/" + std::to_string(p.mesh) + "/primitives/" + std::to_string(p.primitive);
    const int m = gltf::index_at(prim, "material", materials.size(), doc.name, path, true);
    if (m >= 0) by_material[m].push_back(static_cast<int>(i));
  }
  std::map<std::string, std::size_t> index;
  std::vector<Group> groups;
  for (const auto& [m, prims] : by_material) {
    const int set = written[static_cast<std::size_t>(prims[0])].set;
    if (!add_slots(doc, m, set, prims, index, groups))
      report.notes.push_back(material_label(materials, m) + " has no texture on TEXCOORD_" + std::to_string(set) +
                             ": nothing baked for it");
  }
  return groups;
}

// glTF's TANGENT has its bitangent up the image (MikkTSpace on v up), so
// tangents are computed on (u, 1 - v) of the image-convention UVs.
Eigen::MatrixX2d v_up(Eigen::MatrixX2d uv) {
  uv.col(1) = (1 - uv.col(1).array()).matrix();
  return uv;
}

// Everything the bakes of one document share.
struct Context {
  const GltfDocument& doc;
  const AtlasResult& r;
  const std::vector<GltfWrittenPrimitive>& written;
  const TextureTransferOptions& options;
  TextureTransferReport& report;
  json& out;
  std::string& bin;
  AccessorCache accessors;
  std::map<int, Corners> corners;                // per written primitive
  std::map<int, Eigen::MatrixX4d> new_tangents;  // per written primitive with a normal map
  std::map<int, Texture> images;
  std::map<std::string, int> samplers;           // new clamping samplers by their JSON

  const Corners& corners_of(int p) {
    auto it = corners.find(p);
    if (it == corners.end())
      it = corners.emplace(p, gather_corners(doc, written[static_cast<std::size_t>(p)], r, accessors)).first;
    return it->second;
  }
  const Eigen::MatrixX4d& new_tangent_of(int p) {
    auto it = new_tangents.find(p);
    if (it == new_tangents.end()) {
      const Corners& c = corners_of(p);
      it = new_tangents.emplace(p, sane_tangents(compute_tangents(c.position, c.normal, v_up(c.new_uv)), c.normal)).first;
    }
    return it->second;
  }
};

template <typename M>
void append(M& to, const M& rows) {
  const Eigen::Index n = to.rows();
  to.conservativeResize(n + rows.rows(), rows.cols());
  to.bottomRows(rows.rows()) = rows;
}

// The group's triangles through both layouts (and tangent frames for a normal map).
TransferMesh transfer_mesh(Context& cx, const Group& g) {
  TransferMesh tm;
  tm.old_uv.resize(0, 2), tm.new_uv.resize(0, 2), tm.normal.resize(0, 3);
  tm.old_tangent.resize(0, 4), tm.new_tangent.resize(0, 4);
  for (const int p : g.written) {
    const Corners& c = cx.corners_of(p);
    if (c.old_uv.rows() == 0) continue;  // the primitive had no such set: nothing to read
    append(tm.old_uv, c.old_uv);
    append(tm.new_uv, c.new_uv);
    if (g.role != TextureRole::TangentNormal) continue;
    append(tm.normal, c.normal);
    const Eigen::MatrixX4d old_tangent =
        c.old_tangent.rows() ? c.old_tangent
                             : sane_tangents(compute_tangents(c.position, c.normal,
                                                              v_up(transformed(c.old_uv, g.sampling.transform))),
                                             c.normal);
    append(tm.old_tangent, old_tangent);
    append(tm.new_tangent, cx.new_tangent_of(p));
  }
  return tm;
}

int clamping_sampler(Context& cx, int old_sampler) {
  json s = json::object();
  if (old_sampler >= 0) {
    const json& o = cx.doc.json["samplers"][static_cast<std::size_t>(old_sampler)];
    for (const char* k : {"magFilter", "minFilter"})
      if (o.contains(k)) s[k] = o[k];
  }
  s["wrapS"] = 33071, s["wrapT"] = 33071;
  const auto [it, fresh] = cx.samplers.emplace(s.dump(), 0);
  if (fresh) {
    if (!cx.out.contains("samplers")) cx.out["samplers"] = json::array();
    cx.out["samplers"].push_back(s);
    it->second = static_cast<int>(cx.out["samplers"].size() - 1);
  }
  return it->second;
}

// The baked image, its texture, the group's slots pointed at it.
void write_baked(Context& cx, const Group& g, const TransferResult& res) {
  const std::string png = encode_texture_png(res.texture);
  // glTF refuses empty arrays: created only with their first entry.
  if (!cx.out.contains("images")) cx.out["images"] = json::array();
  if (!cx.out.contains("textures")) cx.out["textures"] = json::array();
  json image = {{"bufferView", add_view(cx.out, cx.bin, png, 0)}, {"mimeType", "image/png"}};
  const json& old_image = cx.doc.json["images"][static_cast<std::size_t>(g.image)];
  if (old_image.contains("name") && old_image["name"].is_string()) image["name"] = old_image["name"].get<std::string>() + " (atlas)";
  cx.out["images"].push_back(image);
  const int new_image = static_cast<int>(cx.out["images"].size() - 1);
  cx.out["textures"].push_back({{"source", new_image}, {"sampler", clamping_sampler(cx, g.sampler)}});
  const int texture = static_cast<int>(cx.out["textures"].size() - 1);
  for (const auto& [m, pointer] : g.slots) {
    json& info = cx.out["materials"][static_cast<std::size_t>(m)].at(json::json_pointer(pointer));
    const int set = slot_set(info);
    info["index"] = texture;
    if (set) info["texCoord"] = set;
    else info.erase("texCoord");
    if (info.contains("extensions")) {
      info["extensions"].erase("KHR_texture_transform");
      if (info["extensions"].empty()) info.erase("extensions");
    }
    BakedTexture b;
    b.material = m;
    const json& mat = cx.doc.json["materials"][static_cast<std::size_t>(m)];
    if (mat.contains("name") && mat["name"].is_string()) b.material_name = mat["name"].get<std::string>();
    b.slot = pointer.substr(1);
    b.source = image_label(cx.doc, g.image);
    b.output = "image " + std::to_string(new_image);
    b.width = res.texture.width, b.height = res.texture.height;
    b.texels_covered = res.texels_covered;
    cx.report.baked.push_back(b);
  }
}

void bake_group(Context& cx, const Group& g) {
  const std::string where = material_label(cx.doc.json["materials"], g.slots[0].first) + ", " + g.slots[0].second.substr(1);
  const TransferMesh tm = transfer_mesh(cx, g);
  if (tm.old_uv.rows() == 0) {
    cx.report.notes.push_back(where + ": no primitive has the set it reads; left as it was");
    return;
  }
  auto it = cx.images.find(g.image);
  if (it == cx.images.end()) it = cx.images.emplace(g.image, decode_image(cx.doc, g.image, where)).first;
  const Texture& source = it->second;
  TransferOptions to;
  to.role = g.role;
  to.padding = cx.options.padding;
  to.supersample = cx.options.supersample;
  to.width = to.height = cx.options.size;
  if (cx.options.size == 0) {
    const TextureTransform& t = g.sampling.transform;
    const double scale = std::sqrt(detail::corner_uv_area(tm.old_uv) * std::abs(t.scale_u * t.scale_v) /
                                   std::max(detail::corner_uv_area(tm.new_uv), 1e-30));
    to.width = static_cast<int>(std::clamp<double>(std::lround(source.width * scale), 16, 16384));
    to.height = static_cast<int>(std::clamp<double>(std::lround(source.height * scale), 16, 16384));
  }
  write_baked(cx, g, transfer_texture(tm, source, g.sampling, to));
  if (g.role == TextureRole::TangentNormal)
    for (const int p : g.written) cx.new_tangent_of(p);  // marks the primitive for its TANGENT
}

// KHR_texture_transform no longer declared once no material uses it.
void drop_unused_transform(json& out) {
  if (out.contains("materials") && out["materials"].dump().find("\"KHR_texture_transform\"") != std::string::npos) return;
  for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
    if (!out.contains(list) || !out[list].is_array()) continue;
    json kept = json::array();
    for (const json& e : out[list])
      if (e != "KHR_texture_transform") kept.push_back(e);
    if (kept.empty()) out.erase(list);
    else out[list] = kept;
  }
}

}  // namespace

GltfWriteHook texture_hook(const GltfDocument& doc, const AtlasResult& r, const TextureTransferOptions& options,
                           TextureTransferReport& report) {
  return [&doc, &r, &options, &report](json& out, std::string& bin, const std::vector<GltfWrittenPrimitive>& written) {
    const std::vector<Group> groups = collect_groups(doc, written, report);
    Context cx{doc, r, written, options, report, out, bin, {}, {}, {}, {}, {}};
    for (const Group& g : groups) bake_group(cx, g);
    for (const auto& [p, tangent] : cx.new_tangents)
      if (cx.corners_of(p).has_normal) write_tangents(out, bin, written[static_cast<std::size_t>(p)], tangent);
    drop_unused_transform(out);
  };
}

}  // namespace intrinsic::gltf_textures
