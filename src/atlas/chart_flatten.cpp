// One chart through the one pipeline: make_mesh on the chart's own data, then
// parameterize() with BoundaryShape::Natural (the natural conformal map,
// paper section 4.2, eq. 7; docs/maths.md §3) or the map ChartMapOptions
// chooses (a fixed circle or square boundary with any weights, optionally
// optimal lambda or boundary optimization, paper section 5), scaled so its
// UV area is its 3D area (docs/maths.md §2.4). Then the checks that make the chart safe to
// ship (every chart of an atlas must be valid): a disk (one boundary loop, Euler
// characteristic 1), every triangle positively oriented in the input's corner
// order, every interior vertex wound once (angle sum below 3 pi), and a
// boundary that does not cross itself. A locally injective map of a disk
// with a simple boundary is injective, so the chart does not overlap itself.
#include <algorithm>
#include <cmath>
#include <tuple>

#include "atlas/atlas_internal.h"
#include "intrinsic/error.h"
#include "intrinsic/metrics.h"
#include "intrinsic/boundary_optimization.h"
#include "intrinsic/optimal_lambda.h"
#include "intrinsic/parameterize.h"
#include "optimize/isometric_refinement.h"

namespace intrinsic::detail {
namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// A single triangle in its own plane, counter-clockwise in the order of its
// face: its natural map up to a similarity.
MatrixX2d lay_triangle(const Mesh& mesh) {
  const int a = mesh.F(0, 0), b = mesh.F(0, 1), c = mesh.F(0, 2);
  const Eigen::Vector3d e1 = mesh.V.row(b) - mesh.V.row(a), e2 = mesh.V.row(c) - mesh.V.row(a);
  const double l = e1.norm();
  MatrixX2d UV(3, 2);
  UV.row(a) << 0, 0;
  UV.row(b) << l, 0;
  UV.row(c) << e2.dot(e1) / l, e1.cross(e2).norm() / l;
  return UV;
}

bool segments_cross(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r,
                    const Eigen::Vector2d& s) {
  const double d1 = cross2(q - p, r - p), d2 = cross2(q - p, s - p);
  const double d3 = cross2(s - r, p - r), d4 = cross2(s - r, q - r);
  if (d1 * d2 > 0 || d3 * d4 > 0) return false;
  // Touching or collinear: count it when the boxes meet (conservative).
  return std::max(p.x(), q.x()) >= std::min(r.x(), s.x()) && std::max(r.x(), s.x()) >= std::min(p.x(), q.x()) &&
         std::max(p.y(), q.y()) >= std::min(r.y(), s.y()) && std::max(r.y(), s.y()) >= std::min(p.y(), q.y());
}

// Boundary segments that meet without being neighbours on one loop, over
// every loop of the chart (its outer boundary and its holes), found through
// a uniform grid.
bool boundary_crosses(const std::vector<std::vector<int>>& loops, const MatrixX2d& UV) {
  struct Segment {
    int a, b;      // local vertices
    int loop, at;  // which loop, and where on it
  };
  std::vector<Segment> seg;
  for (size_t l = 0; l < loops.size(); ++l)
    for (size_t i = 0; i < loops[l].size(); ++i)
      seg.push_back({loops[l][i], loops[l][(i + 1) % loops[l].size()], static_cast<int>(l), static_cast<int>(i)});
  const int n = static_cast<int>(seg.size());
  if (n < 4) return false;
  Eigen::Vector2d lo = UV.row(seg[0].a).transpose(), hi = lo;
  for (const Segment& s : seg) lo = lo.cwiseMin(UV.row(s.a).transpose()), hi = hi.cwiseMax(UV.row(s.a).transpose());
  const int g = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(n))));
  const Eigen::Vector2d cell = ((hi - lo) / g).cwiseMax(Eigen::Vector2d::Constant(1e-300));
  std::vector<std::vector<int>> bins(g * g);
  auto bin = [&](double x, double lo_x, double size) { return std::clamp(static_cast<int>((x - lo_x) / size), 0, g - 1); };
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d a = UV.row(seg[i].a), b = UV.row(seg[i].b);
    for (int x = bin(std::min(a.x(), b.x()), lo.x(), cell.x()); x <= bin(std::max(a.x(), b.x()), lo.x(), cell.x()); ++x)
      for (int y = bin(std::min(a.y(), b.y()), lo.y(), cell.y()); y <= bin(std::max(a.y(), b.y()), lo.y(), cell.y()); ++y)
        bins[x * g + y].push_back(i);
  }
  // Neighbours on one loop share a vertex: not a crossing.
  auto adjacent = [&](const Segment& s, const Segment& t) {
    if (s.loop != t.loop) return false;
    const int m = static_cast<int>(loops[s.loop].size());
    const int d = std::abs(s.at - t.at);
    return d == 1 || d == m - 1;
  };
  for (const std::vector<int>& b : bins)
    for (size_t s = 0; s < b.size(); ++s)
      for (size_t t = s + 1; t < b.size(); ++t) {
        const Segment &p = seg[b[s]], &q = seg[b[t]];
        if (adjacent(p, q)) continue;
        if (segments_cross(UV.row(p.a), UV.row(p.b), UV.row(q.a), UV.row(q.b))) return true;
      }
  return false;
}

