// Fuzzes the seams file (`atlas --seams`, one edge "i j" per line) and what
// the atlas does with it, on a fixed small mesh: parse_seams_text, then
// atlas() cutting there (every chart split until valid, merged, packed). The
// mesh is the bumped 5 x 5 vertex grid without its quad at (1, 1) (vertex
// y * 5 + x; two faces per quad, (a, a+1, a+6) and (a, a+6, a+5), row by
// row: 30 faces, as fuzz/make_corpus.py assumes for the seeds).
#include "fuzz_support.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/io.h"
#include "intrinsic/atlas.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace intrinsic;
  static const MeshData grid = [] {
    const Mesh mesh = fuzz::bumped_grid(true);
    MeshData d;
    d.V = mesh.V;
    d.F = mesh.F;
    return d;
  }();
  return fuzz::expect_only_error([&] {
    AtlasOptions o;
    o.charts.seams = parse_seams_text(std::string(reinterpret_cast<const char*>(data), size), "fuzz.txt", grid);
    o.pack.resolution = 64;
    o.charts.max_charts = static_cast<int>(size % 4);
    atlas(grid, o);
  });
}
