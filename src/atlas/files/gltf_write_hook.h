// A hook into write_gltf_atlas for what adds to the written document
// (the texture transfer, src/texture/gltf_textures.cpp): once every primitive
// is rewritten, and before anything is written, the hook sees the output
// JSON, the one output buffer's bytes and how each primitive was split, and
// may add images, textures, attributes. An exception from it writes nothing.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "intrinsic/atlas_files.h"
#include "intrinsic/gltf.h"
#include "io/gltf_document.h"

namespace intrinsic {

struct GltfWrittenPrimitive {
  const GltfDocument::Primitive* source = nullptr;  // in the document's primitives
  int set = 0;                                      // the TEXCOORD_n the atlas went to
  // Per output vertex: its index in the primitive's attributes and its atlas
  // UV row (AtlasResult::UV); per input corner (faces in order, the
  // document's winding): its output vertex.
  std::vector<int> vertex_source, vertex_uv;
  std::vector<std::uint32_t> index;
};

using GltfWriteHook =
    std::function<void(nlohmann::json& out, std::string& bin, const std::vector<GltfWrittenPrimitive>& written)>;

// write_gltf_atlas with `hook` called before the document is serialized.
GltfWriteResult write_gltf_atlas_hooked(const std::string& path, const MeshFile& input, const AtlasResult& result,
                                        const GltfWriteOptions& options, const GltfWriteHook& hook);

}  // namespace intrinsic
