// Images of a written glTF document made to travel with it
// (gltf_images.cpp, docs/formats.md "Images travel with the output").
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "io/gltf_document.h"

namespace intrinsic::gltf {

// The file an image URI of `doc` names: the URI from the document's folder,
// else the longest tail of its path (either separator) found from that
// folder or the one above; "" when none exists or the document was given
// in memory.
std::string image_file(const GltfDocument& doc, const std::string& uri);

// A file name as a URI (RFC 3986 unreserved characters and '/' kept).
std::string uri_escape(const std::string& name);

struct PortableImages {
  std::vector<std::pair<std::string, std::string>> beside;  // (path, bytes) to write beside a .gltf
  std::vector<std::string> missing;    // URIs kept as they were (allow_missing)
  std::vector<std::string> converted;  // files turned into PNG
};

// Rewrites every image URI of the output JSON `j` (whose one buffer is
// `bin`) for the output file `output`: a .glb embeds the image as a buffer
// view; a .gltf keeps a URI that resolves from its own folder, or names a copy
// listed in `beside`. An image that cannot be found is Error(Input) naming it,
// or, with `allow_missing`, left as it was and listed.
PortableImages make_images_portable(nlohmann::json& j, std::string& bin, const GltfDocument& doc,
                                    const std::string& output, bool allow_missing);

}  // namespace intrinsic::gltf