// Flipped or collapsed triangles (input corner order), interior vertices
// wound more than once, boundary vertices wound a full turn.
bool folds(const Mesh& mesh, const MatrixX2d& UV, double degenerate_ratio, int& flipped) {
  std::vector<double> angle_sum(mesh.V.rows(), 0.0);
  flipped = 0;
  for (int f = 0; f < mesh.F.rows(); ++f) {
    Eigen::Vector2d p[3];
    for (int c = 0; c < 3; ++c) p[c] = UV.row(mesh.F(f, c));
    const double twice = cross2(p[1] - p[0], p[2] - p[0]);
    const double longest = std::max({(p[1] - p[0]).squaredNorm(), (p[2] - p[1]).squaredNorm(), (p[0] - p[2]).squaredNorm()});
    if (!(twice > degenerate_ratio * longest)) ++flipped;
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector2d a = p[(c + 1) % 3] - p[c], b = p[(c + 2) % 3] - p[c];
      angle_sum[mesh.F(f, c)] += std::atan2(std::abs(cross2(a, b)), a.dot(b));
    }
  }
  if (flipped > 0) return true;
  // An interior vertex wound twice; a boundary vertex whose faces cover a
  // full turn or more (its two boundary edges fold onto each other: the
  // chart touches itself there, which the crossing test of non-adjacent
  // boundary segments does not see).
  for (int v = 0; v < mesh.V.rows(); ++v) {
    if (!mesh.topology.is_boundary[v] && angle_sum[v] > 3 * M_PI) return true;
    if (mesh.topology.is_boundary[v] && angle_sum[v] > 2 * M_PI * (1 - 1e-9)) return true;
  }
  return false;
}

// Every face's normal within 60 degrees of the chart's area-weighted mean
// normal: the chart is a height field over its mean plane, where the natural
// map of a chart with holes reproduces the layout (a flat one exactly).
bool over_its_plane(const MeshData& chart) {
  const MatrixX3d& V = chart.V;
  const MatrixX3i& F = chart.F;
  std::vector<Eigen::Vector3d> n(F.rows());
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int f = 0; f < F.rows(); ++f) {
    n[f] = (V.row(F(f, 1)) - V.row(F(f, 0))).cross(V.row(F(f, 2)) - V.row(F(f, 0)));
    sum += n[f];
  }
  if (!(sum.norm() > 0)) return false;
  const Eigen::Vector3d mean = sum.normalized();
  for (const Eigen::Vector3d& nf : n)
    if (nf.norm() > 0 && nf.dot(mean) < 0.5 * nf.norm()) return false;
  return true;
}

ChartMethod method_of(const ChartMapOptions& map) {
  if (map.boundary == BoundaryShape::Natural) return ChartMethod::Natural;
  if (map.optimizer == ChartOptimizer::OptimalLambda) return ChartMethod::OptimalLambda;
  if (map.optimizer == ChartOptimizer::OptimizeBoundary) return ChartMethod::OptimizedBoundary;
  return ChartMethod::FixedBoundary;
}

// The chart's map through the library's own calls, as `param` makes it.
MatrixX2d chart_map(const Mesh& mesh, const ChartMapOptions& map) {
  ParamOptions o;
  o.weights = map.weights;
  o.boundary = map.boundary;
  o.scale = ScaleMode::Surface;
  if (map.boundary == BoundaryShape::Natural) o.weights = WeightOptions();
  switch (map.optimizer) {
    case ChartOptimizer::OptimalLambda: {
      OptimalLambdaOptions l;
      l.base = o;
      l.energy = map.lambda_energy;
      return optimal_lambda(mesh, l).map.UV;
    }
    case ChartOptimizer::OptimizeBoundary: {
      BoundaryOptimizationOptions b;
      b.base = o;
      b.energy = map.boundary_energy;
      return optimize_boundary(mesh, b).map.UV;
    }
    case ChartOptimizer::None: break;
  }
  return parameterize(mesh, o).UV;
}

