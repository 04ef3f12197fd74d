// The glTF scene graph (glTF 2.0 spec §3.5): node transforms (a column-major
// matrix, or translation * rotation * scale) composed from the roots down,
// to place each mesh where its first instance is drawn. Nodes must form a
// forest: a node with two parents or on a loop is refused.
#include <Eigen/Geometry>

#include "io/gltf_scene.h"

namespace intrinsic::gltf {

using nlohmann::json;

namespace {

Eigen::Matrix4d local_transform(const json& node, const std::string& name, const std::string& path) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  auto numbers = [&](const char* key, std::size_t n) {
    const json& a = node[key];
    const std::string at = path + "/" + key;
    if (!a.is_array() || a.size() != n) fail(name, at, "expected " + std::to_string(n) + " numbers");
    std::vector<double> v(n);
    for (std::size_t i = 0; i < n; ++i) {
      v[i] = number(a[i], name, at + "/" + std::to_string(i));
      if (!std::isfinite(v[i])) fail(name, at + "/" + std::to_string(i), "not finite");
    }
    return v;
  };
  if (node.contains("matrix")) {
    const std::vector<double> v = numbers("matrix", 16);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = v[static_cast<std::size_t>(4 * c + r)];
    return m;
  }
  if (node.contains("scale")) {
    const std::vector<double> s = numbers("scale", 3);
    m = Eigen::Vector4d(s[0], s[1], s[2], 1).asDiagonal();
  }
  if (node.contains("rotation")) {
    const std::vector<double> q = numbers("rotation", 4);  // x, y, z, w
    Eigen::Quaterniond r(q[3], q[0], q[1], q[2]);
    if (!(r.norm() > 0)) fail(name, path + "/rotation", "zero quaternion");
    Eigen::Matrix4d rm = Eigen::Matrix4d::Identity();
    rm.topLeftCorner<3, 3>() = r.normalized().toRotationMatrix();
    m = rm * m;
  }
  if (node.contains("translation")) {
    const std::vector<double> t = numbers("translation", 3);
    Eigen::Matrix4d tm = Eigen::Matrix4d::Identity();
    tm.topRightCorner<3, 1>() = Eigen::Vector3d(t[0], t[1], t[2]);
    m = tm * m;
  }
  return m;
}

// The order roots are walked in: the default scene's, the other scenes',
// then every node that has no parent.
std::vector<int> root_order(const json& doc, const std::vector<int>& parent, const std::string& name) {
  std::vector<int> roots;
  const json& scenes = array_at(doc, "scenes", name, "");
  int first = 0;
  if (doc.contains("scene")) first = index_at(doc, "scene", scenes.size(), name, "");
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    const std::size_t s = (k + static_cast<std::size_t>(first)) % scenes.size();
    const std::string path = "/scenes/" + std::to_string(s);
    const json& nodes = array_at(scenes[s], "nodes", name, path);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const std::string at = path + "/nodes/" + std::to_string(i);
      const std::int64_t n = integer(nodes[i], name, at);
      if (n < 0 || static_cast<std::size_t>(n) >= parent.size())
        fail(name, at, "node " + std::to_string(n) + " out of range (" + std::to_string(parent.size()) + " nodes)");
      // A listed node that has a parent is reached through it (and a loop
      // must not be entered from the side).
      if (parent[static_cast<std::size_t>(n)] < 0) roots.push_back(static_cast<int>(n));
    }
  }
  for (std::size_t n = 0; n < parent.size(); ++n)
    if (parent[n] < 0) roots.push_back(static_cast<int>(n));
  return roots;
}

}  // namespace

std::vector<Placement> first_instances(const json& doc, const std::string& name, std::size_t mesh_count) {
  const json& nodes = array_at(doc, "nodes", name, "");
  const std::size_t n = nodes.size();
  std::vector<int> parent(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string path = "/nodes/" + std::to_string(i);
    const json& children = array_at(nodes[i], "children", name, path);
    for (std::size_t k = 0; k < children.size(); ++k) {
      const std::string at = path + "/children/" + std::to_string(k);
      const std::int64_t c = integer(children[k], name, at);
      if (c < 0 || static_cast<std::size_t>(c) >= n)
        fail(name, at, "node " + std::to_string(c) + " out of range (" + std::to_string(n) + " nodes)");
      if (static_cast<std::size_t>(c) == i) fail(name, at, "node " + std::to_string(i) + " is its own child (node loop)");
      if (parent[static_cast<std::size_t>(c)] >= 0)
        fail(name, at, "node " + std::to_string(c) + " already has parent " +
                           std::to_string(parent[static_cast<std::size_t>(c)]) + " (nodes must form a tree)");
      parent[static_cast<std::size_t>(c)] = static_cast<int>(i);
    }
  }
  std::vector<Placement> world(mesh_count);
  std::vector<bool> mesh_seen(mesh_count, false), visited(n, false);
  std::vector<std::pair<int, Eigen::Matrix4d>> stack;
  for (const int root : root_order(doc, parent, name)) {
    if (visited[static_cast<std::size_t>(root)]) continue;
    stack.emplace_back(root, Eigen::Matrix4d::Identity());
    while (!stack.empty()) {
      const auto [i, above] = stack.back();
      stack.pop_back();
      if (visited[static_cast<std::size_t>(i)]) continue;
      visited[static_cast<std::size_t>(i)] = true;
      const std::string path = "/nodes/" + std::to_string(i);
      const json& node = nodes[static_cast<std::size_t>(i)];
      const Eigen::Matrix4d m = above * local_transform(node, name, path);
      const int mesh = index_at(node, "mesh", mesh_count, name, path, true);
      if (mesh >= 0 && !mesh_seen[static_cast<std::size_t>(mesh)]) {
        mesh_seen[static_cast<std::size_t>(mesh)] = true;
        world[static_cast<std::size_t>(mesh)] = Placement{m, i};
      }
      const json& children = array_at(node, "children", name, path);
      for (std::size_t k = children.size(); k-- > 0;) stack.emplace_back(children[k].get<int>(), m);
    }
  }
  // Every node reachable from a parentless one has been visited; the rest
  // hang from a loop.
  for (std::size_t i = 0; i < n; ++i)
    if (!visited[i]) fail(name, "/nodes/" + std::to_string(i), "node loop (node " + std::to_string(i) + " is its own ancestor)");
  return world;
}

int give_each_instance_its_mesh(json& doc) {
  if (!doc.contains("nodes") || !doc["nodes"].is_array() || !doc.contains("meshes") || !doc["meshes"].is_array())
    return 0;
  json& meshes = doc["meshes"];
  std::vector<bool> drawn(meshes.size(), false);
  int copies = 0;
  for (json& node : doc["nodes"]) {
    if (!node.is_object() || !node.contains("mesh") || !node["mesh"].is_number_integer()) continue;
    const std::int64_t m = node["mesh"].get<std::int64_t>();
    if (m < 0 || static_cast<std::size_t>(m) >= drawn.size()) continue;  // refused by the reader with its path
    if (!drawn[static_cast<std::size_t>(m)]) {
      drawn[static_cast<std::size_t>(m)] = true;
      continue;
    }
    meshes.push_back(meshes[static_cast<std::size_t>(m)]);
    node["mesh"] = meshes.size() - 1;
    ++copies;
  }
  return copies;
}

}  // namespace intrinsic::gltf
