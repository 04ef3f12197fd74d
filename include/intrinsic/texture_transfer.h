// Re-atlasing a textured asset without changing its look (docs/textures.md):
// when the atlas replaces the texture coordinate set the materials' textures
// read, every such texture is baked anew in the new layout (texture.h's
// transfer_texture) and written with the asset: into the glTF document
// (images embedded, textureInfos pointed at them, TANGENT written for normal
// maps) or beside an OBJ (PNG images, a new .mtl, the OBJ's mtllib on it).
#pragma once

#include <string>
#include <vector>


#include "intrinsic/atlas.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/gltf.h"
#include "intrinsic/mesh_data.h"
#include "intrinsic/mesh_document.h"

namespace intrinsic {

struct TextureTransferOptions {
  bool enabled = false;
  // Side of every baked texture in texels (1..16384), or 0: each source's
  // own size scaled by the ratio of old to new UV area its triangles cover
  // (the same texel density on the surface).
  int size = 2048;
  int padding = 4;      // texels of dilation around every chart (texture.h TransferOptions)
  int supersample = 2;  // samples per texel along each axis, 1..4
  OptionSpelling spelling = OptionSpelling::Keyword;  // how messages name these options
};

// One texture slot of one material that now reads a baked image.
struct BakedTexture {
  int material = -1;          // glTF material index, or for an OBJ the map line's position among the .mtl maps
  std::string material_name;  // "" when the material has none
  std::string slot;           // "pbrMetallicRoughness/baseColorTexture", "normalTexture", "map_Kd", ...
  std::string source;         // the source image: glTF "image 3 (name)" or the OBJ map's file
  std::string output;         // glTF "image 7", or the PNG file written beside the OBJ
  int width = 0, height = 0;
  long texels_covered = 0;    // texels inside a new triangle
};

struct TextureTransferReport {
  std::vector<BakedTexture> baked;
  std::vector<std::string> notes;  // e.g. a material with no texture on the replaced set
  std::vector<std::string> files;  // written beside the output (images, .mtl)
  std::vector<std::string> missing_images;  // named by the input, not found (allow_missing_images)
};

// Error(Usage) for options out of range (before any work).
void check_texture_transfer(const TextureTransferOptions& options);
// What the input and the output allow, checked before any work when they are
// known (an empty `output`: not yet): a glTF input's textures are baked only
// into a glTF output, and only when the atlas replaces the set they read
// (`texcoord_set`, the glTF TEXCOORD_n; -1: none given).
void check_texture_transfer_input(const TextureTransferOptions& options, bool gltf_input, const std::string& output,
                                  int texcoord_set);

// write_atlas_file (atlas_files.h) with the textures following the atlas when
// `textures.enabled`: a glTF input needs gltf.texcoord_set >= 0 (the set the
// textures read; it is replaced), an OBJ input its mtllib materials' map_Kd
// (map_Ks, map_Bump too) and an .obj output. An image that cannot be read or
// decoded, or a sampler it cannot honour, is Error(Input) naming the image and
// the material; nothing is written then (all files or none).
TextureTransferReport write_atlas_with_textures(const std::string& path, const MeshFile& input, const AtlasResult& r,
                                                const GltfWriteOptions& gltf, const TextureTransferOptions& textures);


}  // namespace intrinsic
