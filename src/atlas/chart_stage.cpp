// The charts stage (atlas.h): compute_charts (clean -> segment -> flatten and
// check every chart, splitting the invalid ones until each is valid (a
// single non-degenerate triangle always is) -> merge) and charts_from_ids
// (the user's charts: clean -> their pieces -> flatten and split only where
// invalid). Every chart is flattened by the paper's natural conformal map
// (section 4.2) through the one Parameterizer (chart_flatten.cpp), or the
// map ChartMapOptions chooses. The result is at surface scale, not packed.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <numeric>
#include <string>

#include "atlas/atlas_internal.h"
#include "atlas/thresholds.h"
#include "intrinsic/error.h"
#include "util/parallel_for.h"
#include "util/stopwatch.h"

namespace intrinsic {
using detail::ms_since;
namespace {

void count_split(detail::ChartStatus status, AtlasCharts& r) {
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
// its square (sparse, or a long thin strip) is reported Sparse and one over
// the stretch bound Stretch, unless the charts are the user's (`own`: their
// seams or ids; those are split only where invalid), nor for charts too
// small for their shape to matter (thresholds.h). A chart already sparse in
// projection onto its mean plane is reported Sparse before its map is solved.
detail::ChartStatus flatten_one(const MeshData& input, const detail::CleanMesh& clean, const std::vector<int>& faces,
                                const ChartOptions& options, bool own, detail::FlatChart& chart) {
  const double surface_area = clean.surface_area;
  chart.mesh = detail::chart_mesh(input, clean, faces);
  chart.summary.component = clean.component[faces.front()];
  // Components: the user's pieces, split only where invalid or over the stretch bound.
  const bool packs = !own && options.segmentation == Segmentation::NormalCones &&
                     static_cast<long>(faces.size()) >= detail::kSparseMinFaces;
  const double part_diameter = clean.component_diameter[clean.component[faces.front()]];
  if (packs && !detail::packs_well(detail::planar_chart_box(chart.mesh), surface_area, part_diameter))
    return detail::ChartStatus::Sparse;
  detail::ChartStatus status = detail::flatten_chart(chart, options.chart_map, options.degenerate_ratio);
  if (status == detail::ChartStatus::Valid && packs && !detail::packs_well(detail::chart_box(chart), surface_area, part_diameter))
    status = detail::ChartStatus::Sparse;
  if (status == detail::ChartStatus::Valid && !own && faces.size() > 1 &&
      !detail::within_stretch(chart.summary, options.max_stretch, options.max_face_stretch))
    status = detail::ChartStatus::Stretch;
  return status;
}

// Flattens every chart, splitting invalid ones in two until all are valid.
// Rounds: the charts of one round are solved in parallel, the largest first,
// each core taking the next chart when it is free (one large chart no longer
// waits behind others dealt to the same core); each chart's result is in its
// own slot, so the order of the result is that of a first-in first-out
// queue whatever the timing.
std::vector<detail::FlatChart> flatten_all(const MeshData& input, const detail::CleanMesh& clean,
                                           std::vector<std::vector<int>> work, const ChartOptions& options, bool own,
                                           AtlasCharts& r) {
  std::vector<detail::FlatChart> done;
  while (!work.empty()) {
    const std::int64_t n = static_cast<std::int64_t>(work.size());
    std::vector<detail::FlatChart> flat(work.size());
    std::vector<detail::ChartStatus> status(work.size());
    std::vector<std::int64_t> order(work.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::int64_t a, std::int64_t b) { return work[a].size() > work[b].size(); });
    std::atomic<std::int64_t> next_chart{0};
    const int parts = detail::parallel_parts(n, 1);
    detail::parallel_for_parts(parts, parts, [&](int, std::int64_t, std::int64_t) {
      for (std::int64_t k; (k = next_chart.fetch_add(1)) < n;) {
        const std::int64_t i = order[k];
        status[i] = flatten_one(input, clean, work[i], options, own, flat[i]);
      }
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

// The computation's view of `given`: welded (into `welded_mesh`, when
// options.weld asks for it), cleaned, the user's seams and the hard edges
// cut. Fills r's cleaning, components and clean_ms.
detail::CleanMesh prepare(const MeshData& given, const ChartOptions& options, MeshData& welded_mesh, AtlasCharts& r) {
  const auto t0 = std::chrono::steady_clock::now();
  // --weld: the computation sees welded faces; the result's rows stay the input's faces.
  int welded = 0;
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
  return clean;
}

// The charts as AtlasCharts' arrays: the faces to write (the input's; with
// reorient, reversed ones 0, 2, 1) and per-corner indices into one UV array
// in their corner order, each chart's rows one block; degenerate faces -1.
void store(const MeshData& given, const std::vector<char>& reversed, const std::vector<detail::FlatChart>& charts,
           AtlasCharts& r) {
  const int nf = static_cast<int>(given.F.rows());
  long rows = 0;
  for (const detail::FlatChart& c : charts) rows += c.UV.rows();
  r.V = given.V;
  r.UV.resize(rows, 2);
  r.FUV = MatrixX3i::Constant(nf, 3, -1);
  r.face_chart.assign(nf, -1);
  int offset = 0;
  double area = 0, stretch = 0;
  for (size_t k = 0; k < charts.size(); ++k) {
    const detail::FlatChart& c = charts[k];
    r.UV.middleRows(offset, c.UV.rows()) = c.UV;
    for (size_t i = 0; i < c.mesh.faces.size(); ++i) {
      const int f = c.mesh.faces[i];
      r.face_chart[f] = static_cast<int>(k);
      for (int j = 0; j < 3; ++j) r.FUV(f, j) = offset + c.mesh.corner[3 * i + j];
    }
    offset += static_cast<int>(c.UV.rows());
    r.charts.push_back(c.summary);
    r.charts.back().boundary_length = c.mesh.boundary_length;
    area += c.summary.area_3d;
    stretch += c.summary.area_3d * c.summary.stretch_l2_mean;
  }
  if (area > 0) r.stretch_l2_mean = stretch / area;
  r.F = given.F;
  for (int f = 0; f < nf; ++f)
    if (reversed[f]) {
      std::swap(r.F(f, 1), r.F(f, 2));
      std::swap(r.FUV(f, 1), r.FUV(f, 2));
    }
}

// ChartOptions::face_group: split groups gathered into one chart, the
// changed charts flattened again as the user's (split only where invalid).
void keep_groups(const MeshData& input, const detail::CleanMesh& clean, const ChartOptions& options,
                 std::vector<detail::FlatChart>& charts, AtlasCharts& r) {
  if (options.face_group.empty()) return;
  const auto t = std::chrono::steady_clock::now();
  r.split_groups = detail::keep_groups_whole(options.face_group, clean, charts, [&](std::vector<std::vector<int>> work) {
    return flatten_all(input, clean, std::move(work), options, true, r);
  });
  r.timings.flatten_ms += ms_since(t);
}

}  // namespace

AtlasCharts compute_charts(const MeshData& given, const ChartOptions& options) {
  detail::check_chart_options(options);
  detail::check_face_groups(options.face_group, static_cast<int>(given.F.rows()));
  const auto t0 = std::chrono::steady_clock::now();
  AtlasCharts r;
  MeshData welded_mesh;
  const detail::CleanMesh clean = prepare(given, options, welded_mesh, r);
  const MeshData& input = options.weld > 0 ? welded_mesh : given;
  auto t = std::chrono::steady_clock::now();
  std::vector<std::vector<int>> segments = detail::segment(input, clean, options);
  r.timings.segment_ms = ms_since(t);
  t = std::chrono::steady_clock::now();
  const bool own = !options.seams.empty();
  std::vector<detail::FlatChart> charts = flatten_all(input, clean, std::move(segments), options, own, r);
  r.timings.flatten_ms = ms_since(t);
  t = std::chrono::steady_clock::now();
  if ((!own && options.min_chart_faces > 0) || options.max_charts > 0)
    detail::merge_charts(input, clean, options, charts);
  r.timings.merge_ms = ms_since(t);
  keep_groups(input, clean, options, charts, r);
  store(given, clean.reversed, charts, r);
  r.timings.total_ms = ms_since(t0);
  return r;
}

AtlasCharts charts_from_ids(const MeshData& given, const std::vector<int>& face_chart, const ChartOptions& options) {
  detail::check_chart_options(options);
  detail::check_face_groups(options.face_group, static_cast<int>(given.F.rows()));
  if (face_chart.size() != static_cast<size_t>(given.F.rows()))
    throw_usage("the chart ids number " + std::to_string(face_chart.size()) + " for " +
                std::to_string(given.F.rows()) + " faces (one per face)");
  const auto t0 = std::chrono::steady_clock::now();
  AtlasCharts r;
  MeshData welded_mesh;
  const detail::CleanMesh clean = prepare(given, options, welded_mesh, r);
  const MeshData& input = options.weld > 0 ? welded_mesh : given;
  auto t = std::chrono::steady_clock::now();
  int pieces_split = 0;
  std::vector<std::vector<int>> pieces = detail::given_pieces(clean, face_chart, pieces_split);
  r.splits += pieces_split;
  r.split_reasons.not_disk += pieces_split;
  r.timings.segment_ms = ms_since(t);
  t = std::chrono::steady_clock::now();
  std::vector<detail::FlatChart> charts = flatten_all(input, clean, std::move(pieces), options, true, r);
  r.timings.flatten_ms = ms_since(t);
  keep_groups(input, clean, options, charts, r);
  store(given, clean.reversed, charts, r);
  r.timings.total_ms = ms_since(t0);
  return r;
}

}  // namespace intrinsic
