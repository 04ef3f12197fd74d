// intrinsic::atlas (atlas.h): clean -> segment -> flatten and check
// every chart, splitting the invalid ones until each is valid (a single
// non-degenerate triangle always is) -> pack -> per-corner UVs. Every chart is
// flattened by the paper's natural conformal map (section 4.2) through the
// one Parameterizer (chart_flatten.cpp).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <deque>

#include "atlas/atlas_internal.h"
#include "intrinsic/error.h"
#include "util/parallel_for.h"

namespace intrinsic {

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void check_options(const AtlasOptions& o) {
  if (!(o.max_normal_deviation_deg > 0 && o.max_normal_deviation_deg <= 180))
    throw_usage("the normal deviation must be in (0, 180] degrees");
  if (!(o.hard_angle_deg >= 0 && o.hard_angle_deg < 180))
    throw_usage("the hard angle must be in [0, 180) degrees (0: no hard edges)");
  if (!(o.sharp_angle_deg > 0 && o.sharp_angle_deg <= 180)) throw_usage("the sharp angle must be in (0, 180] degrees");
  if (o.resolution < 1 || o.resolution > 1 << 20) throw_usage("the resolution must be between 1 and 1048576 texels");
  if (!(o.padding >= 0 && o.padding < o.resolution / 4.0))
    throw_usage("the padding must be at least 0 and less than a quarter of the resolution");
  if (o.min_chart_faces < 0) throw_usage("the minimum chart size must be at least 0 faces");
  if (!(o.max_stretch >= 1)) throw_usage("the stretch bound must be at least 1");
  if (!(o.max_face_stretch >= 1)) throw_usage("the per-face stretch bound must be at least 1");
  if (o.chart_map.isometric_iterations < 0) throw_usage("the isometric refinement steps must be at least 0");
  if (o.max_charts < 0) throw_usage("the chart limit must be at least 0 (0: no limit)");
  if (!(o.degenerate_ratio >= 0 && o.degenerate_ratio < 1)) throw_usage("the degenerate ratio must be in [0, 1)");
  if (!(o.weld >= 0 && o.weld < 1))
    throw_usage("the weld distance must be in [0, 1) (a fraction of the bounding box diagonal)");
  const ChartMapOptions& m = o.chart_map;
  if (m.boundary != BoundaryShape::Natural && m.boundary != BoundaryShape::Circle &&
      m.boundary != BoundaryShape::Square)
    throw_usage("a chart's boundary is natural, circle or square");
  if (m.optimizer != ChartOptimizer::None && m.boundary == BoundaryShape::Natural)
    throw_usage("optimal lambda and boundary optimization need a fixed chart boundary (circle or square)");
  // Checked here rather than per chart: a chart whose solve fails is split,
  // so a bad option would otherwise end in single triangles, not an error.
  check_weights(m.weights);
}

void count_split(detail::ChartStatus status, AtlasResult& r) {
  ++r.splits;
  AtlasSplits& s = r.split_reasons;
  switch (status) {
    case detail::ChartStatus::NotDisk: ++s.not_disk; break;
    case detail::ChartStatus::Refused: ++s.refused; break;
    case detail::ChartStatus::SolveFailed: ++s.solve_failed; break;
    case detail::ChartStatus::Flipped: ++s.flipped; break;
    case detail::ChartStatus::BoundaryCrossing: ++s.boundary_crossing; break;
    case detail::ChartStatus::Sparse: ++s.sparse; break;
    case detail::ChartStatus::Stretch: ++s.stretch; break;
    case detail::ChartStatus::Valid: break;
  }
}

// Flattens one chart and checks it; a valid chart that would waste most of
// its square (sparse, or a long thin strip) is reported Sparse when `sparse`
// splits are wanted (not with the user's seams: those charts are theirs, nor
// for charts under `min_sparse_area`). A chart already sparse in projection
// onto its mean plane is reported Sparse before its map is solved.
detail::ChartStatus flatten_one(const MeshData& input, const detail::CleanMesh& clean, const std::vector<int>& faces,
                                const AtlasOptions& options, detail::FlatChart& chart) {
  const double surface_area = clean.surface_area;
  chart.mesh = detail::chart_mesh(input, clean, faces);
  chart.summary.component = clean.component[faces.front()];
  double area = 0;
  for (int f : faces) area += clean.area[f];
  // Charts under 0.5% of the surface are never split for their shape: the
  // packer puts small masks into the gaps of the large ones, so their
  // boxes hardly matter (on a 1M-vertex sphere, 98 such splits of slivers
  // left the utilization unchanged to 13 digits, with 141 charts instead of 45).
  const bool packs = options.seams.empty() && faces.size() >= 64 && area >= 0.005 * surface_area;
  if (packs && !detail::packs_well(detail::planar_chart_box(chart.mesh), surface_area))
    return detail::ChartStatus::Sparse;
  detail::ChartStatus status = detail::flatten_chart(chart, options.chart_map, options.degenerate_ratio);
  if (status == detail::ChartStatus::Valid && packs && !detail::packs_well(detail::chart_box(chart), surface_area))
    status = detail::ChartStatus::Sparse;
  if (status == detail::ChartStatus::Valid && options.seams.empty() && faces.size() > 1 &&
      !detail::within_stretch(chart.summary, options.max_stretch, options.max_face_stretch))
    status = detail::ChartStatus::Stretch;
  return status;
}

// Flattens every chart, splitting invalid ones in two until all are valid.
// Rounds: the charts of one round are solved in parallel (interleaved over
// the cores, each chart's result in its own slot), so the order of the
// result is that of a first-in first-out queue whatever the timing.
std::vector<detail::FlatChart> flatten_all(const MeshData& input, const detail::CleanMesh& clean,
                                           std::vector<std::vector<int>> work, const AtlasOptions& options,
                                           AtlasResult& r) {
  std::vector<detail::FlatChart> done;
  while (!work.empty()) {
    const std::int64_t n = static_cast<std::int64_t>(work.size());
    std::vector<detail::FlatChart> flat(work.size());
    std::vector<detail::ChartStatus> status(work.size());
    const int parts = detail::parallel_parts(n, 1);
    detail::parallel_for_parts(parts, parts, [&](int part, std::int64_t, std::int64_t) {
      for (std::int64_t i = part; i < n; i += parts)
        status[i] = flatten_one(input, clean, work[i], options, flat[i]);
    });
    std::vector<std::vector<int>> next;
    for (std::int64_t i = 0; i < n; ++i) {
      if (status[i] == detail::ChartStatus::Valid) {
        done.push_back(std::move(flat[i]));
        continue;
      }
      if (work[i].size() == 1) throw_numerical("face " + std::to_string(work[i][0]) + " could not be laid flat");
      count_split(status[i], r);
      for (std::vector<int>& half : detail::split_in_two(clean, work[i])) next.push_back(std::move(half));
    }
    work = std::move(next);
  }
  return done;
}

// The faces to write (the input's; with reorient, reversed ones 0, 2, 1) and
// per-corner indices into one UV array in their corner order; degenerate
// faces get theirs from place_degenerate_faces.
void assemble(const MeshData& input, const std::vector<char>& reversed, const std::vector<detail::FlatChart>& charts,
              AtlasResult& r) {
  const int nf = static_cast<int>(input.F.rows());
  long rows = 0;
  for (const detail::FlatChart& c : charts) rows += c.UV.rows();
  r.UV.resize(rows + 1, 2);
  r.FUV = MatrixX3i::Constant(nf, 3, -1);
  r.face_chart.assign(nf, -1);
  int offset = 0;
  for (size_t k = 0; k < charts.size(); ++k) {
    const detail::FlatChart& c = charts[k];
    r.UV.middleRows(offset, c.UV.rows()) = c.UV;
    for (size_t i = 0; i < c.mesh.faces.size(); ++i) {
      const int f = c.mesh.faces[i];
      r.face_chart[f] = static_cast<int>(k);
      for (int j = 0; j < 3; ++j) r.FUV(f, j) = offset + c.mesh.corner[3 * i + j];
    }
    offset += static_cast<int>(c.UV.rows());
  }
  r.F = input.F;
  for (int f = 0; f < nf; ++f)
    if (reversed[f]) {
      std::swap(r.F(f, 1), r.F(f, 2));
      std::swap(r.FUV(f, 1), r.FUV(f, 2));
    }
  r.UV.row(offset) << 0, 0;  // for degenerate faces none of whose vertices is in a chart
  detail::place_degenerate_faces(input.V, r.F, r.face_chart, r.UV, r.FUV, offset);
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

}  // namespace

AtlasResult atlas(const MeshData& given, const AtlasOptions& options) {
  check_options(options);
  const auto t0 = std::chrono::steady_clock::now();
  AtlasResult r;
  // --weld: the computation sees welded faces; the result's rows stay the input's faces.
  int welded = 0;
  MeshData welded_mesh;
  if (options.weld > 0) welded_mesh = detail::weld_vertices(given, options.weld, welded);
  const MeshData& input = options.weld > 0 ? welded_mesh : given;
  detail::CleanMesh clean = detail::clean_mesh(input, options);
  // Seams name the user's vertices; faces keep their rows through welding.
  if (!options.seams.empty()) detail::cut_seams(given, options.seams, clean);
  if (options.hard_angle_deg > 0) clean.cleaning.hard_edges = detail::cut_hard_edges(options.hard_angle_deg, clean);
  r.cleaning = clean.cleaning;
  r.cleaning.welded_vertices = welded;
  r.components = clean.components;
  r.timings.clean_ms = ms_since(t0);
  auto t = std::chrono::steady_clock::now();
  std::vector<std::vector<int>> segments = detail::segment(input, clean, options);
  r.timings.segment_ms = ms_since(t);
  t = std::chrono::steady_clock::now();
  std::vector<detail::FlatChart> charts = flatten_all(input, clean, std::move(segments), options, r);
  r.timings.flatten_ms = ms_since(t);
  t = std::chrono::steady_clock::now();
  if ((options.seams.empty() && options.min_chart_faces > 0) || options.max_charts > 0)
    detail::merge_charts(input, clean, options, charts);
  r.timings.merge_ms = ms_since(t);
  t = std::chrono::steady_clock::now();
  r.utilization = detail::pack_charts(charts, options, r.overlapping);
  assemble(given, clean.reversed, charts, r);
  double area = 0, stretch = 0;
  r.seam_length = seam_length(given.V, r.F, r.FUV);
  for (const detail::FlatChart& c : charts) {
    r.charts.push_back(c.summary);
    r.charts.back().boundary_length = c.mesh.boundary_length;
    r.flipped += c.summary.flipped;
    area += c.summary.area_3d;
    stretch += c.summary.area_3d * c.summary.stretch_l2_mean;
  }
  if (area > 0) r.stretch_l2_mean = stretch / area;
  r.stretch = summarize_stretch(given.V, r.F, r.UV, r.FUV);
  r.timings.pack_ms = ms_since(t);
  r.timings.total_ms = ms_since(t0);
  return r;
}

}  // namespace intrinsic
