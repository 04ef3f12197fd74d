// Dropping what a rewritten glTF document no longer uses (docs/formats.md
// "glTF"): the writer appends new accessors for every rewritten primitive,
// so the old ones, their buffer views and their bytes would otherwise stay
// in the file unreferenced and every round trip would grow it. This walks
// every place the glTF 2.0 spec (and the extensions listed below) lets an
// accessor or a buffer view be named, keeps what is reachable, renumbers
// those references and compacts the one buffer. A document using an
// extension not known here is left whole: such an extension could name an
// accessor or a view that this walk would not see.
#include <functional>
#include <set>

#include "io/gltf_document.h"

namespace intrinsic::gltf {

using nlohmann::json;

namespace {

// Extensions that hold no accessor or buffer view index.
bool harmless(const std::string& e) {
  static const char* names[] = {"KHR_texture_transform", "KHR_lights_punctual",  "KHR_mesh_quantization",
                                "KHR_texture_basisu",    "EXT_texture_webp",     "EXT_texture_avif",
                                "KHR_xmp_json_ld",       "KHR_animation_pointer", "KHR_materials_variants"};
  for (const char* n : names)
    if (e == n) return true;
  return e.compare(0, 14, "KHR_materials_") == 0;
}

// Extensions whose references the walk below knows.
bool walked(const std::string& e) {
  return e == "KHR_draco_mesh_compression" || e == "EXT_mesh_gpu_instancing";
}

// The first extension named anywhere in `j` (extensionsUsed or an
// "extensions" object) that is neither harmless nor walked; "" when none.
std::string unknown_extension(const json& j) {
  if (j.is_array()) {
    for (const json& e : j) {
      const std::string u = unknown_extension(e);
      if (!u.empty()) return u;
    }
    return "";
  }
  if (!j.is_object()) return "";
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it.key() == "extras") continue;  // application data, not glTF references
    if (it.key() == "extensions" && it->is_object())
      for (auto e = it->begin(); e != it->end(); ++e)
        if (!harmless(e.key()) && !walked(e.key())) return e.key();
    if (it.key() == "extensionsUsed" && it->is_array())
      for (const json& e : *it)
        if (e.is_string() && !harmless(e.get<std::string>()) && !walked(e.get<std::string>())) return e.get<std::string>();
    const std::string u = unknown_extension(*it);
    if (!u.empty()) return u;
  }
  return "";
}

using Slot = std::function<void(json& index)>;

json* member(json& j, const char* key) {
  if (!j.is_object()) return nullptr;
  const auto it = j.find(key);
  return it == j.end() ? nullptr : &*it;
}

json* extension(json& j, const char* name) {
  json* e = member(j, "extensions");
  return e ? member(*e, name) : nullptr;
}

void each_value(json* set, const Slot& f) {
  if (set && set->is_object())
    for (auto it = set->begin(); it != set->end(); ++it) f(it.value());
}

void each(json& j, const char* key, const std::function<void(json&)>& f) {
  json* a = member(j, key);
  if (a && a->is_array())
    for (json& e : *a) f(e);
}

// Every accessor index outside the accessors themselves.
void accessor_slots(json& j, const Slot& f) {
  auto maybe = [&](json& o, const char* key) {
    if (json* s = member(o, key)) f(*s);
  };
  each(j, "meshes", [&](json& m) {
    each(m, "primitives", [&](json& p) {
      each_value(member(p, "attributes"), f);
      maybe(p, "indices");
      each(p, "targets", [&](json& t) { each_value(&t, f); });
      // Draco's attribute map holds Draco attribute ids, not accessors.
    });
  });
  each(j, "skins", [&](json& s) { maybe(s, "inverseBindMatrices"); });
  each(j, "animations", [&](json& a) {
    each(a, "samplers", [&](json& s) {
      maybe(s, "input");
      maybe(s, "output");
    });
  });
  each(j, "nodes", [&](json& n) {
    if (json* g = extension(n, "EXT_mesh_gpu_instancing")) each_value(member(*g, "attributes"), f);
  });
}

