// Reading a glTF 2.0 document as one triangle mesh (docs/formats.md "glTF"):
// every TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitive of every mesh,
// positions (float or KHR_mesh_quantization integers, normalized or not)
// moved to world space by the mesh's first instance so that charts are sized
// by the area a viewer sees. Each primitive keeps its own vertices (the
// atlas welds coincident ones itself); the document, with the origin of every
// vertex and face, is kept beside the mesh (MeshFile) for write_gltf_atlas.
#include <array>
#include <map>
#include <cmath>

#include "intrinsic/gltf.h"
#include "io/gltf_document.h"
#include "io/gltf_scene.h"

namespace intrinsic {

using nlohmann::json;

namespace {

using gltf::fail;

// The primitive's triangles as vertex index triples (glTF 2.0 spec §3.7.2.1
// gives the strip and fan orders). Strip triangles that repeat a vertex are
// the usual restart trick and draw nothing: they are dropped.
std::vector<std::array<std::uint32_t, 3>> triangles(int mode, const std::vector<std::uint32_t>& idx) {
  std::vector<std::array<std::uint32_t, 3>> out;
  const std::size_t n = idx.size();
  if (mode == 4) {
    for (std::size_t i = 0; i + 2 < n; i += 3) out.push_back({idx[i], idx[i + 1], idx[i + 2]});
  } else if (mode == 5) {
    for (std::size_t i = 0; i + 2 < n; ++i) {
      const std::array<std::uint32_t, 3> t = i % 2 == 0 ? std::array<std::uint32_t, 3>{idx[i], idx[i + 1], idx[i + 2]}
                                                         : std::array<std::uint32_t, 3>{idx[i + 1], idx[i], idx[i + 2]};
      if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) out.push_back(t);
    }
  } else {
    for (std::size_t i = 1; i + 1 < n; ++i) out.push_back({idx[i], idx[i + 1], idx[0]});
  }
  return out;
}

// Checks every accessor a triangle primitive names (attributes, morph
// targets): in range, readable, one element per vertex.
void check_attributes(const GltfDocument& doc, const json& prim, const std::string& path, std::int64_t vertices) {
  const std::size_t naccessors = gltf::array_at(doc.json, "accessors", doc.name, "").size();
  auto check_set = [&](const json& set, const std::string& at) {
    if (!set.is_object()) fail(doc.name, at, "expected an object");
    for (auto it = set.begin(); it != set.end(); ++it) {
      const int a = gltf::index_at(set, it.key().c_str(), naccessors, doc.name, at);
      const gltf::Accessor acc = gltf::read_accessor(doc, a, vertices);
      if (acc.count != vertices)
        fail(doc.name, at + "/" + it.key(), "accessor " + std::to_string(a) + " has " + std::to_string(acc.count) +
                                                " elements, POSITION has " + std::to_string(vertices));
    }
  };
  check_set(prim["attributes"], path + "/attributes");
  const json& targets = gltf::array_at(prim, "targets", doc.name, path);
  for (std::size_t t = 0; t < targets.size(); ++t) check_set(targets[t], path + "/targets/" + std::to_string(t));
}

std::vector<std::uint32_t> read_indices(const GltfDocument& doc, const json& prim, const std::string& path,
                                        std::int64_t vertices, std::int64_t max_count) {
  std::vector<std::uint32_t> idx;
  const int ia = gltf::index_at(prim, "indices", gltf::array_at(doc.json, "accessors", doc.name, "").size(), doc.name, path, true);
  if (ia < 0) {
    idx.resize(static_cast<std::size_t>(vertices));
    for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<std::uint32_t>(i);
    return idx;
  }
  const gltf::Accessor a = gltf::read_accessor(doc, ia, max_count);
  if (a.components != 1 || (a.component != 5121 && a.component != 5123 && a.component != 5125) || a.normalized)
    fail(doc.name, path + "/indices", "accessor " + std::to_string(ia) +
                                          " is not a SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  idx.resize(static_cast<std::size_t>(a.count));
  for (std::int64_t i = 0; i < a.count; ++i) {
    const double v = a.raw(i, 0);
    if (v >= static_cast<double>(vertices))
      fail(doc.name, path + "/indices", "index " + std::to_string(static_cast<std::uint64_t>(v)) + " out of range (" +
                                            std::to_string(vertices) + " vertices)");
    idx[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(v);
  }
  return idx;
}

struct Merged {
  std::vector<Eigen::Vector3d> V;
  std::vector<Eigen::Vector3i> F;
};

// Appends one triangle primitive to the merged mesh and the provenance.
void add_primitive(GltfDocument& doc, Merged& out, int mesh, int p, const Eigen::Matrix4d& world,
                   const ReadOptions& options) {
  const std::string path = "/meshes/" + std::to_string(mesh) + "/primitives/" + std::to_string(p);
  const json& prim = doc.json["meshes"][static_cast<std::size_t>(mesh)]["primitives"][static_cast<std::size_t>(p)];
  const int mode = static_cast<int>(prim.contains("mode") ? gltf::integer(prim["mode"], doc.name, path + "/mode") : 4);
  if (!prim.contains("attributes") || !prim["attributes"].is_object())
    fail(doc.name, path + "/attributes", "missing");
  const std::size_t naccessors = gltf::array_at(doc.json, "accessors", doc.name, "").size();
  const int pa = gltf::index_at(prim["attributes"], "POSITION", naccessors, doc.name, path + "/attributes");
  const gltf::Accessor pos = gltf::read_accessor(doc, pa, options.max_vertices);
  if (pos.components != 3 || pos.component == 5125)
    fail(doc.name, path + "/attributes/POSITION",
         "accessor " + std::to_string(pa) + " is not a VEC3 of floats or (KHR_mesh_quantization) bytes or shorts");
  check_attributes(doc, prim, path, pos.count);
  const std::vector<std::uint32_t> idx = read_indices(doc, prim, path, pos.count, 3 * options.max_faces + 2);
  const auto tris = triangles(mode, idx);
  if (static_cast<std::int64_t>(out.F.size() + tris.size()) > options.max_faces)
    fail(doc.name, path, "more than " + std::to_string(options.max_faces) + " faces in the document (the limit)");
  GltfDocument::Primitive rec;
  rec.mesh = mesh;
  rec.primitive = p;
  rec.first_vertex = static_cast<int>(out.V.size());
  rec.first_face = static_cast<int>(out.F.size());
  // Only the vertices a triangle uses, in their original order.
  std::vector<int> merged(static_cast<std::size_t>(pos.count), -1);
  for (const auto& t : tris)
    for (const std::uint32_t v : t) merged[v] = 0;
  for (std::size_t v = 0; v < merged.size(); ++v) {
    if (merged[v] < 0) continue;
    if (static_cast<std::int64_t>(out.V.size()) >= options.max_vertices)
      fail(doc.name, path, "more than " + std::to_string(options.max_vertices) + " vertices in the document (the limit)");
    const Eigen::Vector4d local(pos.value(static_cast<std::int64_t>(v), 0), pos.value(static_cast<std::int64_t>(v), 1),
                                pos.value(static_cast<std::int64_t>(v), 2), 1);
    const Eigen::Vector3d w = (world * local).head<3>();
    if (!w.allFinite())
      fail(doc.name, path + "/attributes/POSITION", "vertex " + std::to_string(v) + " is not finite (in world space)");
    merged[v] = static_cast<int>(out.V.size());
    out.V.push_back(w);
    doc.vertex_source.push_back(static_cast<int>(v));
  }
  const int self = static_cast<int>(doc.primitives.size());
  for (const auto& t : tris) {
    out.F.emplace_back(merged[t[0]], merged[t[1]], merged[t[2]]);
    doc.face_primitive.push_back(self);
  }
  rec.vertex_count = static_cast<int>(out.V.size()) - rec.first_vertex;
  rec.face_count = static_cast<int>(out.F.size()) - rec.first_face;
  doc.primitives.push_back(rec);
}

// Per-face labels built primitive by primitive: the distinct names in order
// of first use.
class LabelTable {
 public:
  void add(const std::string* name, std::size_t faces) {
    int id = -1;
    if (name) {
      const auto [it, fresh] = index_.emplace(*name, static_cast<int>(labels_.names.size()));
      if (fresh) labels_.names.push_back(*name);
      id = it->second;
    }
    labels_.of_face.insert(labels_.of_face.end(), faces, id);
    any_ = any_ || id >= 0;
  }
  FaceLabels take() { return any_ ? std::move(labels_) : FaceLabels{}; }

 private:
  FaceLabels labels_;
  std::map<std::string, int> index_;
  bool any_ = false;
};

std::string name_of(const json& array, int i, const char* fallback) {
  if (i < 0 || !array.is_array() || static_cast<std::size_t>(i) >= array.size()) return "";
  const json& o = array[static_cast<std::size_t>(i)];
  if (o.is_object() && o.contains("name") && o["name"].is_string() && !o["name"].get<std::string>().empty()) {
    std::string n = o["name"].get<std::string>();
    for (char& c : n)
      if (c == '\n' || c == '\r' || c == '\0') c = ' ';  // one OBJ statement per line
    return n;
  }
  return fallback ? std::string(fallback) + std::to_string(i) : "";
}

// What an OBJ output gives back of the document: per face its material's
// name (usemtl), its mesh's name (g) and the node drawing it (o); per corner
// the NORMAL attribute in world space (vn). `data` is the merged mesh.
ObjExtras obj_extras(const MeshData& data, const GltfDocument& doc, const std::vector<gltf::Placement>& placed) {
  LabelTable materials, groups, objects;
  const json empty = json::array();
  const json& mats = doc.json.contains("materials") ? doc.json["materials"] : empty;
  const json& nodes = doc.json.contains("nodes") ? doc.json["nodes"] : empty;
  ObjExtras x;
  x.N.resize(data.V.rows(), 3);
  x.FN.resize(data.F.rows(), 3);
  bool any_normal = false;
  for (const GltfDocument::Primitive& p : doc.primitives) {
    const json& mesh = doc.json["meshes"][static_cast<std::size_t>(p.mesh)];
    const json& prim = mesh["primitives"][static_cast<std::size_t>(p.primitive)];
    const int material = prim.contains("material") && prim["material"].is_number_integer() ? prim["material"].get<int>() : -1;
    const std::string mname = name_of(mats, material, "material_");
    materials.add(mname.empty() ? nullptr : &mname, static_cast<std::size_t>(p.face_count));
    const std::string group = mesh.is_object() && mesh.contains("name") && mesh["name"].is_string() ? mesh["name"].get<std::string>() : "";
    groups.add(group.empty() ? nullptr : &group, static_cast<std::size_t>(p.face_count));
    const std::string object = name_of(nodes, placed[static_cast<std::size_t>(p.mesh)].node, nullptr);
    objects.add(object.empty() ? nullptr : &object, static_cast<std::size_t>(p.face_count));
    const bool has = prim["attributes"].contains("NORMAL");
    any_normal = any_normal || has;
    for (int f = p.first_face; f < p.first_face + p.face_count; ++f)
      for (int c = 0; c < 3; ++c) x.FN(f, c) = has ? data.F(f, c) : -1;
    if (!has) continue;
    const gltf::Accessor n = gltf::read_accessor(doc, prim["attributes"]["NORMAL"].get<int>(), std::int64_t{1} << 40);
    const Eigen::Matrix3d to_world = placed[static_cast<std::size_t>(p.mesh)].world.topLeftCorner<3, 3>().inverse().transpose();
    for (int v = 0; v < p.vertex_count; ++v) {
      const std::int64_t src = doc.vertex_source[static_cast<std::size_t>(p.first_vertex + v)];
      Eigen::Vector3d w = to_world * Eigen::Vector3d(n.value(src, 0), n.value(src, 1), n.value(src, 2));
      if (w.norm() > 0 && w.allFinite()) w.normalize();
      else w.setZero();
      x.N.row(p.first_vertex + v) = w.transpose();
    }
  }
  if (!any_normal) x.N.resize(0, 3), x.FN.resize(0, 3);
  x.materials = materials.take();
  x.groups = groups.take();
  x.objects = objects.take();
  return x;
}

}  // namespace

namespace io {

MeshFile read_gltf_document(GltfDocument doc_in, const ReadOptions& options) {
  auto doc = std::make_shared<GltfDocument>(std::move(doc_in));
  const std::string& name = doc->name;
  if (options.instances == InstanceMode::Unique) gltf::give_each_instance_its_mesh(doc->json);
  const json& meshes = gltf::array_at(doc->json, "meshes", name, "");
  const std::vector<gltf::Placement> placed = gltf::first_instances(doc->json, name, meshes.size());
  Merged out;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const std::string path = "/meshes/" + std::to_string(m);
    const json& prims = gltf::array_at(meshes[m], "primitives", name, path);
    for (std::size_t p = 0; p < prims.size(); ++p) {
      const std::string at = path + "/primitives/" + std::to_string(p);
      if (!prims[p].is_object()) fail(name, at, "expected an object");
      const std::int64_t mode = prims[p].contains("mode") ? gltf::integer(prims[p]["mode"], name, at + "/mode") : 4;
      if (mode < 0 || mode > 6) fail(name, at + "/mode", std::to_string(mode) + " is not a glTF primitive mode");
      if (mode >= 4) add_primitive(*doc, out, static_cast<int>(m), static_cast<int>(p), placed[m].world, options);
    }
  }
  if (out.F.empty()) throw_input(name + ": no triangles (no mesh primitive with mode TRIANGLES, STRIP or FAN)");
  MeshFile file;
  MeshData& data = file.mesh;
  data.V.resize(static_cast<Eigen::Index>(out.V.size()), 3);
  for (std::size_t v = 0; v < out.V.size(); ++v) data.V.row(static_cast<Eigen::Index>(v)) = out.V[v];
  data.F.resize(static_cast<Eigen::Index>(out.F.size()), 3);
  for (std::size_t f = 0; f < out.F.size(); ++f) data.F.row(static_cast<Eigen::Index>(f)) = out.F[f];
  data.path = name;
  file.document.obj = obj_extras(data, *doc, placed);
  file.document.gltf = doc;
  return file;
}

}  // namespace io

namespace {

std::string folder_of(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash);
}

}  // namespace

