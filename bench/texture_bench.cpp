// Timings of the texel transfer (not a test): a generated bumpy sphere of
// about 100k faces, re-atlased by `atlas`, its texture moved from a
// latitude-longitude layout into the atlas at 2048^2. Prints one markdown
// row per case, medians of `runs` repetitions.
//   texture_bench [runs] [rings]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bench_timing.h"
#include "intrinsic/atlas.h"
#include "intrinsic/generate.h"
#include "intrinsic/texture.h"

using namespace intrinsic;

namespace {

using intrinsic::bench::median;
using intrinsic::bench::ms_since;

template <class Fn>
double time_ms(int runs, Fn&& fn) {
  std::vector<double> t;
  for (int k = 0; k < runs; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  return median(t);
}

// A smooth colour pattern with some high frequencies, 8-bit RGBA.
Texture synthetic_source(int size) {
  Texture t;
  t.width = t.height = size, t.channels = 4, t.bits = 8;
  t.texels.resize(static_cast<std::size_t>(size) * size * 4);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      float* p = &t.texels[(static_cast<std::size_t>(y) * size + x) * 4];
      p[0] = std::round(255 * (0.5f + 0.4f * std::sin(0.05f * x) * std::cos(0.03f * y))) / 255;
      p[1] = std::round(255 * (0.5f + 0.4f * std::sin(0.21f * x + 0.13f * y))) / 255;
      p[2] = ((x / 16 + y / 16) % 2) ? 0.8f : 0.2f;
      p[3] = 1;
    }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::atoi(argv[1]) : 3;
  GenerateOptions g;
  g.rings = argc > 2 ? std::atoi(argv[2]) : 158;
  const MeshData mesh = generate_bumpy_sphere(g);
  const auto t0 = std::chrono::steady_clock::now();
  const AtlasResult a = atlas(mesh);
  const double atlas_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const Eigen::Index m = a.F.rows();
  TransferMesh tm;
  tm.old_uv.resize(3 * m, 2), tm.new_uv.resize(3 * m, 2), tm.normal.resize(3 * m, 3);
  Eigen::MatrixX3d pos(3 * m, 3);
  for (Eigen::Index f = 0; f < m; ++f)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = mesh.V.row(a.F(f, k)).transpose();
      pos.row(3 * f + k) = p.transpose();
      tm.normal.row(3 * f + k) = p.normalized().transpose();  // close enough for timing
      tm.old_uv.row(3 * f + k) << 0.5 + std::atan2(p.y(), p.x()) / (2 * M_PI), std::acos(p.z() / p.norm()) / M_PI;
      tm.new_uv.row(3 * f + k) = a.UV.row(a.FUV(f, k));
    }
  std::printf("bumpy sphere, %ld faces, atlas %.0f ms (%zu charts), source 2048^2 RGBA8, %d runs (median)\n\n",
              static_cast<long>(m), atlas_ms, a.charts.size(), runs);
  std::printf("| case | texels covered | edge | dilated | time |\n|---|---|---|---|---|\n");
  const Texture source = synthetic_source(2048);
  for (int ss : {1, 2})
    for (TextureRole role : {TextureRole::Color, TextureRole::Data}) {
      TransferOptions o;
      o.role = role, o.supersample = ss;
      TransferResult r;
      const double ms = time_ms(runs, [&] { r = transfer_texture(tm, source, TextureSampler{}, o); });
      std::printf("| %s, supersample %d | %ld | %ld | %ld | %.0f ms |\n", role == TextureRole::Color ? "Color" : "Data",
                  ss, r.texels_covered, r.texels_edge, r.texels_dilated, ms);
    }
  Eigen::MatrixX2d up_old = tm.old_uv, up_new = tm.new_uv;
  up_old.col(1) = (1 - up_old.col(1).array()).matrix();
  up_new.col(1) = (1 - up_new.col(1).array()).matrix();
  const double tan_ms = time_ms(runs, [&] { tm.old_tangent = compute_tangents(pos, tm.normal, up_old); });
  tm.new_tangent = compute_tangents(pos, tm.normal, up_new);
  std::printf("| compute_tangents (one layout) | | | | %.0f ms |\n", tan_ms);
  TransferOptions o;
  o.role = TextureRole::TangentNormal;
  TransferResult r;
  const double ms = time_ms(runs, [&] { r = transfer_texture(tm, source, TextureSampler{}, o); });
  std::printf("| TangentNormal, supersample 1 | %ld | %ld | %ld | %.0f ms |\n", r.texels_covered, r.texels_edge,
              r.texels_dilated, ms);
  const double enc = time_ms(runs, [&] { encode_texture_png(r.texture); });
  std::printf("| encode_texture_png 2048^2 RGBA8 | | | | %.0f ms |\n", enc);
  return 0;
}
