// One chart per connected component (paper section 1.3: closed or multi-piece
// surfaces are handled as an atlas of disk-like charts), each parameterized on
// its own, then laid out by shelf packing of bounding boxes.
#include "intrinsic/charts.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

#include "intrinsic/error.h"

namespace intrinsic {
namespace {

// A component as a mesh of its own, with compact vertex indices.
struct Chart {
  Mesh mesh;
  std::vector<int> global;  // local vertex -> mesh vertex
};

Chart extract_chart(const Mesh& mesh, int component, std::vector<int>& local_of) {
  Chart c;
  MeshData d;
  std::vector<int> faces;
  for (int f = 0; f < mesh.F.rows(); ++f)
    if (mesh.topology.face_component[f] == component) faces.push_back(f);
  d.F.resize(static_cast<int>(faces.size()), 3);
  for (size_t k = 0; k < faces.size(); ++k)
    for (int i = 0; i < 3; ++i) {
      const int v = mesh.F(faces[k], i);
      if (local_of[v] < 0) {
        local_of[v] = static_cast<int>(c.global.size());
        c.global.push_back(v);
      }
      d.F(static_cast<int>(k), i) = local_of[v];
    }
  d.V.resize(static_cast<int>(c.global.size()), 3);
  for (size_t k = 0; k < c.global.size(); ++k) d.V.row(static_cast<int>(k)) = mesh.V.row(c.global[k]);
  for (int v : c.global) local_of[v] = -1;  // ready for the next component
  c.mesh = make_mesh(d);  // already valid and consistently oriented: this only builds the adjacency
  c.mesh.path = mesh.path;
  return c;
}

std::vector<FixedVertex> to_local(const std::vector<FixedVertex>& given, const std::vector<int>& local_of_all) {
  std::vector<FixedVertex> out;
  for (const FixedVertex& fv : given)
    if (fv.vertex >= 0 && fv.vertex < static_cast<int>(local_of_all.size()) && local_of_all[fv.vertex] >= 0)
      out.push_back({local_of_all[fv.vertex], fv.uv});
  return out;
}

std::string boundary_name(BoundaryShape s) {
  switch (s) {
    case BoundaryShape::Circle: return "circle";
    case BoundaryShape::Square: return "square";
    case BoundaryShape::Given: return "given";
    case BoundaryShape::Natural: return "natural";
  }
  return "?";
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

ChartsResult parameterize_charts(const Mesh& mesh, const ParamOptions& o) {
  const Topology& t = mesh.topology;
  for (int c = 0; c < t.num_components; ++c)
    if (t.component_loops[c].empty())
      throw_input((mesh.path.empty() ? "" : mesh.path + ": ") + "component " + std::to_string(c) + " of " +
                  std::to_string(t.num_components) + " (" + std::to_string(t.component_faces[c]) +
                  " faces) is closed (no boundary): cut it open to a disk, or keep only the largest component");
  for (const std::vector<FixedVertex>* list : {&o.given, &o.pins})
    for (const FixedVertex& fv : *list)
      if (fv.vertex < 0 || fv.vertex >= mesh.V.rows())
        throw_input((list == &o.pins ? "pin on vertex " : "boundary position for vertex ") + std::to_string(fv.vertex) +
                    ", which does not exist (the mesh has " + std::to_string(mesh.V.rows()) + " vertices)");

  ChartsResult result;
  result.UV = MatrixX2d::Zero(mesh.V.rows(), 2);
  std::vector<int> local_of(mesh.V.rows(), -1);
  std::set<std::string> solvers;
  struct Placed {
    std::vector<int> global;
    MatrixX2d UV;
    Eigen::Vector2d lo, hi;
  };
  std::vector<Placed> placed(t.num_components);
  bool any_fixed = false;

  for (int c = 0; c < t.num_components; ++c) {
    const Chart chart = extract_chart(mesh, c, local_of);
    std::vector<int> local_of_all(mesh.V.rows(), -1);
    for (size_t k = 0; k < chart.global.size(); ++k) local_of_all[chart.global[k]] = static_cast<int>(k);
    const Topology& ct = chart.mesh.topology;

    ParamOptions co = o;
    co.given = to_local(o.given, local_of_all);
    co.pins = to_local(o.pins, local_of_all);
    const size_t outer_size = ct.boundary_loops[ct.component_loops[0][0]].size();
    bool usable = true;
    if (o.boundary == BoundaryShape::Given) usable = !co.given.empty();
    if (o.boundary == BoundaryShape::Square) usable = outer_size >= 4;
    if (!usable) {
      co.boundary = BoundaryShape::Natural;
      co.weights = WeightOptions{};  // the natural map is conformal
    }
    if (co.boundary == BoundaryShape::Natural && co.pins.size() == 1)
      throw_usage("chart " + std::to_string(c) + " has one pin (vertex " + std::to_string(chart.global[co.pins[0].vertex]) +
                  "); pin at least two vertices of a chart, or none");
    const bool fixed_in_place = co.boundary == BoundaryShape::Given || !co.pins.empty();
    if (!fixed_in_place) co.scale = ScaleMode::Surface;

    ParamResult r;
    try {
      r = parameterize(chart.mesh, co);
    } catch (const Error& e) {
      throw Error(e.kind(), "chart " + std::to_string(c) + " (component of " + std::to_string(t.component_faces[c]) +
                                " faces): " + e.what());
    }
    // A common scale for every movable chart: parameter area = 3D area.
    if (!fixed_in_place) scale_to_surface_area(r.UV, chart.mesh);
    any_fixed = any_fixed || fixed_in_place;

    const DistortionSummary d = summarize_distortion(chart.mesh.V, chart.mesh.F, r.UV);
    ChartSummary s;
    s.component = c;
    s.vertices = static_cast<int>(chart.global.size());
    s.faces = static_cast<int>(chart.mesh.F.rows());
    s.boundary = boundary_name(co.boundary);
    s.holes = r.holes;
    s.packed = !fixed_in_place;
    s.flipped_triangles = d.flipped_triangles;
    s.angle_distortion_mean = d.angle_distortion.mean;
    result.charts.push_back(s);
    solvers.insert(r.solver);
    result.residual = std::max(result.residual, r.residual);
    result.timings.assemble_ms += r.timings.assemble_ms;
    result.timings.factor_ms += r.timings.factor_ms;
    result.timings.solve_ms += r.timings.solve_ms;

    Placed& p = placed[c];
    p.global = chart.global;
    p.UV = r.UV;
    p.lo = r.UV.colwise().minCoeff().transpose();
    p.hi = r.UV.colwise().maxCoeff().transpose();
  }

  // Shelf packing of the movable charts: tallest first, left to right, a new
  // shelf when the row would exceed about the square root of the total area.
  Eigen::Vector2d origin(0, 0);
  if (any_fixed) {
    Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
    for (int c = 0; c < t.num_components; ++c)
      if (!result.charts[c].packed) { lo = lo.cwiseMin(placed[c].lo); hi = hi.cwiseMax(placed[c].hi); }
    origin = Eigen::Vector2d(hi.x(), lo.y());
  }
  std::vector<int> order;
  double area = 0, widest = 0;
  for (int c = 0; c < t.num_components; ++c)
    if (result.charts[c].packed) {
      order.push_back(c);
      const Eigen::Vector2d size = placed[c].hi - placed[c].lo;
      area += size.x() * size.y();
      widest = std::max(widest, size.x());
    }
  const double gap = 0.02 * std::sqrt(area);
  if (any_fixed) origin.x() += gap;
  const double row_width = std::max(widest, std::sqrt(area) * 1.2);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return placed[a].hi.y() - placed[a].lo.y() > placed[b].hi.y() - placed[b].lo.y();
  });
  double x = 0, y = 0, shelf = 0;
  for (int c : order) {
    const Eigen::Vector2d size = placed[c].hi - placed[c].lo;
    if (x > 0 && x + size.x() > row_width) {
      y += shelf + gap;
      x = 0;
      shelf = 0;
    }
    const Eigen::Vector2d shift = origin + Eigen::Vector2d(x, y) - placed[c].lo;
    placed[c].UV.rowwise() += shift.transpose();
    x += size.x() + gap;
    shelf = std::max(shelf, size.y());
  }
  for (int c = 0; c < t.num_components; ++c)
    for (size_t k = 0; k < placed[c].global.size(); ++k)
      result.UV.row(placed[c].global[k]) = placed[c].UV.row(static_cast<int>(k));

  if (any_fixed) {
    result.scale = "given";
  } else if (o.scale == ScaleMode::Unit) {
    fit_unit_square(result.UV, t.is_used);
    result.scale = "unit";
  } else {
    result.scale = "surface";
  }
  for (ChartSummary& s : result.charts) {
    const std::vector<int>& g = placed[s.component].global;
    s.box_min = result.UV.row(g[0]).transpose();
    s.box_max = s.box_min;
    for (int v : g) {
      s.box_min = s.box_min.cwiseMin(result.UV.row(v).transpose());
      s.box_max = s.box_max.cwiseMax(result.UV.row(v).transpose());
    }
  }
  for (const std::string& name : solvers) result.solver += (result.solver.empty() ? "" : ", ") + name;
  return result;
}

}  // namespace intrinsic
