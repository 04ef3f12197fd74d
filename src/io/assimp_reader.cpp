// Reading every other asset format through assimp (docs/formats.md "Other
// formats (assimp)"): assimp imports the file and splits its polygons into
// triangles; the rest is done here, as the glTF reader does it for glTF.
// - World scale: the node tree is walked and each mesh is placed by the
//   world transform of its first instance (a mesh drawn by several nodes
//   appears once), so charts are sized by the area a viewer sees.
// - Connected surface: importers split a vertex at every normal, UV or
//   material seam (one aiMesh per material), so corners are welded again by
//   exactly equal world position (as the STL reader welds its corners; no
//   tolerance: nearby but distinct points stay distinct).
// - Labels: per face its material's name (an OBJ output gets `usemtl`), the
//   node that places its mesh (`o`) and the mesh's name (`g`).
// Points and lines are skipped. assimp's log stays off: library code never
// prints, and assimp only logs when a program creates its DefaultLogger.
#include "io/assimp_reader.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>
#include <unordered_set>

#include "io/mesh_builder.h"

namespace intrinsic::io {

namespace {

// Triangulate: polygons become fans of triangles. ValidateDataStructure:
// indices out of range and other inconsistencies a damaged file may give
// are refused by assimp before we read them (it only checks in debug builds
// otherwise).
constexpr unsigned kSteps = aiProcess_Triangulate | aiProcess_ValidateDataStructure;

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  for (unsigned r = 0; r < 4; ++r)
    for (unsigned c = 0; c < 4; ++c) out(r, c) = static_cast<double>(m[r][c]);
  return out;
}

// A name as a label: line breaks and NULs would break an OBJ statement.
std::string label_text(const aiString& s) {
  std::string out(s.C_Str(), s.length);
  for (char& c : out)
    if (c == '\n' || c == '\r' || c == '\0') c = ' ';
  return out;
}

struct Instance {
  Eigen::Matrix4d world = Eigen::Matrix4d::Identity();
  const aiNode* node = nullptr;  // nullptr: no node draws the mesh
};

// Per mesh the world transform and node of its first instance: the tree
// walked depth first from the root, children in order.
std::vector<Instance> first_instances(const aiScene& scene) {
  std::vector<Instance> out(scene.mNumMeshes);
  if (!scene.mRootNode) return out;
  std::vector<std::pair<const aiNode*, Eigen::Matrix4d>> stack{{scene.mRootNode, Eigen::Matrix4d::Identity()}};
  // An importer builds a tree; a node met twice (a damaged file turned into
  // a loop) is not walked again, so the walk always ends.
  std::unordered_set<const aiNode*> seen;
  while (!stack.empty()) {
    const auto [node, above] = stack.back();
    stack.pop_back();
    if (!seen.insert(node).second) continue;
    const Eigen::Matrix4d world = above * to_eigen(node->mTransformation);
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const unsigned m = node->mMeshes[k];
      if (m < out.size() && !out[m].node) out[m] = Instance{world, node};
    }
    for (unsigned k = node->mNumChildren; k-- > 0;)
      if (node->mChildren[k]) stack.emplace_back(node->mChildren[k], world);
  }
  return out;
}

// Corners welded by bitwise-equal world coordinates (-0 counts as +0).
class Welder {
 public:
  explicit Welder(MeshBuilder& b) : b_(b) {}
  int vertex(const Eigen::Vector3d& p) {
    Key k;
    for (int a = 0; a < 3; ++a) {
      const double x = p[a] == 0.0 ? 0.0 : p[a];
      std::memcpy(&k.bits[a], &x, sizeof x);
    }
    const auto [it, fresh] = map_.emplace(k, static_cast<int>(b_.vertex_count()));
    if (fresh) b_.xyz.insert(b_.xyz.end(), {p[0], p[1], p[2]});
    return it->second;
  }

 private:
  struct Key {
    std::uint64_t bits[3];
    bool operator==(const Key& o) const { return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2]; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = k.bits[0] * 0x9E3779B97F4A7C15ull;
      h = (h ^ (h >> 31) ^ k.bits[1]) * 0xFF51AFD7ED558CCDull;
      h = (h ^ (h >> 29) ^ k.bits[2]) * 0xC4CEB9FE1A85EC53ull;
      return static_cast<std::size_t>(h ^ (h >> 32));
    }
  };
  MeshBuilder& b_;
  std::unordered_map<Key, int, Hash> map_;
};

const aiScene* import(Assimp::Importer& importer, const std::string& bytes, const std::string& name,
                      const std::string& ext, bool from_file) {
  if (bytes.empty()) throw_input(name + ": empty file");
  // Skeletons without skin would come back as made-up bone meshes.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  const aiScene* scene = nullptr;
  try {
    scene = from_file ? importer.ReadFile(name, kSteps)
                      : importer.ReadFileFromMemory(bytes.data(), bytes.size(), kSteps, ext.substr(1).c_str());
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw_input(name + ": assimp cannot read it: " + e.what());
  }
  if (!scene) {
    std::string why = importer.GetErrorString();
    if (why.empty()) why = "no scene";
    throw_input(name + ": assimp cannot read it: " + why);
  }
  if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)
    throw_input(name + ": assimp read an incomplete scene (no mesh data; an animation or skeleton only?)");
  return scene;
}

// Faces of the asset that are triangles (the rest are points or lines).
std::int64_t triangle_count(const aiScene& scene) {
  std::int64_t n = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m)
    for (unsigned f = 0; f < scene.mMeshes[m]->mNumFaces; ++f) n += scene.mMeshes[m]->mFaces[f].mNumIndices == 3;
  return n;
}