ChartStatus solve(FlatChart& chart, Mesh& mesh, const ChartMapOptions& map) {
  try {
    chart.UV = chart_map(mesh, map);
  } catch (const Error&) {
    return ChartStatus::SolveFailed;
  }
  if (!chart.UV.allFinite()) return ChartStatus::SolveFailed;
  const double a3 = surface_area(mesh.V, mesh.F), a2 = parameter_area(mesh.F, chart.UV);
  if (!(a2 > 0)) return ChartStatus::Flipped;
  chart.UV *= std::sqrt(a3 / a2);
  return ChartStatus::Valid;
}

// The natural map refined toward an isometry (isometric_refinement.h),
// kept only when its boundary stays simple (the refinement keeps every
// triangle positively oriented, not the boundary from touching itself).
void refine(const Mesh& mesh, const ChartMapOptions& map, double degenerate_ratio, FlatChart& chart) {
  IsometricRefinementOptions o;
  o.iterations = map.isometric_iterations;
  o.degenerate_ratio = degenerate_ratio;
  MatrixX2d UV = chart.UV;
  if (refine_isometric(mesh, UV, o).iterations == 0) return;
  const double a3 = surface_area(mesh.V, mesh.F), a2 = parameter_area(mesh.F, UV);
  if (!(a2 > 0)) return;
  UV *= std::sqrt(a3 / a2);
  int flipped = 0;
  if (folds(mesh, UV, degenerate_ratio, flipped) || boundary_crosses(mesh.topology.boundary_loops, UV)) return;
  chart.UV = std::move(UV);
  chart.summary.refined = true;
}

// The chart's figures at its own scale (UV area = 3D area, as in the atlas):
// the area-weighted mean and root mean square of Sander's per-face L2, and
// per face the stretch max(s1, 1/s2) with its 95th percentile and maximum
// (docs/maths.md §9.7).
// Local vertices at one 3D point (a pinch, where two fans of the chart meet)
// that the map put a rounding apart get one UV: the packer's transforms then
// keep them on one point, instead of rounding one corner into the other's
// triangle (2CylinderEngine). Farther apart than 1e-9 of the chart's size,
// they are left for the exact overlap test. Whether the chart has a pinch.
bool join_pinched_corners(const MatrixX3d& V, MatrixX2d& UV) {
  if (V.rows() != UV.rows() || UV.rows() == 0) return false;
  std::vector<int> order(static_cast<size_t>(V.rows()));
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return std::make_tuple(V(a, 0), V(a, 1), V(a, 2)) < std::make_tuple(V(b, 0), V(b, 1), V(b, 2));
  });
  const double size = (UV.colwise().maxCoeff() - UV.colwise().minCoeff()).norm();
  bool pinched = false;
  for (size_t i = 1; i < order.size(); ++i) {
    const int a = order[i - 1], b = order[i];
    if (V.row(a) != V.row(b)) continue;
    pinched = true;
    if ((UV.row(a) - UV.row(b)).norm() <= 1e-9 * size) UV.row(b) = UV.row(a);
  }
  return pinched;
}

void summarize_stretch(const Mesh& mesh, FlatChart& chart) {
  const FaceDistortion d = face_distortion(mesh.V, mesh.F, chart.UV);
  AtlasChart& s = chart.summary;
  const int nf = static_cast<int>(mesh.F.rows());
  chart.face_stretch.assign(nf, INFINITY);
  chart.face_area.assign(d.area_3d.data(), d.area_3d.data() + nf);
  double area = 0, angle = 0, mean = 0, square = 0;
  for (int f = 0; f < nf; ++f) {
    const double a = d.area_3d[f], l2 = d.stretch_l2[f], linf = d.stretch_linf[f];
    if (!std::isfinite(l2)) continue;
    area += a, angle += a * d.angle[f], mean += a * l2, square += a * l2 * l2;
    // s1 from L2^2 = (1/s1^2 + 1/s2^2) / 2 and Linf = 1/s2.
    const double inv_s1_sq = std::max(2 * l2 * l2 - linf * linf, 1e-300);
    chart.face_stretch[f] = std::max({1.0, 1 / std::sqrt(inv_s1_sq), linf});
  }
  if (area > 0) s.angle_distortion_mean = angle / area, s.stretch_l2_mean = mean / area,
                s.stretch_l2_rms = std::sqrt(square / area);
  s.face_stretch_max = *std::max_element(chart.face_stretch.begin(), chart.face_stretch.end());
  s.face_stretch_p95 = weighted_quantile(chart.face_stretch, chart.face_area, 0.95);
}

}  // namespace

