// Where each glTF mesh is drawn first (gltf_scene.cpp).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "io/gltf_document.h"

namespace intrinsic::gltf {

// Where a mesh is drawn first: the world transform of that instance and its
// node (-1 and identity for a mesh no node draws).
struct Placement {
  Eigen::Matrix4d world = Eigen::Matrix4d::Identity();
  int node = -1;
};

// Per mesh its first instance (walking the default scene's roots, the other
// scenes', then the remaining parentless nodes, depth first, children in
// order). Refuses node loops, a node with two parents and indices out of
// range.
std::vector<Placement> first_instances(const nlohmann::json& doc, const std::string& name, std::size_t mesh_count);

// Every node drawing a mesh that an earlier node (in index order) draws
// gets a copy of that mesh's JSON (same accessors, same material) appended
// to "meshes": each instance then has charts of its own. Returns how many
// copies were made.
int give_each_instance_its_mesh(nlohmann::json& doc);

}  // namespace intrinsic::gltf