namespace io {

// From read_mesh: the bytes of `name` (already un-gzipped), external buffer
// files beside it when `files_allowed`.
MeshFile read_gltf(const std::string& bytes, const std::string& name, const ReadOptions& options, bool files_allowed) {
  // Every JSON access checks its type first; should one have been missed,
  // the file is refused, not the program ended.
  try {
    return read_gltf_document(gltf::load_document(bytes, name, folder_of(name), files_allowed), options);
  } catch (const nlohmann::json::exception& e) {
    throw_input(name + ": unexpected JSON: " + e.what());
  }
}

}  // namespace io

MeshFile read_gltf_file(const std::string& path, const ReadOptions& options) {
  const std::string ext = mesh_extension(path);
  if (ext != ".gltf" && ext != ".glb") throw_usage("read_gltf: '" + path + "' is not a .gltf or .glb file");
  return read_mesh_file(path, options);
}

MeshData read_gltf(const std::string& path, const ReadOptions& options) {
  return read_gltf_file(path, options).mesh;
}

MeshFile read_gltf_file_from_memory(const std::string& bytes, const std::string& name, const ReadOptions& options) {
  return io::read_gltf(bytes, name, options, false);
}

MeshData read_gltf_from_memory(const std::string& bytes, const std::string& name, const ReadOptions& options) {
  return read_gltf_file_from_memory(bytes, name, options).mesh;
}

