// Where each glTF mesh is drawn first (gltf_scene.cpp).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "io/gltf_document.h"

namespace intrinsic::gltf {

// Per mesh: the world transform of its first instance (walking the default
// scene's roots, the other scenes', then the remaining parentless nodes, depth
// first, children in order); identity for a mesh no node draws. Refuses node
// loops, a node with two parents and indices out of range.
std::vector<Eigen::Matrix4d> first_instances(const nlohmann::json& doc, const std::string& name,
                                             std::size_t mesh_count);

}  // namespace intrinsic::gltf
