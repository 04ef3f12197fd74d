// write_atlas_with_textures (texture_transfer.h): the atlas written with its
// textures following it, through the glTF writer's hook or the OBJ side
// (docs/textures.md), and the report's "textures" object.
#include "intrinsic/atlas_files.h"
#include "intrinsic/texture_transfer.h"

#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "texture/gltf_textures.h"
#include "texture/obj_textures.h"

namespace intrinsic {

void check_texture_transfer(const TextureTransferOptions& o) {
  const auto label = [&](std::string_view key) { return option_label(key, o.spelling); };
  if (o.size < 0 || o.size > 16384)
    throw_usage(label("texture_size") + " must be 0 (each source's own density) or 1..16384");
  if (o.padding < -1 || o.padding > 1024)
    throw_usage(label("texture_padding") + " must be -1 (fill the image) or 0..1024");
  if (o.supersample < 1 || o.supersample > 4) throw_usage(label("texture_supersample") + " must be between 1 and 4");
}

void check_texture_transfer_input(const TextureTransferOptions& o, bool gltf_input, const std::string& output,
                                  int texcoord_set) {
  if (!o.enabled || !gltf_input) return;
  const auto label = [&](std::string_view key) { return option_label(key, o.spelling); };
  if (!output.empty() && mesh_extension(output) == ".obj")
    throw_usage(label("transfer_textures") + ": a glTF input is written back as .glb or .gltf");
  if (texcoord_set < 0)
    throw_usage(label("transfer_textures") + " replaces the set the textures read: add " + label("uv_set") +
                " N (usually 0)");
}

TextureTransferReport write_atlas_with_textures(const std::string& path, const MeshFile& input, const AtlasResult& r,
                                                const GltfWriteOptions& gltf, const TextureTransferOptions& textures) {
  TextureTransferReport report;
  auto keep = [&report](const GltfWriteResult& w) {
    report.files.insert(report.files.end(), w.files.begin(), w.files.end());
    report.missing_images = w.missing_images;
    // The baked images' numbers as written (replaced ones before them were dropped).
    for (BakedTexture& b : report.baked)
      if (b.output.rfind("image ", 0) == 0) {
        const std::size_t i = std::stoul(b.output.substr(6));
        if (i < w.image_index.size()) b.output = "image " + std::to_string(w.image_index[i]);
      }
  };
  if (!textures.enabled) {
    keep(write_atlas_file(path, input, r, gltf));
    return report;
  }
  check_texture_transfer(textures);
  check_atlas_output(path);
  const std::string ext = mesh_extension(path);
  const auto label = [&](std::string_view key) { return option_label(key, textures.spelling); };
  if (const GltfDocument* doc = input.document.gltf.get()) {
    check_texture_transfer_input(textures, true, path, gltf.texcoord_set);
    GltfWriteOptions o = gltf;
    o.replace_used_set = true;
    keep(write_gltf_atlas_hooked(path, input, r, o, gltf_textures::texture_hook(*doc, r, textures, report)));
    return report;
  }
  if (ext != ".obj" || input.document.obj.material_libraries.empty())
    throw_usage(label("transfer_textures") +
                " needs a glTF input, or an OBJ input with mtllib materials written as .obj");
  if (!input.mesh.has_uv())
    throw_usage(label("transfer_textures") + ": " + input.mesh.path +
                " has no texture coordinates on every face to bake from");
  return write_obj_with_textures(path, input, r, textures);
}

}  // namespace intrinsic
