// Shared by the glTF side of the texture transfer (docs/textures.md):
// gltf_textures.cpp finds the textures that read the replaced set and bakes
// them, gltf_corners.cpp gathers what a bake needs per corner of a written
// primitive (positions, normals, old and new UVs, tangent frames) and writes
// the new TANGENT attribute.
#pragma once

#include <map>

#include "intrinsic/texture.h"
#include "intrinsic/texture_transfer.h"
#include "atlas/files/gltf_write_hook.h"

namespace intrinsic::gltf_textures {

using nlohmann::json;

// The written primitive's corners (row c = corner c of GltfWrittenPrimitive::
// index), positions and normals in the primitive's own space, UVs in glTF's
// image convention (v down). old_uv is empty when the primitive has no
// TEXCOORD_n of the replaced set; old_tangent when it has no TANGENT.
struct Corners {
  Eigen::MatrixX3d position, normal;
  Eigen::MatrixX2d old_uv, new_uv;
  Eigen::MatrixX4d old_tangent;
  bool has_normal = false;  // NORMAL given (else face normals, and no TANGENT is written)
};

using AccessorCache = std::map<int, gltf::Accessor>;

Corners gather_corners(const GltfDocument& doc, const GltfWrittenPrimitive& w, const AtlasResult& r,
                       AccessorCache& cache);

// KHR_texture_transform applied to every row (glTF's order: scale, rotate, offset).
Eigen::MatrixX2d transformed(const Eigen::MatrixX2d& uv, const TextureTransform& t);

// Appends bytes as a new buffer view of the output's one buffer (4-byte aligned).
int add_view(json& out, std::string& bin, const std::string& bytes, int target);

// Writes `tangent` (per corner) as the primitive's TANGENT attribute, one
// value per output vertex (its first corner's).
void write_tangents(json& out, std::string& bin, const GltfWrittenPrimitive& w, const Eigen::MatrixX4d& tangent);

// Every row a unit tangent perpendicular to its normal with w = +-1.
Eigen::MatrixX4d sane_tangents(const Eigen::MatrixX4d& t, const Eigen::MatrixX3d& n);

// The writer's hook that bakes every texture reading the replaced set
// (gltf_textures.cpp); what it baked and noted goes to `report`. The
// arguments must outlive the write.
GltfWriteHook texture_hook(const GltfDocument& doc, const AtlasResult& r, const TextureTransferOptions& options,
                           TextureTransferReport& report);

}  // namespace intrinsic::gltf_textures
