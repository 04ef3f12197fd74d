// The texture transfer end to end (docs/textures.md): a generated fragmented
// textured asset (generate.h) read as .glb, re-atlased, its texture baked
// into the new layout and the document written, timed as one job (median of
// --runs). With --picture PATH it instead draws docs/images/texture-transfer.png:
// the asset before and after, and the two texture layouts.
//
//   texture_transfer_bench [--cells 92] [--chart-cells 2] [--size 2048] [--runs 3]
//   texture_transfer_bench --picture docs/images/texture-transfer.png
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "intrinsic/atlas.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/generate.h"
#include "intrinsic/gltf.h"
#include "intrinsic/io.h"
#include "intrinsic/render.h"
#include "intrinsic/texture_transfer.h"

using namespace intrinsic;
namespace fs = std::filesystem;

namespace {

TextureTransferReport run(const std::string& in, const std::string& out, int size, AtlasResult* atlas_out = nullptr) {
  const MeshFile m = read_mesh_file(in);
  const AtlasResult r = atlas(m, AtlasOptions{});
  GltfWriteOptions g;
  g.texcoord_set = 0;
  TextureTransferOptions t;
  t.enabled = true;
  t.size = size;
  TextureTransferReport rep = write_atlas_with_textures(out, m, r, g, t);
  if (atlas_out) *atlas_out = r;
  return rep;
}

// Nearest-texel resize of a texture to a square panel.
Image panel(const Image& t, int side) {
  Image p(side, side);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x)
      std::copy_n(t.pixel(x * t.width / side, y * t.height / side), 3, p.pixel(x, y));
  return p;
}

// The OBJ written beside for drawing: per corner UVs are what render wants.
Image draw(const std::string& obj, const Image& texture, int side) {
  const MeshData m = read_mesh(obj);
  MatrixX3d V(3 * m.F.rows(), 3);
  MatrixX3i F(m.F.rows(), 3);
  MatrixX2d UV(3 * m.F.rows(), 2);
  for (int f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      V.row(3 * f + k) = m.V.row(m.F(f, k));
      UV.row(3 * f + k) = m.TC.row(m.FTC(f, k));
      F(f, k) = 3 * f + k;
    }
  RenderOptions o;
  o.width = o.height = side;
  o.auto_view = false;
  o.azimuth_deg = 35, o.elevation_deg = 25;
  o.texture = &texture;
  return render_checker(V, F, UV, o);
}

int picture(const std::string& path) {
  const fs::path dir = fs::temp_directory_path() / "intrinsic-texture-picture";
  fs::create_directories(dir);
  TexturedAssetOptions o;
  o.cells = 16, o.chart_cells = 1, o.texture_size = 1024;
  const TexturedAsset a = generate_textured_asset(o);
  write_textured_asset((dir / "in.obj").string(), a);
  const MeshFile m = read_mesh_file((dir / "in.obj").string());
  const AtlasResult r = atlas(m, AtlasOptions{});
  TextureTransferOptions t;
  t.enabled = true, t.size = 1024;
  const TextureTransferReport rep = write_atlas_with_textures((dir / "out.obj").string(), m, r, GltfWriteOptions{}, t);
  const Image baked = decode_png([&] {
    std::FILE* f = std::fopen(rep.baked.at(0).output.c_str(), "rb");
    std::string s;
    char b[65536];
    for (std::size_t n; (n = std::fread(b, 1, sizeof b, f)) > 0;) s.append(b, n);
    std::fclose(f);
    return s;
  }());
  const int side = 400;
  const Image img = compose_panels(
      {draw((dir / "in.obj").string(), a.texture, side), draw((dir / "out.obj").string(), baked, side),
       panel(a.texture, side), panel(baked, side)},
      {"before: " + std::to_string(m.mesh.F.rows()) + " faces, 1,536 tiny charts", "after: re-atlased, texture baked",
       "old texture layout", "new texture layout (" + std::to_string(r.charts.size()) + " charts)"},
      2);
  write_file_atomically(path, encode_png(img));
  fs::remove_all(dir);
  std::printf("%s\n", path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  TexturedAssetOptions o;
  o.cells = 92, o.chart_cells = 2, o.texture_size = 2048;
  int size = 2048, runs = 3;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i];
    if (k == "--picture") return picture(argv[i + 1]);
    const int v = std::atoi(argv[i + 1]);
    if (k == "--cells") o.cells = v;
    else if (k == "--chart-cells") o.chart_cells = v;
    else if (k == "--size") size = v;
    else if (k == "--runs") runs = v;
  }
  const fs::path dir = fs::temp_directory_path() / "intrinsic-texture-bench";
  fs::create_directories(dir);
  const std::string in = (dir / "in.glb").string(), out = (dir / "out.glb").string();
  const TexturedAsset a = generate_textured_asset(o);
  write_textured_asset(in, a);
  std::vector<double> ms;
  TextureTransferReport rep;
  for (int i = 0; i < runs; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    rep = run(in, out, size);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  std::printf("textured asset: %ld faces, %dx%d source texture; read + atlas + bake %dx%d + write: median %.0f ms of %d runs "
              "(min %.0f, max %.0f); texels covered %ld\n",
              static_cast<long>(a.mesh.F.rows()), o.texture_size, o.texture_size, size, size, ms[ms.size() / 2], runs,
              ms.front(), ms.back(), rep.baked.empty() ? 0L : rep.baked[0].texels_covered);
  fs::remove_all(dir);
  return 0;
}
