// The OBJ side of the texture transfer (obj_textures.cpp, docs/textures.md).
#pragma once

#include "intrinsic/texture_transfer.h"

namespace intrinsic {

// The atlas OBJ at `path` with each mtllib material's map_Kd (map_Ks,
// map_Bump) baked into PNGs beside it (STEM_<material>_Kd.png), a new
// STEM.mtl pointing at them, and the OBJ's mtllib pointing at that; all files
// or none.
TextureTransferReport write_obj_with_textures(const std::string& path, const MeshFile& input, const AtlasResult& r,
                                              const TextureTransferOptions& options);

}  // namespace intrinsic
