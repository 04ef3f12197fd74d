// The pack stage (atlas.h: pack_charts): the charts of compute_charts or
// charts_from_ids, at surface scale, packed into [0,1]^2 at one texel
// density (atlas_packing.cpp), the degenerate faces placed, and the packed
// atlas measured (seam length, stretch: docs/maths.md §9.6, §9.8). The
// charts are copied, so the same AtlasCharts packs again at another
// resolution or padding without a chart being recomputed.
#include <algorithm>
#include <array>
#include <chrono>
#include <string>

#include "atlas/atlas_internal.h"
#include "intrinsic/error.h"
#include "intrinsic/metrics.h"

namespace intrinsic {
namespace {

// The shapes pack_charts relies on; Error(Usage) otherwise (an AtlasCharts
// changed by hand).
void check_shapes(const AtlasCharts& c) {
  const long nf = c.F.rows();
  if (c.FUV.rows() != nf || static_cast<long>(c.face_chart.size()) != nf)
    throw_usage("the charts' FUV and face_chart must have one row per face of F");
  if (c.F.size() > 0 && (c.F.minCoeff() < 0 || c.F.maxCoeff() >= c.V.rows()))
    throw_usage("the charts' F refers to a vertex outside V");
  const int charts = static_cast<int>(c.charts.size());
  for (long f = 0; f < nf; ++f) {
    const int k = c.face_chart[f];
    const bool none = c.FUV.row(f).minCoeff() < 0;
    if (k < -1 || k >= charts || (k < 0) != none || c.FUV.row(f).maxCoeff() >= c.UV.rows())
      throw_usage("face " + std::to_string(f) + ": its chart " + std::to_string(k) +
                  " or its UV rows do not fit the charts (FUV -1 exactly where face_chart is -1)");
  }
}

// The charts as the packer takes them: per chart its faces (in face order),
// its block of UV rows and its faces in those rows (as written). Each
// chart's rows must be one block, the blocks in chart order.
std::vector<detail::FlatChart> unstore(const AtlasCharts& c) {
  const int n = static_cast<int>(c.charts.size());
  std::vector<detail::FlatChart> flat(n);
  std::vector<int> lo(n, INT32_MAX), hi(n, -1);
  for (int f = 0; f < static_cast<int>(c.face_chart.size()); ++f) {
    const int k = c.face_chart[f];
    if (k < 0) continue;
    flat[k].mesh.faces.push_back(f);
    lo[k] = std::min(lo[k], c.FUV.row(f).minCoeff());
    hi[k] = std::max(hi[k], c.FUV.row(f).maxCoeff());
  }
  int next = 0;
  for (int k = 0; k < n; ++k) {
    if (flat[k].mesh.faces.empty() || lo[k] != next)
      throw_usage("chart " + std::to_string(k) + ": no faces, or its UV rows are not the block after chart " +
                  std::to_string(k - 1) + "'s");
    detail::FlatChart& chart = flat[k];
    chart.summary = c.charts[k];
    chart.UV = c.UV.middleRows(lo[k], hi[k] - lo[k] + 1);
    chart.mesh.data.F.resize(static_cast<int>(chart.mesh.faces.size()), 3);
    for (size_t i = 0; i < chart.mesh.faces.size(); ++i)
      chart.mesh.data.F.row(static_cast<int>(i)) = c.FUV.row(chart.mesh.faces[i]).array() - lo[k];
    next = hi[k] + 1;
  }
  // Every row used: an unused one would still count in its chart's box.
  std::vector<char> used(c.UV.rows(), 0);
  for (int f = 0; f < static_cast<int>(c.face_chart.size()); ++f)
    if (c.face_chart[f] >= 0)
      for (int j = 0; j < 3; ++j) used[c.FUV(f, j)] = 1;
  if (next != c.UV.rows() || std::find(used.begin(), used.end(), 0) != used.end())
    throw_usage("the charts' UV has rows no chart uses");
  return flat;
}

// AtlasResult::seam_length: distinct UV pairs per input edge, beyond the first.
double seam_length(const MatrixX3d& V, const MatrixX3i& F, const MatrixX3i& FUV) {
  std::vector<std::array<int, 4>> edges;  // (lower vertex, higher vertex, its UV, the other's UV)
  edges.reserve(3 * static_cast<size_t>(F.rows()));
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int d = (c + 1) % 3, a = F(f, c), b = F(f, d);
      if (a == b) continue;
      if (a < b) edges.push_back({a, b, FUV(f, c), FUV(f, d)});
      else edges.push_back({b, a, FUV(f, d), FUV(f, c)});
    }
  std::sort(edges.begin(), edges.end());
  double length = 0;
  for (size_t i = 1; i < edges.size(); ++i)
    if (edges[i][0] == edges[i - 1][0] && edges[i][1] == edges[i - 1][1] && edges[i] != edges[i - 1])
      length += (V.row(edges[i][0]) - V.row(edges[i][1])).norm();
  return length;
}

// Pairs of faces whose UV triangles' interiors meet, in one chart or two,
// measured exactly on the layout as written (pages side by side in u): the
// packer and the chart checks make it 0, and the report says so by
// measurement rather than by their construction.
int overlapping_pairs(const AtlasResult& r) {
  int within = 0, between = 0;
  overlapping_uv_triangles(r.FUV, r.UV, &within, &between, &r.face_chart);
  return within + between;
}

}  // namespace

AtlasResult pack_charts(const AtlasCharts& c, const PackOptions& options) {
  detail::check_pack_options(options);
  check_shapes(c);
  const auto t = std::chrono::steady_clock::now();
  std::vector<detail::FlatChart> charts = unstore(c);
  AtlasResult r;
  detail::PageLayout pages;
  r.utilization = detail::pack_flat_charts(charts, options, &pages);
  if (options.texels_per_unit > 0) {
    r.pages = static_cast<int>(pages.page_utilization.size());
    r.chart_page = std::move(pages.chart_page);
    r.page_utilization = std::move(pages.page_utilization);
    r.shrunk_charts = std::move(pages.shrunk);
  } else {
    r.chart_page.assign(charts.size(), 0);
    r.page_utilization = {r.utilization};
  }
  // The packed charts' rows in the same blocks, one more (zero) row for
  // degenerate faces none of whose vertices is in a chart.
  const int rows = static_cast<int>(c.UV.rows());
  r.UV.resize(rows + 1, 2);
  int offset = 0;
  for (const detail::FlatChart& chart : charts) {
    r.UV.middleRows(offset, chart.UV.rows()) = chart.UV;
    offset += static_cast<int>(chart.UV.rows());
  }
  r.UV.row(rows) << 0, 0;
  r.F = c.F;
  r.FUV = c.FUV;
  r.face_chart = c.face_chart;
  detail::place_degenerate_faces(c.V, r.F, r.face_chart, r.UV, r.FUV, rows);
  r.seam_length = seam_length(c.V, r.F, r.FUV);
  r.overlapping = overlapping_pairs(r);
  for (const detail::FlatChart& chart : charts) {
    r.charts.push_back(chart.summary);
    r.flipped += chart.summary.flipped;
  }
  r.components = c.components;
  r.splits = c.splits;
  r.split_reasons = c.split_reasons;
  r.split_groups = c.split_groups;
  r.stretch_l2_mean = c.stretch_l2_mean;
  r.stretch = summarize_stretch(c.V, r.F, r.UV, r.FUV);
  r.cleaning = c.cleaning;
  r.timings = c.timings;
  const auto ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
  r.timings.pack_ms = ms;
  r.timings.total_ms = c.timings.total_ms + ms;
  return r;
}

}  // namespace intrinsic