// Every buffer view index outside the views themselves: images, Draco
// streams, and the accessors' (with their sparse parts).
void view_slots(json& j, const Slot& f) {
  auto maybe = [&](json* o, const char* key) {
    if (!o) return;
    if (json* s = member(*o, key)) f(*s);
  };
  each(j, "images", [&](json& i) { maybe(&i, "bufferView"); });
  each(j, "meshes", [&](json& m) {
    each(m, "primitives", [&](json& p) { maybe(extension(p, "KHR_draco_mesh_compression"), "bufferView"); });
  });
  each(j, "accessors", [&](json& a) {
    maybe(&a, "bufferView");
    if (json* s = member(a, "sparse")) {
      maybe(member(*s, "indices"), "bufferView");
      maybe(member(*s, "values"), "bufferView");
    }
  });
}

// Old index -> new index for the entries of `key` whose `used` is set, the
// array itself reduced to them.
std::vector<std::int64_t> keep_used(json& j, const char* key, const std::vector<bool>& used) {
  std::vector<std::int64_t> to(used.size(), -1);
  json kept = json::array();
  for (std::size_t i = 0; i < used.size(); ++i)
    if (used[i]) {
      to[i] = static_cast<std::int64_t>(kept.size());
      kept.push_back(std::move(j[key][i]));
    }
  if (kept.empty()) j.erase(key);
  else j[key] = std::move(kept);
  return to;
}

std::vector<bool> mark(json& j, const char* key, const std::function<void(json&, const Slot&)>& slots) {
  json* a = member(j, key);
  std::vector<bool> used(a && a->is_array() ? a->size() : 0, false);
  slots(j, [&](json& i) {
    if (i.is_number_integer() && i.get<std::int64_t>() >= 0 && static_cast<std::size_t>(i.get<std::int64_t>()) < used.size())
      used[static_cast<std::size_t>(i.get<std::int64_t>())] = true;
  });
  return used;
}

void renumber(json& j, const std::function<void(json&, const Slot&)>& slots, const std::vector<std::int64_t>& to) {
  slots(j, [&](json& i) {
    if (i.is_number_integer() && i.get<std::int64_t>() >= 0 && static_cast<std::size_t>(i.get<std::int64_t>()) < to.size())
      i = to[static_cast<std::size_t>(i.get<std::int64_t>())];
  });
}

}  // namespace

PruneOutcome prune_unreferenced(json& j, std::string& bin) {
  PruneOutcome out;
  out.kept_because = unknown_extension(j);
  if (!out.kept_because.empty()) return out;
  // Accessors first: a dropped accessor's view may become unused.
  const std::vector<bool> accessors = mark(j, "accessors", accessor_slots);
  renumber(j, accessor_slots, keep_used(j, "accessors", accessors));
  const std::vector<bool> views = mark(j, "bufferViews", view_slots);
  renumber(j, view_slots, keep_used(j, "bufferViews", views));
  // Each kept view's bytes, at the same offset modulo 4 as before: every
  // accessor inside it keeps its alignment (glTF asks for at most 4 bytes),
  // and a document written again keeps its layout instead of drifting.
  std::string packed;
  if (json* vs = member(j, "bufferViews"))
    for (json& v : *vs) {
      const auto from = static_cast<std::size_t>(v.value("byteOffset", std::int64_t{0}));
      const auto length = static_cast<std::size_t>(v["byteLength"].get<std::int64_t>());
      while (packed.size() % 4 != from % 4) packed.push_back('\0');
      v["byteOffset"] = packed.size();
      packed.append(bin, from, length);
    }
  for (const bool u : accessors) out.accessors_dropped += !u;
  for (const bool u : views) out.views_dropped += !u;
  out.bytes_dropped = static_cast<std::int64_t>(bin.size()) - static_cast<std::int64_t>(packed.size());
  out.pruned = true;
  bin = std::move(packed);
  return out;
}

}  // namespace intrinsic::gltf

