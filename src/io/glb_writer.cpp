// glTF 2.0 binary output (atlases for game engines and Blender),
// through Debian's tinygltf. glTF has one index per vertex for all
// attributes, so each (vertex, texture coordinate) pair used by a corner
// becomes one glTF vertex: vertices are split exactly at the seams. Normals
// are smoothed as "auto smooth" does in modelling tools: a corner's normal is
// the area-weighted mean of the face normals around its vertex within
// kSmoothAngleDeg of its own face's, so smooth surfaces shade smoothly
// (across UV seams too) and hard edges stay hard; a vertex is also split
// where its corners' normals differ. The file is formatted in memory and
// written atomically (atomic_file.cpp).
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <unordered_map>

#include "intrinsic/error.h"
#include "intrinsic/io.h"

namespace intrinsic {
namespace {

// Appends `count` floats or uint32s to the buffer, 4-byte aligned, as one
// buffer view; returns its index.
template <class T>
int add_view(tinygltf::Model& model, const std::vector<T>& data, int target) {
  std::vector<unsigned char>& bytes = model.buffers[0].data;
  while (bytes.size() % 4) bytes.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = bytes.size();
  view.byteLength = data.size() * sizeof(T);
  view.target = target;
  bytes.resize(bytes.size() + view.byteLength);
  if (!data.empty()) std::memcpy(bytes.data() + view.byteOffset, data.data(), view.byteLength);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size() - 1);
}

int add_accessor(tinygltf::Model& model, int view, int component, int type, size_t count,
                 std::vector<double> min = {}, std::vector<double> max = {}) {
  tinygltf::Accessor a;
  a.bufferView = view;
  a.componentType = component;
  a.type = type;
  a.count = count;
  a.minValues = std::move(min);
  a.maxValues = std::move(max);
  model.accessors.push_back(a);
  return static_cast<int>(model.accessors.size() - 1);
}

void check_mesh(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV, const MatrixX3i& FUV) {
  if (F.rows() == 0) throw_input("glb: the mesh has no faces");
  if (FUV.rows() != F.rows()) throw_input("glb: one row of texture indices per face is needed");
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (F(f, c) < 0 || F(f, c) >= V.rows() || FUV(f, c) < 0 || FUV(f, c) >= UV.rows())
        throw_input("glb: face " + std::to_string(f) + " has an index out of range");
  if (static_cast<double>(F.rows()) * 3 > std::numeric_limits<std::uint32_t>::max())
    throw_input("glb: too many faces for 32-bit indices");
}

float to_float(double x, const char* what, Eigen::Index row) {
  const float f = static_cast<float>(x);
  if (!std::isfinite(f))
    throw_input(std::string("glb: ") + what + " " + std::to_string(row) + " does not fit in a 32-bit float");
  return f;
}

// Corners whose faces meet at a smaller angle share a smoothed normal.
constexpr double kSmoothAngleDeg = 60;

// Per corner (3 per face, in face order): the unit auto-smooth normal. A
// corner of a zero-area face takes the smoothed normal of its vertex's
// faces; (0, 0, 1) when every face there has zero area.
std::vector<Eigen::Vector3f> corner_normals(const MatrixX3d& V, const MatrixX3i& F) {
  const Eigen::Index m = F.rows();
  std::vector<Eigen::Vector3d> area_normal(m);  // |n| = twice the area
  std::vector<std::vector<int>> faces_of(V.rows());
  for (Eigen::Index f = 0; f < m; ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    area_normal[f] = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) faces_of[F(f, k)].push_back(static_cast<int>(f));
  }
  const double cos_limit = std::cos(kSmoothAngleDeg * 3.14159265358979323846 / 180);
  std::vector<Eigen::Vector3f> out(3 * m);
  for (Eigen::Index f = 0; f < m; ++f) {
    const double nf = area_normal[f].norm();
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (const int g : faces_of[F(f, k)]) {
        const double ng = area_normal[g].norm();
        if (nf == 0 || (ng > 0 && area_normal[f].dot(area_normal[g]) >= cos_limit * nf * ng)) sum += area_normal[g];
      }
      const double len = sum.norm();
      out[3 * f + k] = len > 0 && std::isfinite(len) ? (sum / len).cast<float>() : Eigen::Vector3f(0, 0, 1);
    }
  }
  return out;
}

