// Fuzzes the whole atlas pipeline on small mutated meshes: read,
// atlas() (cleaning, optional weld, segmentation, flattening, merging,
// packing), then checks the atlas's promises with `metrics`' own measures
// (metrics.h: charts, flips per chart, exact overlaps): a result with a
// flipped, collapsed or overlapping triangle, a mirrored chart, a chart count
// other than the atlas's (with padding), or a UV outside [0,1]^2 aborts (a
// finding), as does any exception but Error.
// Input: one option byte, then the mesh file.
//   bits 0-1: format (obj, off, ply, obj)
//   bit 2: Segmentation::Components (else NormalCones)
//   bit 3: weld 1e-3 of the diagonal
//   bits 4-5: min_chart_faces 20, 0, 5, 60
//   bit 6: padding 0 (else 2), bit 7: resolution 64 (else 1024)
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "fuzz_support.h"
#include "intrinsic/atlas.h"
#include "intrinsic/metrics.h"

namespace {

[[noreturn]] void broken(const char* what, long count) {
  std::fprintf(stderr, "fuzz_atlas: %s: %ld\n", what, count);
  std::abort();
}

// The atlas's promises, measured independently of the packer.
void check(const intrinsic::MeshData& m, const intrinsic::AtlasResult& r, bool padded) {
  using namespace intrinsic;
  if (r.FUV.rows() != m.F.rows() || r.F.rows() != m.F.rows() || r.F != m.F) broken("FUV rows or faces not the input's", r.FUV.rows());
  if (!r.UV.allFinite()) broken("non-finite UV", 0);
  if (r.UV.rows() > 0 && (r.UV.minCoeff() < 0 || r.UV.maxCoeff() > 1)) broken("UV outside [0,1]^2", 0);
  // Faces as written (the input's): every chart keeps its faces' winding.
  MatrixX3d PT = MatrixX3d::Zero(r.UV.rows(), 3);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      if (r.FUV(f, c) < 0 || r.FUV(f, c) >= r.UV.rows()) broken("FUV out of range in face", f);
      PT.row(r.FUV(f, c)) = m.V.row(r.F(f, c));
    }
  const UvAtlasMetrics um = uv_atlas_metrics(PT, r.FUV, r.UV);
  if (um.flipped_triangles) broken("flipped triangles", um.flipped_triangles);
  if (um.collapsed_triangles) broken("collapsed triangles", um.collapsed_triangles);
  if (um.mirrored_charts) broken("mirrored charts", um.mirrored_charts);
  if (um.overlapping_triangles) broken("overlapping triangles", um.overlapping_triangles);
  // As many charts as the atlas reports (zero-area faces form none of their
  // own). Without padding two charts' corners may coincide and join.
  const long charts = static_cast<long>(um.charts.size()) - um.degenerate_charts;
  if (padded && charts != static_cast<long>(r.charts.size())) broken("metrics' chart count differs", charts);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace intrinsic;
  if (size < 1 || size > 4096) return 0;  // keep each execution fast
  const std::uint8_t opt = data[0];
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  static const char* const kNames[] = {"fuzz.obj", "fuzz.off", "fuzz.ply", "fuzz.obj"};
  static const int kMinFaces[] = {20, 0, 5, 60};
  return fuzz::expect_only_error([&] {
    const MeshData m = read_mesh_from_memory(text, kNames[opt & 3], fuzz::small_limits());
    AtlasOptions o;
    o.charts.segmentation = (opt & 4) ? Segmentation::Components : Segmentation::NormalCones;
    o.charts.weld = (opt & 8) ? 1e-3 : 0;
    o.charts.min_chart_faces = kMinFaces[(opt >> 4) & 3];
    o.pack.padding = (opt & 64) ? 0 : 2;
    o.pack.resolution = (opt & 128) ? 64 : 1024;
    check(m, atlas(m, o), o.pack.padding > 0);
  });
}
