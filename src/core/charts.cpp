// One chart per connected component (paper section 1.3: closed or multi-piece
// surfaces are handled as an atlas of disk-like charts), each parameterized
// by the one Parameterizer, then laid out by shelf packing of bounding boxes.
#include "intrinsic/charts.h"

#include <algorithm>
#include <cmath>

#include "core/shelf_packing.h"
#include "intrinsic/error.h"

namespace intrinsic {
namespace {

// A component as a mesh of its own, with compact vertex indices.
struct Chart {
  Mesh mesh;
  std::vector<int> global;  // local vertex -> mesh vertex
  MatrixX2d UV;             // local, once solved and placed
  Eigen::Vector2d lo, hi;   // bounding box of UV
};

// Every component's faces and vertices in one pass over the faces. A vertex
// belongs to one component, so one array `local` (vertex -> index in its
// chart, -1 if unused) serves them all.
std::vector<Chart> split_components(const Mesh& mesh, std::vector<int>& local) {
  const Topology& t = mesh.topology;
  std::vector<MeshData> data(t.num_components);
  std::vector<Chart> charts(t.num_components);
  for (int c = 0; c < t.num_components; ++c) data[c].F.resize(t.component_faces[c], 3);
  local.assign(mesh.V.rows(), -1);
  std::vector<int> filled(t.num_components, 0);
  for (int f = 0; f < mesh.F.rows(); ++f) {
    const int c = t.face_component[f];
    for (int i = 0; i < 3; ++i) {
      const int v = mesh.F(f, i);
      if (local[v] < 0) {
        local[v] = static_cast<int>(charts[c].global.size());
        charts[c].global.push_back(v);
      }
      data[c].F(filled[c], i) = local[v];
    }
    ++filled[c];
  }
  for (int c = 0; c < t.num_components; ++c) {
    data[c].V.resize(static_cast<int>(charts[c].global.size()), 3);
    for (size_t k = 0; k < charts[c].global.size(); ++k) data[c].V.row(static_cast<int>(k)) = mesh.V.row(charts[c].global[k]);
    charts[c].mesh = make_mesh(data[c]);  // already valid and oriented: this only builds the adjacency
    charts[c].mesh.path = mesh.path;
  }
  return charts;
}

// The entries of `given` on this chart, in local indices.
std::vector<FixedVertex> to_local(const std::vector<FixedVertex>& given, const std::vector<int>& local,
                                  const Chart& chart) {
  std::vector<FixedVertex> out;
  for (const FixedVertex& fv : given) {
    const int k = fv.vertex >= 0 && fv.vertex < static_cast<int>(local.size()) ? local[fv.vertex] : -1;
    if (k >= 0 && k < static_cast<int>(chart.global.size()) && chart.global[k] == fv.vertex) out.push_back({k, fv.uv});
  }
  return out;
}

// The chart's options: the caller's, or the natural map when its boundary
// cannot be used (named in summary.fallback).
ParamOptions chart_options(const ParamOptions& o, const std::vector<int>& local, const Chart& chart,
                           ChartSummary& summary) {
  ParamOptions co = o;
  co.given = to_local(o.given, local, chart);
  co.pins = to_local(o.pins, local, chart);
  const Topology& ct = chart.mesh.topology;
  if (o.boundary == BoundaryShape::Given && co.given.empty()) summary.fallback = ChartFallback::NoGivenPositions;
  if (o.boundary == BoundaryShape::Square && ct.boundary_loops[ct.component_loops[0][0]].size() < 4)
    summary.fallback = ChartFallback::LoopTooShort;
  if (summary.fallback != ChartFallback::None) {
    co.boundary = BoundaryShape::Natural;
    co.weights = WeightOptions{};  // the natural map is conformal
  }
  if (co.boundary == BoundaryShape::Natural && co.pins.size() == 1)
    throw_usage("chart " + std::to_string(summary.component) + " has one pin (vertex " +
                std::to_string(chart.global[co.pins[0].vertex]) + "); pin at least two vertices of a chart, or none");
  summary.packed = !(co.boundary == BoundaryShape::Given || !co.pins.empty());
  if (summary.packed) co.scale = ScaleMode::Surface;
  summary.boundary = co.boundary;
  summary.weights = co.weights;
  return co;
}

// Solves one chart; a movable chart gets parameter area = 3D area.
ChartSummary solve_chart(const ParamOptions& o, const Mesh& mesh, const std::vector<int>& local, int c, Chart& chart,
                         ParamResult& total) {
  ChartSummary s;
  s.component = c;
  const ParamOptions co = chart_options(o, local, chart, s);
  ParamResult r;
  try {
    r = parameterize(chart.mesh, co);
  } catch (const Error& e) {
    throw Error(e.kind(), "chart " + std::to_string(c) + " (component of " +
                              std::to_string(mesh.topology.component_faces[c]) + " faces): " + e.what());
  }
  if (s.packed) scale_to_surface_area(r.UV, chart.mesh);
  const DistortionSummary d = summarize_distortion(chart.mesh.V, chart.mesh.F, r.UV);
  s.vertices = static_cast<int>(chart.global.size());
  s.faces = static_cast<int>(chart.mesh.F.rows());
  s.holes = r.holes;
  s.flipped_triangles = d.flipped_triangles;
  s.angle_distortion_mean = d.angle_distortion.mean;
  s.residual = r.residual;
  s.free_vertices = r.free_vertices;
  s.fixed_vertices = r.fixed_vertices;
  for (SolverKind k : r.solvers)
    if (std::find(total.solvers.begin(), total.solvers.end(), k) == total.solvers.end()) total.solvers.push_back(k);
  total.residual = std::max(total.residual, r.residual);
  total.free_vertices += r.free_vertices;
  total.fixed_vertices += r.fixed_vertices;
  total.filled_holes += r.filled_holes;
  total.factorizations += r.factorizations;
  total.iterations = std::max(total.iterations, r.iterations);
  total.timings.assemble_ms += r.timings.assemble_ms;
  total.timings.factor_ms += r.timings.factor_ms;
  total.timings.solve_ms += r.timings.solve_ms;
  chart.UV = r.UV;
  chart.lo = r.UV.colwise().minCoeff().transpose();
  chart.hi = r.UV.colwise().maxCoeff().transpose();
  return s;
}

void check_charts_input(const Mesh& mesh, const ParamOptions& o) {
  const Topology& t = mesh.topology;
  for (int c = 0; c < t.num_components; ++c)
    if (t.component_loops[c].empty())
      throw_input((mesh.path.empty() ? "" : mesh.path + ": ") + "component " + std::to_string(c) + " of " +
                  std::to_string(t.num_components) + " (" + std::to_string(t.component_faces[c]) +
                  " faces) is closed (no boundary): use `intrinsic atlas` (library: atlas.h), or keep only the largest component");
  for (const std::vector<FixedVertex>* list : {&o.given, &o.pins})
    for (const FixedVertex& fv : *list)
      if (fv.vertex < 0 || fv.vertex >= mesh.V.rows())
        throw_input((list == &o.pins ? "pin on vertex " : "boundary position for vertex ") + std::to_string(fv.vertex) +
                    ", which does not exist (the mesh has " + std::to_string(mesh.V.rows()) + " vertices)");
}

// Movable charts shelf-packed to the right of the fixed ones, with a gap of
// 2% of the square root of their total box area.
void pack_movable(const std::vector<ChartSummary>& summaries, std::vector<Chart>& charts) {
  std::vector<int> movable;
  std::vector<Eigen::Vector2d> sizes;
  Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  double area = 0;
  for (size_t c = 0; c < charts.size(); ++c) {
    if (!summaries[c].packed) {
      lo = lo.cwiseMin(charts[c].lo);
      hi = hi.cwiseMax(charts[c].hi);
      continue;
    }
    movable.push_back(static_cast<int>(c));
    sizes.push_back(charts[c].hi - charts[c].lo);
    area += sizes.back().x() * sizes.back().y();
  }
  const bool any_fixed = movable.size() < charts.size();
  const double gap = 0.02 * std::sqrt(area);
  const Eigen::Vector2d origin = any_fixed ? Eigen::Vector2d(hi.x() + gap, lo.y()) : Eigen::Vector2d(0, 0);
  const std::vector<Eigen::Vector2d> corner = detail::pack_shelves(sizes, origin, gap);
  for (size_t k = 0; k < movable.size(); ++k) {
    Chart& chart = charts[movable[k]];
    const Eigen::Vector2d shift = corner[k] - chart.lo;
    chart.UV.rowwise() += shift.transpose();
  }
}

}  // namespace

int largest_component(const Mesh& mesh) {
  const std::vector<int>& faces = mesh.topology.component_faces;
  return static_cast<int>(std::max_element(faces.begin(), faces.end()) - faces.begin());
}

MeshData component_data(const Mesh& mesh, int component) {
  MeshData d;
  d.V = mesh.V;
  d.path = mesh.path;
  d.F.resize(mesh.topology.component_faces.at(component), 3);
  int m = 0;
  for (int f = 0; f < mesh.F.rows(); ++f)
    if (mesh.topology.face_component[f] == component) {
      d.F.row(m++) = mesh.F.row(f);
      if (!mesh.face_line.empty()) d.face_line.push_back(mesh.face_line[f]);
    }
  return d;
}

ParamResult parameterize_charts(const Mesh& mesh, const ParamOptions& o) {
  check_charts_input(mesh, o);
  std::vector<int> local;
  std::vector<Chart> charts = split_components(mesh, local);
  ParamResult result;
  result.weights = o.weights;
  result.boundary = o.boundary;
  result.spacing = o.spacing;
  result.holes = HolesApplied::None;
  for (size_t c = 0; c < charts.size(); ++c)
    result.charts.push_back(solve_chart(o, mesh, local, static_cast<int>(c), charts[c], result));
  pack_movable(result.charts, charts);
  result.UV = MatrixX2d::Zero(mesh.V.rows(), 2);
  for (const Chart& chart : charts)
    for (size_t k = 0; k < chart.global.size(); ++k) result.UV.row(chart.global[k]) = chart.UV.row(static_cast<int>(k));
  const bool any_fixed = std::any_of(result.charts.begin(), result.charts.end(), [](const ChartSummary& s) { return !s.packed; });
  result.placement = any_fixed ? Placement::Given : o.scale == ScaleMode::Unit ? Placement::Unit : Placement::Surface;
  if (result.placement == Placement::Unit) fit_unit_square(result.UV, mesh.topology.is_used);
  for (ChartSummary& s : result.charts) {
    const std::vector<int>& g = charts[s.component].global;
    s.box_min = s.box_max = result.UV.row(g[0]).transpose();
    for (int v : g) {
      s.box_min = s.box_min.cwiseMin(result.UV.row(v).transpose());
      s.box_max = s.box_max.cwiseMax(result.UV.row(v).transpose());
    }
    if (result.holes == HolesApplied::None) result.holes = s.holes;  // the first chart with holes
  }
  return result;
}

}  // namespace intrinsic
