// intrinsic::atlas (atlas.h; issue 13): clean -> segment -> flatten and check
// every chart, splitting the invalid ones until each is valid (a single
// non-degenerate triangle always is) -> pack -> per-corner UVs. Every chart is
// flattened by the paper's natural conformal map (section 4.2) through the
// one Parameterizer (chart_flatten.cpp).
#include <chrono>
#include <deque>

#include "atlas/atlas_internal.h"
#include "intrinsic/error.h"

namespace intrinsic {

const char* chart_method_name(ChartMethod m) { return m == ChartMethod::Natural ? "natural" : "triangle"; }

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void check_options(const AtlasOptions& o) {
  if (!(o.max_normal_deviation_deg > 0 && o.max_normal_deviation_deg <= 180))
    throw_usage("the normal deviation must be in (0, 180] degrees");
  if (!(o.sharp_angle_deg > 0 && o.sharp_angle_deg <= 180)) throw_usage("the sharp angle must be in (0, 180] degrees");
  if (o.resolution < 1 || o.resolution > 1 << 20) throw_usage("the resolution must be between 1 and 1048576 texels");
  if (!(o.padding >= 0 && o.padding < o.resolution / 4.0))
    throw_usage("the padding must be at least 0 and less than a quarter of the resolution");
  if (o.min_chart_faces < 0) throw_usage("the minimum chart size must be at least 0 faces");
  if (!(o.max_stretch >= 1)) throw_usage("the stretch bound for merging must be at least 1");
  if (!(o.degenerate_ratio >= 0 && o.degenerate_ratio < 1)) throw_usage("the degenerate ratio must be in [0, 1)");
  if (!(o.weld >= 0 && o.weld < 1))
    throw_usage("the weld distance must be in [0, 1) (a fraction of the bounding box diagonal)");
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
    case detail::ChartStatus::Valid: break;
  }
}

// Flattens every chart, splitting invalid ones in two until all are valid.
std::vector<detail::FlatChart> flatten_all(const MeshData& input, const detail::CleanMesh& clean,
                                           std::vector<std::vector<int>> charts, double ratio, AtlasResult& r) {
  std::deque<std::vector<int>> work(std::make_move_iterator(charts.begin()), std::make_move_iterator(charts.end()));
  std::vector<detail::FlatChart> done;
  while (!work.empty()) {
    std::vector<int> faces = std::move(work.front());
    work.pop_front();
    detail::FlatChart chart;
    chart.mesh = detail::chart_mesh(input, clean, faces);
    chart.summary.component = clean.component[faces.front()];
    detail::ChartStatus status = detail::flatten_chart(chart, ratio);
    // A valid chart that would waste most of its square (sparse, or a long thin strip) is split for packing.
    if (status == detail::ChartStatus::Valid && faces.size() >= 64 && detail::square_fill(chart) < 0.15)
      status = detail::ChartStatus::Sparse;
    if (status == detail::ChartStatus::Valid) {
      done.push_back(std::move(chart));
      continue;
    }
    if (faces.size() == 1) throw_numerical("face " + std::to_string(faces[0]) + " could not be laid flat");
    count_split(status, r);
    for (std::vector<int>& half : detail::split_in_two(clean, faces)) work.push_back(std::move(half));
  }
  return done;
}

// Per-corner indices into one UV array; degenerate faces collapse onto a UV of one of their vertices.
void assemble(const MeshData& input, const std::vector<detail::FlatChart>& charts, AtlasResult& r) {
  const int nf = static_cast<int>(input.F.rows());
  long rows = 0;
  for (const detail::FlatChart& c : charts) rows += c.UV.rows();
  r.UV.resize(rows + 1, 2);
  r.FUV = MatrixX3i::Constant(nf, 3, -1);
  r.face_chart.assign(nf, -1);
  std::vector<int> vertex_uv(input.V.rows(), -1);
  int offset = 0;
  for (size_t k = 0; k < charts.size(); ++k) {
    const detail::FlatChart& c = charts[k];
    r.UV.middleRows(offset, c.UV.rows()) = c.UV;
    for (size_t i = 0; i < c.mesh.faces.size(); ++i) {
      const int f = c.mesh.faces[i];
      r.face_chart[f] = static_cast<int>(k);
      for (int j = 0; j < 3; ++j) {
        r.FUV(f, j) = offset + c.mesh.corner[3 * i + j];
        if (vertex_uv[input.F(f, j)] < 0) vertex_uv[input.F(f, j)] = r.FUV(f, j);
      }
    }
    offset += static_cast<int>(c.UV.rows());
  }
  r.UV.row(offset) << 0, 0;  // for degenerate faces none of whose vertices is in a chart
  for (int f = 0; f < nf; ++f)
    if (r.face_chart[f] < 0) {
      int uv = offset;
      for (int j = 2; j >= 0; --j)
        if (vertex_uv[input.F(f, j)] >= 0) uv = vertex_uv[input.F(f, j)];
      r.FUV.row(f).setConstant(uv);
    }
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
  const detail::CleanMesh clean = detail::clean_mesh(input, options);
  r.cleaning = clean.cleaning;
  r.cleaning.welded_vertices = welded;
  r.components = clean.components;
  r.timings.clean_ms = ms_since(t0);
  auto t = std::chrono::steady_clock::now();
  std::vector<std::vector<int>> segments = detail::segment(input, clean, options);
  r.timings.segment_ms = ms_since(t);
  t = std::chrono::steady_clock::now();
  std::vector<detail::FlatChart> charts = flatten_all(input, clean, std::move(segments), options.degenerate_ratio, r);
  r.timings.flatten_ms = ms_since(t);
  t = std::chrono::steady_clock::now();
  if (options.min_chart_faces > 0) detail::merge_small_charts(input, clean, options, charts);
  r.timings.merge_ms = ms_since(t);
  t = std::chrono::steady_clock::now();
  r.utilization = detail::pack_charts(charts, options, r.overlapping);
  assemble(input, charts, r);
  r.face_reversed = clean.reversed;
  for (const detail::FlatChart& c : charts) {
    r.charts.push_back(c.summary);
    r.flipped += c.summary.flipped;
  }
  r.timings.pack_ms = ms_since(t);
  r.timings.total_ms = ms_since(t0);
  return r;
}

}  // namespace intrinsic