SceneSummary scene_summary(const MeshDocument& document) {
  SceneSummary s;
  if (!document.gltf) return s;
  const json& j = document.gltf->json;
  auto count = [&j](const char* key) { return j.contains(key) && j[key].is_array() ? static_cast<int>(j[key].size()) : 0; };
  s.meshes = count("meshes");
  s.materials = count("materials");
  s.images = count("images");
  s.cameras = count("cameras");
  if (j.contains("extensions") && j["extensions"].is_object() && j["extensions"].contains("KHR_lights_punctual")) {
    const json& l = j["extensions"]["KHR_lights_punctual"];
    if (l.is_object() && l.contains("lights") && l["lights"].is_array()) s.lights = static_cast<int>(l["lights"].size());
  }
  if (j.contains("nodes") && j["nodes"].is_array())
    for (const json& n : j["nodes"]) s.instances += n.is_object() && n.contains("mesh");
  if (j.contains("meshes") && j["meshes"].is_array())
    for (const json& m : j["meshes"])
      if (m.is_object() && m.contains("primitives") && m["primitives"].is_array())
        for (const json& p : m["primitives"]) s.skipped_primitives += p.is_object() && p.value("mode", 4) < 4;
  return s;
}

void read_gltf_texcoords(MeshFile& file, int set) {
  MeshData& data = file.mesh;
  if (!file.document.gltf) throw_usage("read_gltf_texcoords: " + data.path + " was not read from a glTF document");
  const GltfDocument& doc = *file.document.gltf;
  const std::string key = "TEXCOORD_" + std::to_string(set);
  MatrixX2d TC(data.V.rows(), 2);
  for (const GltfDocument::Primitive& p : doc.primitives) {
    const json& prim = doc.json["meshes"][static_cast<std::size_t>(p.mesh)]["primitives"][static_cast<std::size_t>(p.primitive)];
    const std::string at = "/meshes/" + std::to_string(p.mesh) + "/primitives/" + std::to_string(p.primitive);
    if (!prim["attributes"].contains(key)) fail(doc.name, at + "/attributes", "no " + key + " to re-pack");
    const gltf::Accessor a = gltf::read_accessor(doc, prim["attributes"][key].get<int>(), std::int64_t{1} << 40);
    if (a.components != 2) fail(doc.name, at + "/attributes/" + key, "not a VEC2");
    for (int v = 0; v < p.vertex_count; ++v) {
      const std::int64_t src = doc.vertex_source[static_cast<std::size_t>(p.first_vertex + v)];
      TC.row(p.first_vertex + v) << a.value(src, 0), 1 - a.value(src, 1);
    }
  }
  data.TC = std::move(TC);
  data.FTC = data.F;
  data.had_texcoords = true;
}

GltfProvenance gltf_provenance(const MeshFile& file) {
  if (!file.document.gltf) throw_usage("gltf_provenance: " + file.mesh.path + " was not read from a glTF document");
  const GltfDocument& doc = *file.document.gltf;
  GltfProvenance p;
  for (const GltfDocument::Primitive& r : doc.primitives) {
    for (int v = 0; v < r.vertex_count; ++v) {
      p.vertex_mesh.push_back(r.mesh);
      p.vertex_primitive.push_back(r.primitive);
      p.vertex_index.push_back(doc.vertex_source[static_cast<std::size_t>(r.first_vertex + v)]);
    }
    p.face_mesh.insert(p.face_mesh.end(), static_cast<std::size_t>(r.face_count), r.mesh);
    p.face_primitive.insert(p.face_primitive.end(), static_cast<std::size_t>(r.face_count), r.primitive);
  }
  return p;
}

}  // namespace intrinsic