// The glTF vertex arrays: one vertex per distinct (vertex, texture
// coordinate, normal) corner, in order of first use by the faces.
struct GlbVertices {
  std::vector<float> pos, tex, nrm;
  std::vector<std::uint32_t> idx;
  std::vector<double> lo, hi;  // position bounds (glTF requires them)
};

struct CornerKey {
  int vertex, uv;
  float n[3];
  bool operator==(const CornerKey& o) const {
    return vertex == o.vertex && uv == o.uv && n[0] == o.n[0] && n[1] == o.n[1] && n[2] == o.n[2];
  }
};

struct CornerKeyHash {
  size_t operator()(const CornerKey& k) const {
    size_t h = std::hash<int>()(k.vertex) * 0x9E3779B97F4A7C15ull ^ std::hash<int>()(k.uv);
    for (const float x : k.n) h = h * 1099511628211ull ^ std::hash<float>()(x);
    return h;
  }
};

GlbVertices split_vertices(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV, const MatrixX3i& FUV) {
  const std::vector<Eigen::Vector3f> normal = corner_normals(V, F);
  std::unordered_map<CornerKey, std::uint32_t, CornerKeyHash> index;
  GlbVertices g;
  g.idx.reserve(3 * F.rows());
  g.lo.assign(3, std::numeric_limits<double>::infinity());
  g.hi.assign(3, -std::numeric_limits<double>::infinity());
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3f& n = normal[3 * f + c];
      const CornerKey key{F(f, c), FUV(f, c), {n.x(), n.y(), n.z()}};
      const auto [it, fresh] = index.emplace(key, static_cast<std::uint32_t>(g.pos.size() / 3));
      if (fresh) {
        for (int k = 0; k < 3; ++k) {
          g.pos.push_back(to_float(V(F(f, c), k), "vertex", F(f, c)));
          g.lo[k] = std::min<double>(g.lo[k], g.pos.back());
          g.hi[k] = std::max<double>(g.hi[k], g.pos.back());
          g.nrm.push_back(n[k]);
        }
        g.tex.push_back(to_float(UV(FUV(f, c), 0), "texture coordinate", FUV(f, c)));
        g.tex.push_back(to_float(1 - UV(FUV(f, c), 1), "texture coordinate", FUV(f, c)));
      }
      g.idx.push_back(it->second);
    }
  return g;
}

}  // namespace

void write_glb(const std::string& path, const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV,
               const MatrixX3i& FUV) {
  check_mesh(V, F, UV, FUV);
  const GlbVertices g = split_vertices(V, F, UV, FUV);
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "intrinsic";
  model.buffers.emplace_back();
  const size_t n = g.pos.size() / 3;
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = add_accessor(model, add_view(model, g.pos, TINYGLTF_TARGET_ARRAY_BUFFER),
                                             TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n, g.lo, g.hi);
  prim.attributes["NORMAL"] = add_accessor(model, add_view(model, g.nrm, TINYGLTF_TARGET_ARRAY_BUFFER),
                                           TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
  prim.attributes["TEXCOORD_0"] = add_accessor(model, add_view(model, g.tex, TINYGLTF_TARGET_ARRAY_BUFFER),
                                               TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, n);
  prim.indices = add_accessor(model, add_view(model, g.idx, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                              TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, g.idx.size());
  tinygltf::Mesh mesh;
  mesh.primitives.push_back(prim);
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  std::ostringstream out;
  tinygltf::TinyGLTF gltf;
  // .gltf: the same document as JSON, the buffer embedded as a data URI.
  const bool binary = mesh_extension(path) != ".gltf";
  if (!gltf.WriteGltfSceneToStream(&model, out, false, binary)) throw_output(path + ": could not format the glTF file");
  write_file_atomically(path, out.str());
}

}  // namespace intrinsic
