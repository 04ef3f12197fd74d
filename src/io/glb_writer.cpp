// glTF 2.0 binary output (issue 13 item 6: atlases for engines and Blender),
// through Debian's tinygltf. glTF has one index per vertex for all
// attributes, so each (vertex, texture coordinate) pair used by a corner
// becomes one glTF vertex: vertices are split exactly at the seams. The file
// is formatted in memory and written atomically (atomic_file.cpp).
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

}  // namespace

void write_glb(const std::string& path, const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV,
               const MatrixX3i& FUV) {
  check_mesh(V, F, UV, FUV);
  // One glTF vertex per distinct (vertex, texture coordinate) corner, in order of first use.
  std::unordered_map<std::uint64_t, std::uint32_t> index;
  std::vector<float> pos, tex;
  std::vector<std::uint32_t> idx;
  idx.reserve(3 * F.rows());
  std::vector<double> lo(3, std::numeric_limits<double>::infinity()), hi(3, -std::numeric_limits<double>::infinity());
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const std::uint64_t key = (static_cast<std::uint64_t>(F(f, c)) << 32) | static_cast<std::uint32_t>(FUV(f, c));
      const auto [it, fresh] = index.emplace(key, static_cast<std::uint32_t>(pos.size() / 3));
      if (fresh) {
        for (int k = 0; k < 3; ++k) {
          pos.push_back(to_float(V(F(f, c), k), "vertex", F(f, c)));
          lo[k] = std::min<double>(lo[k], pos.back());
          hi[k] = std::max<double>(hi[k], pos.back());
        }
        tex.push_back(to_float(UV(FUV(f, c), 0), "texture coordinate", FUV(f, c)));
        tex.push_back(to_float(1 - UV(FUV(f, c), 1), "texture coordinate", FUV(f, c)));
      }
      idx.push_back(it->second);
    }
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "intrinsic";
  model.buffers.emplace_back();
  const size_t n = pos.size() / 3;
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = add_accessor(model, add_view(model, pos, TINYGLTF_TARGET_ARRAY_BUFFER),
                                             TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n, lo, hi);
  prim.attributes["TEXCOORD_0"] = add_accessor(model, add_view(model, tex, TINYGLTF_TARGET_ARRAY_BUFFER),
                                               TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, n);
  prim.indices = add_accessor(model, add_view(model, idx, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                              TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, idx.size());
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
  if (!gltf.WriteGltfSceneToStream(&model, out, false, true)) throw_output(path + ": could not format the glTF file");
  write_file_atomically(path, out.str());
}

}  // namespace intrinsic