// Texture coordinates are kept (one row per assimp vertex) only when every
// mesh with triangles has a first UV set, as an OBJ's are only kept when
// every face indexes them.
bool every_mesh_has_uv(const aiScene& scene) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m)
    if (scene.mMeshes[m]->mNumFaces > 0 && !scene.mMeshes[m]->HasTextureCoords(0)) return false;
  return true;
}

std::string mesh_label(const aiScene& scene, unsigned m) {
  const aiMesh& mesh = *scene.mMeshes[m];
  return mesh.mName.length > 0 ? "mesh " + std::to_string(m) + " '" + label_text(mesh.mName) + "'"
                               : "mesh " + std::to_string(m);
}

// Per-face labels filled mesh by mesh: a name for each mesh's faces, or none.
class Labels {
 public:
  void add(const std::string* name, std::size_t before, std::size_t n) {
    int id = -1;
    if (name) id = index_.emplace(*name, static_cast<int>(index_.size())).first->second;
    if (id >= static_cast<int>(labels_.names.size())) labels_.names.push_back(*name);
    if (id < 0 && labels_.of_face.empty()) return;
    if (labels_.of_face.empty()) labels_.of_face.assign(before, -1);
    labels_.of_face.insert(labels_.of_face.end(), n, id);
  }
  FaceLabels take(std::size_t faces) {
    if (!labels_.of_face.empty()) labels_.of_face.resize(faces, -1);
    return std::move(labels_);
  }

 private:
  FaceLabels labels_;
  std::unordered_map<std::string, int> index_;
};

// The asset's triangles appended mesh by mesh.
struct Assembly {
  Assembly(const aiScene& s, const std::string& n, const ReadOptions& o)
      : scene(s), name(n), options(o), placed(first_instances(s)), uv(every_mesh_has_uv(s)) {}
  const aiScene& scene;
  const std::string& name;
  const ReadOptions& options;
  std::vector<Instance> placed;
  bool uv = false;
  MeshBuilder b;
  Welder weld{b};
  Labels materials, objects, groups;

  // The welded index of the mesh's vertex i.
  int world_vertex(unsigned m, unsigned i) {
    const aiVector3D& p = scene.mMeshes[m]->mVertices[i];
    const Eigen::Vector3d w = (placed[m].world * Eigen::Vector4d(p.x, p.y, p.z, 1)).head<3>();
    if (!w.allFinite())
      throw_input(name + ": " + mesh_label(scene, m) + ", vertex " + std::to_string(i) + ": non-finite position");
    const int v = weld.vertex(w);
    if (b.vertex_count() > vertex_limit(options))
      throw_input(name + ": more than " + std::to_string(vertex_limit(options)) + " distinct vertices (the limit)");
    return v;
  }

  void add_mesh(unsigned m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    b.had_texcoords = b.had_texcoords || mesh.HasTextureCoords(0);
    std::vector<int> vertex(mesh.mNumVertices, -1);  // welded index of each vertex once used
    const std::size_t before = b.tri.size() / 3, uv_base = b.uv.size() / 2;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // a point or a line
      for (unsigned c = 0; c < 3; ++c) {
        const unsigned i = face.mIndices[c];
        if (vertex[i] < 0) vertex[i] = world_vertex(m, i);
        b.tri.push_back(vertex[i]);
        if (uv) b.tri_uv.push_back(static_cast<int>(uv_base + i));
      }
    }
    if (uv)
      for (unsigned i = 0; i < mesh.mNumVertices; ++i)
        b.uv.insert(b.uv.end(), {mesh.mTextureCoords[0][i].x, mesh.mTextureCoords[0][i].y});
    add_labels(m, before, b.tri.size() / 3 - before);
  }

  void add_labels(unsigned m, std::size_t before, std::size_t n) {
    const aiMesh& mesh = *scene.mMeshes[m];
    const aiMaterial* material =
        mesh.mMaterialIndex < scene.mNumMaterials ? scene.mMaterials[mesh.mMaterialIndex] : nullptr;
    aiString material_name;
    std::string text;
    if (material && material->Get(AI_MATKEY_NAME, material_name) == aiReturn_SUCCESS && material_name.length > 0)
      text = label_text(material_name);
    else
      text = "material_" + std::to_string(mesh.mMaterialIndex);
    materials.add(&text, before, n);
    const std::string object = placed[m].node ? label_text(placed[m].node->mName) : "";
    objects.add(object.empty() ? nullptr : &object, before, n);
    const std::string group = label_text(mesh.mName);
    groups.add(group.empty() ? nullptr : &group, before, n);
  }
};

}  // namespace

MeshData read_assimp(const std::string& bytes, const std::string& name, const std::string& ext,
                     const ReadOptions& options, bool from_file) {
  Assimp::Importer importer;
  const aiScene& scene = *import(importer, bytes, name, ext, from_file);
  const std::int64_t triangles = triangle_count(scene);
  if (triangles == 0)
    throw_input(name + ": no triangles (" + std::to_string(scene.mNumMeshes) +
                " meshes, none with a face of three or more corners)");
  if (triangles > face_limit(options))
    throw_input(name + ": " + std::to_string(triangles) + " triangles, more than the limit of " +
                std::to_string(face_limit(options)));
  Assembly a(scene, name, options);
  a.b.tri.reserve(static_cast<std::size_t>(triangles) * 3);
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) a.add_mesh(m);
  a.b.line.assign(a.b.tri.size() / 3, 0);  // no source lines
  MeshData out = a.b.finish(name);
  const std::size_t faces = static_cast<std::size_t>(out.F.rows());
  out.materials = a.materials.take(faces);
  out.objects = a.objects.take(faces);
  out.groups = a.groups.take(faces);
  return out;
}

}  // namespace intrinsic::io