namespace intrinsic::gltf {

namespace {

// Calls fn(info) for every texture info ({"index": t, ...} under a key
// ending in "Texture", the spec's and the KHR_materials_* extensions'
// spelling) anywhere outside the "textures" array. J: json or const json.
template <class J, class Fn>
void each_texture_info(J& j, const Fn& fn, bool top = true) {
  if (j.is_array()) {
    for (auto& e : j) each_texture_info(e, fn, false);
    return;
  }
  if (!j.is_object()) return;
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (top && it.key() == "textures") continue;
    const std::string& k = it.key();
    if (k.size() > 7 && k.compare(k.size() - 7, 7, "Texture") == 0 && it->is_object() && it->contains("index") &&
        (*it)["index"].is_number_integer())
      fn(*it);
    each_texture_info(*it, fn, false);
  }
}

// The images and samplers the listed textures use ("source" in a texture or
// in one of its extensions, "sampler").
void image_refs(const json& j, const std::set<int>& textures, std::set<int>& images, std::set<int>& samplers) {
  if (!j.contains("textures") || !j["textures"].is_array()) return;
  for (const int t : textures) {
    if (t < 0 || static_cast<std::size_t>(t) >= j["textures"].size()) continue;
    const json& tex = j["textures"][static_cast<std::size_t>(t)];
    if (!tex.is_object()) continue;
    if (tex.contains("source") && tex["source"].is_number_integer()) images.insert(tex["source"].get<int>());
    if (tex.contains("sampler") && tex["sampler"].is_number_integer()) samplers.insert(tex["sampler"].get<int>());
    if (tex.contains("extensions") && tex["extensions"].is_object())
      for (const json& e : tex["extensions"])
        if (e.is_object() && e.contains("source") && e["source"].is_number_integer()) images.insert(e["source"].get<int>());
  }
}

struct Refs {
  std::set<int> textures, images, samplers;
  explicit Refs(const json& j) {
    each_texture_info(j, [this](const json& info) { textures.insert(info["index"].get<int>()); });
    image_refs(j, textures, images, samplers);
  }
};

// Drops entries of j[key] in `gone`; returns the new index of each old one (-1: dropped).
std::vector<int> drop(json& j, const char* key, const std::set<int>& gone) {
  std::vector<int> to;
  if (!j.contains(key) || !j[key].is_array()) return to;
  json kept = json::array();
  for (std::size_t i = 0; i < j[key].size(); ++i) {
    const bool out = gone.count(static_cast<int>(i)) > 0;
    to.push_back(out ? -1 : static_cast<int>(kept.size()));
    if (!out) kept.push_back(j[key][i]);
  }
  if (kept.empty()) j.erase(key);
  else j[key] = kept;
  return to;
}

}  // namespace

std::vector<int> prune_replaced_textures(const json& before, json& after) {
  const Refs was(before), is(after);
  std::set<int> textures, images, samplers;
  for (const int t : was.textures)
    if (!is.textures.count(t)) textures.insert(t);
  for (const int i : was.images)
    if (!is.images.count(i)) images.insert(i);
  for (const int s : was.samplers)
    if (!is.samplers.count(s)) samplers.insert(s);
  if (textures.empty() && images.empty() && samplers.empty()) return {};
  const std::vector<int> t_to = drop(after, "textures", textures);
  const std::vector<int> i_to = drop(after, "images", images);
  const std::vector<int> s_to = drop(after, "samplers", samplers);
  each_texture_info(after, [&t_to](json& info) {
    const int t = info["index"].get<int>();
    if (t >= 0 && static_cast<std::size_t>(t) < t_to.size()) info["index"] = t_to[static_cast<std::size_t>(t)];
  });
  auto renumber = [](json& o, const char* key, const std::vector<int>& to) {
    if (o.is_object() && o.contains(key) && o[key].is_number_integer()) {
      const int v = o[key].get<int>();
      if (v >= 0 && static_cast<std::size_t>(v) < to.size()) o[key] = to[static_cast<std::size_t>(v)];
    }
  };
  if (after.contains("textures"))
    for (json& tex : after["textures"]) {
      renumber(tex, "source", i_to);
      renumber(tex, "sampler", s_to);
      if (tex.is_object() && tex.contains("extensions") && tex["extensions"].is_object())
        for (json& e : tex["extensions"]) renumber(e, "source", i_to);
    }
  return i_to;
}

}  // namespace intrinsic::gltf
