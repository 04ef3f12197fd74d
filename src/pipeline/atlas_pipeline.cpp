// The atlas job of pipeline.h (`intrinsic atlas` without its command line):
// read the mesh with its document (which the writers give back, and which
// tells a glTF input's texture coordinates and meshes) or take the mesh,
// read the seams file against it, build the atlas (atlas.h).
#include <chrono>

#include "intrinsic/atlas_files.h"
#include "intrinsic/gltf.h"
#include "intrinsic/pipeline.h"
#include "intrinsic/texture_transfer.h"

namespace intrinsic {
namespace {

using Clock = std::chrono::steady_clock;

AtlasOutcome run(MeshFile input, const AtlasRequest& request, Clock::time_point t0) {
  AtlasOutcome out;
  out.input = std::move(input);
  out.options = request.options;
  if (!request.seams_file.empty()) out.options.charts.seams = read_seams_file(request.seams_file, out.input.mesh);
  if (out.options.pack_only && out.input.document.gltf)
    read_gltf_texcoords(out.input, request.gltf.texcoord_set < 0 ? 0 : request.gltf.texcoord_set);
  out.read_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  out.result = atlas(out.input, out.options);
  return out;
}

}  // namespace

AtlasOutcome atlas_file(const std::string& path, const AtlasRequest& request) {
  if (request.textures.enabled) check_texture_transfer(request.textures);
  const std::string ext = mesh_extension(path);
  check_texture_transfer_input(request.textures, ext == ".gltf" || ext == ".glb", request.output,
                               request.gltf.texcoord_set);
  const auto t0 = Clock::now();
  return run(read_mesh_file(path, request.read), request, t0);
}

AtlasOutcome atlas_data(MeshData data, const AtlasRequest& request) {
  if (request.textures.enabled) check_texture_transfer(request.textures);
  return run(MeshFile{std::move(data)}, request, Clock::now());
}

}  // namespace intrinsic
