// The OBJ side of the texture transfer (docs/textures.md): placeholder until
// the .mtl maps are baked.
#include "texture/obj_textures.h"

#include "intrinsic/error.h"

namespace intrinsic {

TextureTransferReport write_obj_with_textures(const std::string& path, const MeshData&, const AtlasResult&,
                                              const TextureTransferOptions&) {
  throw_usage("output '" + path + "': transfer_textures for OBJ is not available yet");
}

}  // namespace intrinsic
