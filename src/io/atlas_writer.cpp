// Writing an atlas (io.h "Atlases"): the OBJ with one texture coordinate per
// corner, or the .glb/.gltf through write_glb, chosen by the output's
// extension; a mesh read from glTF goes back into its document (gltf.h).
#include <charconv>

#include "intrinsic/atlas.h"
#include "intrinsic/error.h"
#include "intrinsic/gltf.h"
#include "intrinsic/io.h"

namespace intrinsic {
namespace {

void put(std::string& s, double x) {
  char b[32];
  s.append(b, std::to_chars(b, b + sizeof b, x).ptr);
}

void put(std::string& s, long x) {
  char b[24];
  s.append(b, std::to_chars(b, b + sizeof b, x).ptr);
}

}  // namespace

// The OBJ, streamed in blocks of lines.
void write_atlas_obj(const std::string& path, const MeshData& m, const AtlasResult& r) {
  write_file_atomically(path, [&](const ByteSink& sink) {
    std::string s = "# intrinsic atlas: " + std::to_string(r.charts.size()) + " charts\n";
    auto flush = [&](bool force) {
      if (force || s.size() > (1 << 20)) sink(s.data(), s.size()), s.clear();
    };
    for (int v = 0; v < m.V.rows(); ++v) {
      s += "v";
      for (int c = 0; c < 3; ++c) s += ' ', put(s, m.V(v, c));
      s += '\n';
      flush(false);
    }
    for (int t = 0; t < r.UV.rows(); ++t) {
      s += "vt ";
      put(s, r.UV(t, 0));
      s += ' ';
      put(s, r.UV(t, 1));
      s += '\n';
      flush(false);
    }
    for (int f = 0; f < r.F.rows(); ++f) {
      s += "f";
      for (int c = 0; c < 3; ++c) {
        s += ' ';
        put(s, static_cast<long>(r.F(f, c)) + 1);
        s += '/';
        put(s, static_cast<long>(r.FUV(f, c)) + 1);
      }
      s += '\n';
      flush(false);
    }
    flush(true);
  });
}

void check_atlas_output(const std::string& path) {
  const std::string ext = mesh_extension(path);
  if (ext != ".obj" && ext != ".glb" && ext != ".gltf")
    throw_usage("output '" + path + "': the atlas is written as .obj (one texture coordinate per corner), .glb or .gltf");
  if (ext != ".obj" && path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0)
    throw_usage("output '" + path + "': " + ext + " is written uncompressed (drop the .gz)");
}

void write_atlas_file(const std::string& path, const MeshData& m, const AtlasResult& r) {
  check_atlas_output(path);
  const std::string ext = mesh_extension(path);
  // A glTF input is written back as the same document with the atlas added.
  if (ext != ".obj" && m.gltf) write_gltf_atlas(path, m, r);
  else if (ext != ".obj") write_glb(path, m.V, r.F, r.UV, r.FUV);  // the faces as written (reorient)
  else write_atlas_obj(path, m, r);
}

}  // namespace intrinsic