ChartStatus flatten_chart(FlatChart& chart, const ChartMapOptions& map, double degenerate_ratio) {
  // Euler characteristic of the chart's own mesh before building it: most
  // charts split on a large mesh are not disks, and this needs no make_mesh.
  // A chart with holes (genus 0, several boundary loops) is kept whole when
  // the natural map frees every loop and the chart lies over its mean plane
  // (a flat plate with drilled holes is one chart, not dozens of pieces).
  const long k = chart.mesh.data.F.rows(), local_edges = (3 * k + chart.mesh.open_edges) / 2;
  const long euler = chart.mesh.data.V.rows() - local_edges + k;
  const bool holes_allowed = map.boundary == BoundaryShape::Natural && euler <= 0 && over_its_plane(chart.mesh.data);
  if (euler != 1 && !holes_allowed) return ChartStatus::NotDisk;
  ValidateOptions vo;
  vo.degenerate_ratio = degenerate_ratio;
  vo.allow_closed = true;
  Mesh mesh;
  try {
    mesh = make_mesh(chart.mesh.data, vo);
  } catch (const Error&) {
    return ChartStatus::Refused;
  }
  const Topology& t = mesh.topology;
  long boundary_edges = 0;
  for (const std::vector<int>& loop : t.boundary_loops) boundary_edges += static_cast<long>(loop.size());
  const long nf = mesh.F.rows(), edges = (3 * nf + boundary_edges) / 2;
  const long loops = static_cast<long>(t.boundary_loops.size());
  // Genus 0 with at least one loop: a disk, or (when allowed) a disk with holes.
  if (loops == 0 || mesh.V.rows() - edges + nf != 2 - loops || (loops > 1 && !holes_allowed))
    return ChartStatus::NotDisk;
  // A cut edge (a user's seam, a non-manifold or inconsistent edge) whose two
  // ends are glued around it would be an interior edge of the chart's mesh:
  // the cut would not be in the UVs. Split until it lies on the boundary.
  if (boundary_edges != chart.mesh.open_edges) return ChartStatus::NotDisk;
  // Glued edges are consistently oriented, so nothing is reoriented; if it
  // were, the input's corner order would no longer match the map.
  if (mesh.validation.reoriented_faces != 0) return ChartStatus::Refused;
  AtlasChart& s = chart.summary;
  s.faces = static_cast<int>(nf);
  s.vertices = static_cast<int>(mesh.V.rows());
  s.area_3d = surface_area(mesh.V, mesh.F);
  if (nf == 1) {
    s.method = ChartMethod::Triangle;
    chart.UV = lay_triangle(mesh);
  } else {
    s.method = method_of(map);
    const ChartStatus solved = solve(chart, mesh, map);
    if (solved != ChartStatus::Valid) return solved;
  }
  if (folds(mesh, chart.UV, degenerate_ratio, s.flipped)) return ChartStatus::Flipped;
  if (boundary_crosses(t.boundary_loops, chart.UV)) return ChartStatus::BoundaryCrossing;
  if (nf > 1 && map.boundary == BoundaryShape::Natural && map.isometric_iterations > 0) refine(mesh, map, degenerate_ratio, chart);
  // With holes or a pinch, the exact test of every pair of triangles as
  // well: a messy export's flat face can fold over itself in 3D
  // (2CylinderEngine), which the map of a flat chart reproduces, and a
  // boundary that passes twice through one point leaves two corners there
  // that must not lie inside each other's triangles. (Elsewhere the fold and
  // boundary tests above suffice, and the test would cost every chart tried.)
  const bool pinched = join_pinched_corners(chart.mesh.data.V, chart.UV);
  if (t.boundary_loops.size() > 1 || pinched) {
    const std::vector<char> overlapping = overlapping_uv_triangles(mesh.F, chart.UV);
    if (std::find(overlapping.begin(), overlapping.end(), 1) != overlapping.end()) return ChartStatus::BoundaryCrossing;
  }
  summarize_stretch(mesh, chart);
  chart.box_fill = chart_box(chart).fill;
  return ChartStatus::Valid;
}

double weighted_quantile(const std::vector<double>& value, const std::vector<double>& weight, double q) {
  std::vector<int> order(value.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return value[a] < value[b]; });
  double total = 0;
  for (double w : weight) total += w;
  double below = 0;
  for (int i : order) {
    below += weight[i];
    if (below >= q * total) return value[i];
  }
  return order.empty() ? 1 : value[order.back()];
}

}  // namespace intrinsic::detail

