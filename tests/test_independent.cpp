// Numbers checked against references that owe nothing to the library's own
// code or to values it wrote: linear reproduction on flat meshes (cotangent,
// authalic and mean-value weights reproduce linear functions, so a flat disk
// with holes filled must come back as its own x, y); each chart of a
// several-component mesh against parameterize() of that component alone, up
// to a similarity fitted here by least squares; boundary optimization against
// the known optimum 0 of its energies on a flat disk; constrained maps against
// a dense Lagrange (KKT) system assembled and solved here with Eigen's
// FullPivLU from the weights of tests/independent_assembly.h; invariances
// under scaling and rigid motions; and the weight matrices' rows (zero sums,
// entries equal to the independent weights) on generated surfaces and every
// shared mesh.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <complex>
#include <queue>

#include "independent_assembly.h"
#include "weights/assemble.h"
#include "intrinsic/boundary_optimization.h"
#include "intrinsic/charts.h"
#include "intrinsic/io.h"
#include "intrinsic/metrics.h"
#include "intrinsic/parameterizer.h"
#include "test_support.h"

namespace intrinsic {
namespace {

// ------------------------------------------------------------ helpers

// Graph distance (in edges) from every vertex to the nearest source.
std::vector<int> hops_from(const MatrixX3i& F, int n, const std::vector<int>& sources) {
  std::vector<std::vector<int>> adj(n);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) adj[F(f, c)].push_back(F(f, (c + 1) % 3)), adj[F(f, (c + 1) % 3)].push_back(F(f, c));
  std::vector<int> d(n, 1 << 30);
  std::queue<int> q;
  for (int s : sources) d[s] = 0, q.push(s);
  while (!q.empty()) {
    const int v = q.front();
    q.pop();
    for (int w : adj[v])
      if (d[w] > d[v] + 1) d[w] = d[v] + 1, q.push(w);
  }
  return d;
}

// A jittered flat disk with the faces around `count` interior vertices
// removed: the vertices are at least 3 edges from the outer boundary and 4
// from each other, so every hole is a one-ring on its own (manifold, its
// loop shares nothing with another). The centres stay in V, unreferenced.
Mesh flat_disk_with_holes(int count, std::vector<int>& centres) {
  GenerateOptions g;
  g.rings = 10;
  g.jitter = 0.5;
  const MeshData disk = generate_flat_disk(g);
  const Mesh whole = make_mesh(disk);
  const int n = static_cast<int>(disk.V.rows());
  const std::vector<int> to_boundary = hops_from(disk.F, n, whole.topology.boundary_loops[0]);
  centres.clear();
  for (int v = 7; v < n && static_cast<int>(centres.size()) < count; v += 13) {
    if (to_boundary[v] < 3) continue;
    if (!centres.empty() && hops_from(disk.F, n, centres)[v] < 4) continue;
    centres.push_back(v);
  }
  EXPECT_EQ(static_cast<int>(centres.size()), count);
  std::vector<Eigen::RowVector3i> kept;
  for (Eigen::Index f = 0; f < disk.F.rows(); ++f) {
    bool touches = false;
    for (int c = 0; c < 3; ++c) touches |= std::count(centres.begin(), centres.end(), disk.F(f, c)) > 0;
    if (!touches) kept.push_back(disk.F.row(f));
  }
  MatrixX3i F(static_cast<Eigen::Index>(kept.size()), 3);
  for (size_t f = 0; f < kept.size(); ++f) F.row(static_cast<Eigen::Index>(f)) = kept[f];
  return make_mesh(disk.V, F);
}

// Least-squares fit of Q ~ s P + t (uniform scale and translation) or, with
// `rotate`, Q ~ a P + t for a complex a (any similarity), over `rows`.
// Returns the largest distance between the fitted P and Q.
double similarity_fit_residual(const MatrixX2d& P, const MatrixX2d& Q, const std::vector<int>& rows, bool rotate) {
  using C = std::complex<double>;
  C pm = 0, qm = 0;
  for (int v : rows) pm += C(P(v, 0), P(v, 1)), qm += C(Q(v, 0), Q(v, 1));
  pm /= static_cast<double>(rows.size());
  qm /= static_cast<double>(rows.size());
  C num = 0;
  double den = 0;
  for (int v : rows) {
    const C p = C(P(v, 0), P(v, 1)) - pm, q = C(Q(v, 0), Q(v, 1)) - qm;
    num += rotate ? std::conj(p) * q : C((std::conj(p) * q).real(), 0);
    den += std::norm(p);
  }
  const C a = num / den;
  double worst = 0;
  for (int v : rows) {
    const C fitted = a * (C(P(v, 0), P(v, 1)) - pm) + qm;
    worst = std::max(worst, std::abs(fitted - C(Q(v, 0), Q(v, 1))));
  }
  return worst;
}

std::vector<int> used_vertices(const Mesh& mesh) {
  std::vector<int> v;
  for (int i = 0; i < mesh.V.rows(); ++i)
    if (mesh.topology.is_used[i]) v.push_back(i);
  return v;
}

double max_abs_on(const MatrixX2d& A, const std::vector<int>& rows) {
  double m = 0;
  for (int v : rows) m = std::max(m, A.row(v).cwiseAbs().maxCoeff());
  return m;
}

// ------------------------------------------------------------ 2. holes, fill rule

// The flat disk with three one-ring holes, its outer loop given at its own
// x, y and the holes filled: conformal, authalic, mixed and mean-value rows
// all vanish at the identity of a flat mesh (the fans around the centroids
// are flat too), so the map must be the disk's own x, y. Tutte's uniform
// weights do not reproduce linear functions and are not tested here.
TEST(Independent, FlatDiskWithFilledHolesReproducesItself) {
  std::vector<int> centres;
  const Mesh mesh = flat_disk_with_holes(3, centres);
  ASSERT_EQ(mesh.topology.boundary_loops.size(), 4u);
  EXPECT_EQ(mesh.validation.unreferenced_vertices, 3);
  // Precondition of the argument: each fan triangle (b, a, centroid) is
  // counter-clockwise in the plane, so the filled mesh is a flat embedding.
  for (size_t l = 1; l < 4; ++l) {
    const std::vector<int>& loop = mesh.topology.boundary_loops[l];
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (int v : loop) c += mesh.V.row(v).head<2>().transpose() / static_cast<double>(loop.size());
    for (size_t k = 0; k < loop.size(); ++k) {
      const Eigen::Vector2d a = mesh.V.row(loop[k]).head<2>(), b = mesh.V.row(loop[(k + 1) % loop.size()]).head<2>();
      ASSERT_GT((a - b).x() * (c - b).y() - (a - b).y() * (c - b).x(), 0) << "hole " << l;
    }
  }
  const MatrixX2d XY = mesh.V.leftCols(2);
  const std::vector<int> used = used_vertices(mesh);
  ParamOptions o;
  o.boundary = BoundaryShape::Given;
  o.holes = HoleRule::Fill;
  for (int v : mesh.topology.boundary_loops[0]) o.given.push_back({v, XY.row(v).transpose()});
  for (const WeightOptions& w : {WeightOptions{Method::Conformal, 1, 0}, WeightOptions{Method::Authalic, 0, 1},
                                 WeightOptions{Method::Mixed, 0.3, 0.7}, WeightOptions{Method::Floater, 0, 0}}) {
    o.weights = w;
    const ParamResult r = parameterize(mesh, o);
    EXPECT_EQ(r.filled_holes, 3) << method_name(w.method);
    EXPECT_EQ(r.holes, HolesApplied::Fill);
    EXPECT_LT(max_abs_on(r.UV - XY, used), 1e-12 * test::diameter(XY)) << method_name(w.method);
  }
}

// ------------------------------------------------------------ 3. charts

// Two generated patches of different shape in one mesh: a sphere cap and a
// jittered flat disk moved away from it.
Mesh cap_and_disk() {
  GenerateOptions g;
  g.rings = 6;
  const MeshData cap = generate_sphere_cap(g);
  g.rings = 7;
  g.jitter = 0.5;
  g.seed = 5;
  const MeshData disk = generate_flat_disk(g);
  MeshData both;
  both.V.resize(cap.V.rows() + disk.V.rows(), 3);
  both.V << cap.V, disk.V.rowwise() + Eigen::RowVector3d(3, 0.5, 0);
  both.F.resize(cap.F.rows() + disk.F.rows(), 3);
  both.F << cap.F, disk.F.array() + static_cast<int>(cap.V.rows());
  ValidateOptions vo;
  vo.allow_several_components = true;
  return make_mesh(both, vo);
}

// Each chart of parameterize_charts equals parameterize() of its component
// alone, up to a uniform scale and a translation (the packing); the natural
// map's pins are placed by a similarity, so a rotation is allowed there.
void check_charts_match_components(const Mesh& mesh, const ParamOptions& o, bool rotate) {
  ASSERT_GE(mesh.topology.num_components, 2);
  const ParamResult all = parameterize_charts(mesh, o);
  ASSERT_EQ(static_cast<int>(all.charts.size()), mesh.topology.num_components);
  for (int c = 0; c < mesh.topology.num_components; ++c) {
    const Mesh part = make_mesh(component_data(mesh, c));
    const ParamResult alone = parameterize(part, o);
    const std::vector<int> used = used_vertices(part);
    const double size = test::diameter(all.UV(used, Eigen::all));
    EXPECT_LT(similarity_fit_residual(alone.UV, all.UV, used, rotate), 1e-9 * size)
        << "component " << c << " " << boundary_shape_name(o.boundary) << " " << method_name(o.weights.method);
  }
}

TEST(Independent, EachChartIsItsComponentAloneUpToASimilarity) {
  for (const Mesh& mesh : {test::two_disks(), cap_and_disk()}) {
    ParamOptions o;
    check_charts_match_components(mesh, o, false);
    o.weights = {Method::Authalic, 0, 1};
    check_charts_match_components(mesh, o, false);
    o = ParamOptions();
    o.boundary = BoundaryShape::Natural;
    check_charts_match_components(mesh, o, true);
  }
}

// ------------------------------------------------------------ 4. boundary optimization

// A flat disk is isometric to its own x, y, and the conformal map of that
// boundary is the identity, so both section 5.1 energies (docs/maths.md
// §8.2) have the minimum 0 over boundary positions, reached at any rigid
// motion of x, y. From the circle the optimizer must get there, not merely
// descend: below 1e-6 of the start's energy.
TEST(Independent, BoundaryOptimizationReachesZeroEnergyOnAFlatDisk) {
  GenerateOptions g;
  g.rings = 6;
  g.jitter = 0.5;
  MeshData disk = generate_flat_disk(g);
  // Bent and stretched in its plane, so the circle start is far from the
  // optimum; the mesh stays flat (z = 0).
  for (Eigen::Index v = 0; v < disk.V.rows(); ++v)
    disk.V.row(v).head<2>() << 1.6 * disk.V(v, 0), disk.V(v, 1) + 0.3 * disk.V(v, 0) * disk.V(v, 0);
  const Mesh mesh = make_mesh(disk);
  for (BoundaryEnergy e : {BoundaryEnergy::EdgeLength, BoundaryEnergy::Area}) {
    SCOPED_TRACE(boundary_energy_name(e));
    // The target value itself: the identity has energy 0 (to rounding).
    EXPECT_LT(boundary_energy(mesh.V, mesh.F, mesh.V.leftCols(2), e, nullptr), 1e-25);
    BoundaryOptimizationOptions o;
    o.energy = e;
    const BoundaryOptimizationResult r = optimize_boundary(mesh, o);
    const double start = r.energy_history.front(), end = r.energy_history.back();
    EXPECT_GT(start, 1e-2);
    EXPECT_LT(end, 1e-6 * start) << r.stop_reason << " after " << r.iterations << " iterations";
    if (e == BoundaryEnergy::EdgeLength)  // zero edge-length energy: the disk itself, up to a rigid motion
      EXPECT_LT(similarity_fit_residual(mesh.V.leftCols(2), r.UV, used_vertices(mesh), true), 1e-3);
  }
}

// ------------------------------------------------------------ 5. constraints

// K = D - W of a method (docs/maths.md §1.4: K_ij = -w_ij, K_ii = sum_j w_ij),
// dense, from the independent weights.
Eigen::MatrixXd dense_K(const Mesh& mesh, const WeightOptions& w) {
  const Eigen::MatrixXd W = Eigen::MatrixXd(test::weight_table(mesh.V, mesh.F, w));
  Eigen::MatrixXd K = -W;
  K.diagonal() += W.rowwise().sum();
  return K;
}

// The outer loop on the unit circle by 3D arc length (maths §2.2), computed
// here, then moved by uv -> s uv + o.
std::vector<FixedVertex> own_circle(const Mesh& mesh, double s, const Eigen::Vector2d& o) {
  const std::vector<int>& loop = mesh.topology.boundary_loops[0];
  double total = 0;
  for (size_t k = 0; k < loop.size(); ++k) total += (mesh.V.row(loop[(k + 1) % loop.size()]) - mesh.V.row(loop[k])).norm();
  std::vector<FixedVertex> out;
  double run = 0;
  for (size_t k = 0; k < loop.size(); ++k) {
    const double a = 2 * M_PI * run / total;
    out.push_back({loop[k], s * Eigen::Vector2d(std::cos(a), std::sin(a)) + o});
    run += (mesh.V.row(loop[(k + 1) % loop.size()]) - mesh.V.row(loop[k])).norm();
  }
  return out;
}

// The constrained map by the Lagrange system of docs/maths.md §5.3, formed
// densely on the free vertices and solved by FullPivLU:
//   [K_II C^T; C 0] [x; l] = [-K_IB U_B; t]   (constraints on free vertices only)
MatrixX2d dense_lagrange_map(const Mesh& mesh, const Eigen::MatrixXd& K, const std::vector<FixedVertex>& fixed,
                             const Constraints& cons) {
  const int n = static_cast<int>(mesh.V.rows());
  MatrixX2d UV = MatrixX2d::Zero(n, 2);
  std::vector<int> free_of(n, -1);
  std::vector<char> is_fixed(n, 0);
  for (const FixedVertex& f : fixed) UV.row(f.vertex) = f.uv.transpose(), is_fixed[f.vertex] = 1;
  int nI = 0;
  for (int v = 0; v < n; ++v)
    if (!is_fixed[v] && mesh.topology.is_used[v]) free_of[v] = nI++;
  const int m = static_cast<int>(cons.points.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(nI + m, nI + m), rhs = Eigen::MatrixXd::Zero(nI + m, 2);
  for (int i = 0; i < n; ++i) {
    if (free_of[i] < 0) continue;
    for (int j = 0; j < n; ++j) {
      if (free_of[j] >= 0) A(free_of[i], free_of[j]) = K(i, j);
      else if (is_fixed[j]) rhs.row(free_of[i]) -= K(i, j) * UV.row(j);
    }
  }
  for (int r = 0; r < m; ++r) {
    const SurfacePoint& p = cons.points[r].point;
    std::vector<std::pair<int, double>> terms;
    if (p.vertex >= 0) terms.push_back({p.vertex, 1.0});
    else for (int c = 0; c < 3; ++c) terms.push_back({mesh.F(p.face, c), p.bary[c]});
    for (const auto& [v, b] : terms) {
      EXPECT_GE(free_of[v], 0) << "the dense system takes constraints on free vertices only";
      A(nI + r, free_of[v]) = A(free_of[v], nI + r) = b;
    }
    rhs.row(nI + r) = cons.points[r].uv.transpose();
  }
  const Eigen::MatrixXd x = A.fullPivLu().solve(rhs);
  EXPECT_LT((A * x - rhs).norm(), 1e-12 * rhs.norm());
  for (int v = 0; v < n; ++v)
    if (free_of[v] >= 0) UV.row(v) = x.row(free_of[v]);
  return UV;
}

// A point constraint on an interior vertex and one inside a face whose
// corners are all interior, on a generated sphere cap; conformal (symmetric)
// and authalic (non-symmetric) weights; the boundary given at positions
// computed here, and the circle placed on [0,1]^2 as maths §2.4 says.
TEST(Independent, ConstrainedMapsEqualADenseLagrangeSolve) {
  GenerateOptions g;
  g.rings = 8;
  g.jitter = 0.4;
  const Mesh mesh = make_mesh(generate_sphere_cap(g));
  const Topology& t = mesh.topology;
  int vertex = static_cast<int>(mesh.V.rows()) / 3;
  while (t.is_boundary[vertex]) ++vertex;
  int face = static_cast<int>(mesh.F.rows()) / 2;
  while (t.is_boundary[mesh.F(face, 0)] || t.is_boundary[mesh.F(face, 1)] || t.is_boundary[mesh.F(face, 2)] ||
         (mesh.F.row(face).array() == vertex).any())
    ++face;
  Constraints cons;
  cons.points.push_back({SurfacePoint::at_vertex(vertex), Eigen::Vector2d(0.15, -0.2), ""});
  cons.points.push_back({SurfacePoint::in_face(face, Eigen::Vector3d(0.2, 0.5, 0.3)), Eigen::Vector2d(-0.3, 0.25), ""});
  for (const WeightOptions& w : {WeightOptions{Method::Conformal, 1, 0}, WeightOptions{Method::Authalic, 0, 1}}) {
    for (bool given : {true, false}) {
      SCOPED_TRACE(method_name(w.method) + (given ? " given" : " circle"));
      ParamOptions o;
      o.weights = w;
      if (given) {
        o.boundary = BoundaryShape::Given;
        o.given = own_circle(mesh, 1.3, Eigen::Vector2d(0.2, -0.1));
      }
      const std::vector<FixedVertex> fixed = given ? o.given : own_circle(mesh, 0.5, Eigen::Vector2d(0.5, 0.5));
      const MatrixX2d expected = dense_lagrange_map(mesh, dense_K(mesh, w), fixed, cons);
      Parameterizer p(mesh, o);
      const MatrixX2d unconstrained = p.solve().UV;
      p.set_constraints(cons);
      const ParamResult r = p.solve();
      EXPECT_LT((r.UV - expected).cwiseAbs().maxCoeff(), 1e-9);
      EXPECT_GT((r.UV - unconstrained).cwiseAbs().maxCoeff(), 0.05) << "the constraints must matter";
    }
  }
}

// ------------------------------------------------------------ 6. invariance

MeshData scaled(MeshData d, double f) {
  d.V *= f;
  return d;
}

// Unit-scale and surface-scale maps of the input scaled by 1e-6 and 1e6:
// the unit map unchanged, the surface map scaled by exactly the factor.
// With `pins` (natural map), user pins at their 3D distance replace the
// default ones and only the surface map is compared (pins are kept as given).
void check_scaling(const MeshData& data, ParamOptions o, const std::vector<int>& pins) {
  const Mesh mesh = make_mesh(data);
  auto with_pins = [&](const Mesh& m) {  // user pins at their 3D distance
    ParamOptions p = o;
    if (!pins.empty())
      p.pins = {{pins[0], Eigen::Vector2d(0, 0)}, {pins[1], Eigen::Vector2d((m.V.row(pins[0]) - m.V.row(pins[1])).norm(), 0)}};
    return p;
  };
  o.scale = ScaleMode::Unit;
  const MatrixX2d unit = parameterize(mesh, o).UV;
  o.scale = ScaleMode::Surface;
  const MatrixX2d surface = parameterize(mesh, with_pins(mesh)).UV;
  for (double f : {1e-6, 1e6}) {
    const Mesh small_or_large = make_mesh(scaled(data, f));
    o.scale = ScaleMode::Unit;
    if (pins.empty())
      EXPECT_LT((parameterize(small_or_large, o).UV - unit).cwiseAbs().maxCoeff(), 1e-10) << "unit, factor " << f;
    o.scale = ScaleMode::Surface;
    const MatrixX2d s = parameterize(small_or_large, with_pins(small_or_large)).UV;
    EXPECT_LT((s - f * surface).cwiseAbs().maxCoeff(), 1e-10 * f * surface.cwiseAbs().maxCoeff()) << "surface, factor " << f;
  }
}

MeshData wavy_data() {
  GenerateOptions g;
  g.rings = 10;
  return generate_wavy_patch(g);
}

// Uniform scaling of the input by 1e-6 and 1e6 leaves unit-scale maps
// unchanged and scales surface-scale maps by exactly the factor (circle with
// conformal and authalic weights; the natural map with two user pins at
// their 3D distance); a rigid motion leaves the unit-scale maps unchanged.
TEST(Independent, ScalingAndRigidMotionsOfTheInput) {
  const MeshData data = wavy_data();
  const Mesh mesh = make_mesh(data);
  MeshData moved = data;
  moved.V = test::rigid_motion(data.V);
  const Mesh rigid = make_mesh(moved);
  ParamOptions conformal, authalic, natural;
  authalic.weights = {Method::Authalic, 0, 1};
  natural.boundary = BoundaryShape::Natural;
  for (const ParamOptions& o : {conformal, authalic, natural}) {
    SCOPED_TRACE(boundary_shape_name(o.boundary) + " " + method_name(o.weights.method));
    EXPECT_LT((parameterize(rigid, o).UV - parameterize(mesh, o).UV).cwiseAbs().maxCoeff(), 1e-10) << "rigid motion";
    // Default pins: see NaturalDefaultPinsAreScaleInvariant below.
    check_scaling(data, o, o.boundary == BoundaryShape::Natural ? std::vector<int>{7, 328} : std::vector<int>{});
  }
}

// Regression (default pins, docs/maths.md §3.4): the wavy patch's outer loop
// is mirror-symmetric, so vertices 286-323 and 306-329 are both farthest
// pairs (|x_i - x_j|^2 = 4.0208069966370754 for both). Breaking ties by exact
// equality let rounding after scaling V by 1e-6 make the second pair larger
// by one ulp, so the pins moved and the unit-scale natural map moved by 0.49.
// Ties are now within a relative 1e-12, broken by the smallest index pair.
TEST(Independent, NaturalDefaultPinsAreScaleInvariant) {
  ParamOptions natural;
  natural.boundary = BoundaryShape::Natural;
  check_scaling(wavy_data(), natural, {});
}

// Every method's matrix K: each row sums to zero (K 1 = 0, maths §1.4) to
// 1e-12 of its largest entry, and its off-diagonal entries are -w_ij of the
// independent assembly.
void expect_weight_rows(const Mesh& mesh) {
  for (const WeightOptions& w : {WeightOptions{Method::Conformal, 1, 0}, WeightOptions{Method::Authalic, 0, 1},
                                 WeightOptions{Method::Tutte, 0, 0}, WeightOptions{Method::Floater, 0, 0},
                                 WeightOptions{Method::Mixed, 0.3, 0.7}}) {
    const test::RowSparse K = assemble_weight_matrix(mesh.V, mesh.F, w);
    const test::RowSparse W = test::weight_table(mesh.V, mesh.F, w);
    const test::RowSparse D = K + W;  // zero off the diagonal
    double worst_sum = 0, worst_entry = 0;
    for (int i = 0; i < K.rows(); ++i) {
      double sum = 0, largest = 0, off = 0;
      for (test::RowSparse::InnerIterator it(K, i); it; ++it) sum += it.value(), largest = std::max(largest, std::abs(it.value()));
      for (test::RowSparse::InnerIterator it(D, i); it; ++it)
        if (it.col() != i) off = std::max(off, std::abs(it.value()));
      if (largest == 0) continue;  // unused vertex
      worst_sum = std::max(worst_sum, std::abs(sum) / largest);
      worst_entry = std::max(worst_entry, off / largest);
    }
    EXPECT_LE(worst_sum, 1e-12) << method_name(w.method);
    EXPECT_LE(worst_entry, 1e-12) << method_name(w.method);
  }
}

TEST(Independent, WeightMatrixRowsSumToZeroAndEqualTheWeights) {
  GenerateOptions g;
  g.rings = 12;
  g.jitter = 0.6;
  for (const char* name : {"wave", "cap", "strip", "flat"}) {
    SCOPED_TRACE(name);
    expect_weight_rows(make_mesh(generate_surface(name, g)));
  }
  SCOPED_TRACE("holed wave");
  expect_weight_rows(make_mesh(test::holed_wavy(3)));
}

TEST(IndependentCorpus, WeightMatrixRowsSumToZeroAndEqualTheWeights) {
  REQUIRE_SHARED_MESHES();
  for (const char* name : test::kSharedMeshes) {
    SCOPED_TRACE(name);
    expect_weight_rows(make_mesh(read_mesh(test::shared_mesh(name))));
  }
}

}  // namespace
}  // namespace intrinsic
