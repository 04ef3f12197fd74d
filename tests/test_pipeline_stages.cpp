// The stages around the solve (read, validate, write, metrics) and the param
// pipeline that runs them: each against a plain formulation written here, the
// same result on one thread as on two, and the pipeline's own output (written
// while the map is measured) equal to writing and measuring one after the other.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "cli_support.h"
#include "weights/assemble.h"
#include "intrinsic/error.h"
#include "intrinsic/weights.h"
#include "intrinsic/metrics.h"
#include "intrinsic/pipeline.h"
#include "mesh/topology_build.h"
#include "test_support.h"
#include "util/parallel_for.h"
#include "util/vertex_adjacency.h"

namespace intrinsic {
namespace {

using test::slurp;
using test::TempDir;

// Large enough that the face loops split into two parts (50000 faces a part).
MeshData big_patch() {
  GenerateOptions g;
  g.rings = 140;  // about 59000 vertices, 117000 faces
  return generate_wavy_patch(g);
}

// Runs fn with the worker threads limited to `threads`, restoring the limit.
template <class Fn>
auto with_threads(int threads, Fn&& fn) {
  std::atomic<int>& limit = detail::thread_limit();
  const int saved = limit.load();
  limit = threads;
  struct Restore {
    std::atomic<int>& l;
    int v;
    ~Restore() { l = v; }
  } restore{limit, saved};
  return fn();
}

// A map with some distortion and no symmetry: an affine map of the 3D
// positions plus a small nonlinear term.
MatrixX2d some_map(const MatrixX3d& V) {
  MatrixX2d UV(V.rows(), 2);
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    UV(i, 0) = 1.3 * V(i, 0) + 0.2 * V(i, 1) + 0.1 * V(i, 2) * V(i, 2);
    UV(i, 1) = -0.1 * V(i, 0) + 0.8 * V(i, 1) + 0.05 * std::sin(3 * V(i, 0));
  }
  return UV;
}

TEST(PipelineStages, UniqueEdgesEqualASetOfEdges) {
  const MeshData d = big_patch();
  std::set<std::pair<int, int>> plain;
  for (Eigen::Index f = 0; f < d.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int i = d.F(f, c), j = d.F(f, (c + 1) % 3);
      plain.insert({std::min(i, j), std::max(i, j)});
    }
  for (int threads : {1, 2, 3}) {
    const Eigen::MatrixX2i E = with_threads(threads, [&] { return unique_edges(d.F); });
    ASSERT_EQ(E.rows(), static_cast<Eigen::Index>(plain.size())) << threads;
    Eigen::Index k = 0;
    for (const auto& [i, j] : plain) {
      ASSERT_EQ(E(k, 0), i) << k;
      ASSERT_EQ(E(k, 1), j) << k;
      ++k;
    }
  }
}

// The adjacency of the faces as one std::set per new vertex number, straight
// from the definition: the kept vertices sharing a face with a kept vertex.
std::vector<std::set<int>> adjacency_sets(const MatrixX3i& F, const std::vector<int>& number, int count,
                                          detail::AdjacencyNeighbours which) {
  std::vector<std::set<int>> sets(count);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      for (int e = 0; e < 3; ++e) {
        const int a = number[F(f, c)], b = number[F(f, e)];
        if (c == e || a < 0 || b < 0) continue;
        if (which != detail::AdjacencyNeighbours::LargerOnly || b > a) sets[a].insert(b);
      }
  if (which == detail::AdjacencyNeighbours::AllAndSelf)
    for (int k = 0; k < count; ++k) sets[k].insert(k);
  return sets;
}

void expect_pattern_is(const SparseMatrix& P, const std::vector<std::set<int>>& sets, const std::string& what) {
  ASSERT_EQ(P.rows(), static_cast<Eigen::Index>(sets.size())) << what;
  ASSERT_EQ(P.cols(), static_cast<Eigen::Index>(sets.size())) << what;
  ASSERT_TRUE(P.isCompressed()) << what;
  int k = 0;
  for (size_t j = 0; j < sets.size(); ++j) {
    ASSERT_EQ(P.outerIndexPtr()[j], k) << what << ", column " << j;
    for (int i : sets[j]) ASSERT_EQ(P.innerIndexPtr()[k++], i) << what << ", column " << j;
  }
  ASSERT_EQ(P.outerIndexPtr()[sets.size()], k) << what;
}

// util/vertex_adjacency.h against sets built here, on a mesh large enough
// for the faces to split into parts, whose faces around three vertices are
// dropped (those three are unused) and with two vertices no face names at
// the end: every vertex kept with its own number, and a subset (every third
// vertex, one unused vertex and one named by faces left out) numbered
// backwards, so that the new order is not the vertices'. Each of the three
// kinds of column, on 1 to 3 threads.
TEST(PipelineStages, VertexAdjacencyEqualsSetsOnASubset) {
  const MeshData d = big_patch();
  const int n = static_cast<int>(d.V.rows()) + 2;
  const int unused[] = {1000, 20000, 40000};
  std::vector<int> rows;
  for (int f = 0; f < d.F.rows(); ++f) {
    bool drop = false;
    for (int c = 0; c < 3; ++c)
      for (int u : unused) drop = drop || d.F(f, c) == u;
    if (!drop) rows.push_back(f);
  }
  const MatrixX3i F = d.F(rows, Eigen::all);
  ASSERT_GT(F.rows(), 100000);  // two parts at least
  ASSERT_LT(F.rows(), d.F.rows());
  std::vector<int> identity(n), subset(n, -1);
  for (int v = 0; v < n; ++v) identity[v] = v;
  int count = 0;
  for (int v = n - 1; v >= 0; --v)
    if (v % 3 != 0 && v != unused[1] && v != 777) subset[v] = count++;
  using detail::AdjacencyNeighbours;
  for (AdjacencyNeighbours which :
       {AdjacencyNeighbours::All, AdjacencyNeighbours::AllAndSelf, AdjacencyNeighbours::LargerOnly}) {
    const std::vector<std::set<int>> all = adjacency_sets(F, identity, n, which);
    const std::vector<std::set<int>> some = adjacency_sets(F, subset, count, which);
    for (int threads : {1, 2, 3}) {
      const std::string what = "kind " + std::to_string(static_cast<int>(which)) + ", " + std::to_string(threads) +
                               " threads";
      expect_pattern_is(with_threads(threads, [&] { return detail::vertex_adjacency_pattern(F, n, {}, which); }),
                        all, what + ", every vertex");
      expect_pattern_is(
          with_threads(threads, [&] { return detail::vertex_adjacency_pattern(F, count, subset, which); }), some,
          what + ", a subset");
    }
  }
}

// The summary against plain serial loops over the faces and a set of edges
// (the definitions of docs/maths.md §9), and the same bits on 1 and 2 threads.
TEST(PipelineStages, DistortionSummaryEqualsPlainLoops) {
  const MeshData d = big_patch();
  const MatrixX2d UV = some_map(d.V);
  const int m = static_cast<int>(d.F.rows());
  double area3 = 0, area2 = 0;
  std::vector<double> a3(m);
  for (int f = 0; f < m; ++f) {
    const Eigen::Vector3d x0 = d.V.row(d.F(f, 0)), x1 = d.V.row(d.F(f, 1)), x2 = d.V.row(d.F(f, 2));
    const Eigen::Vector2d u0 = UV.row(d.F(f, 0)), u1 = UV.row(d.F(f, 1)), u2 = UV.row(d.F(f, 2));
    a3[f] = 0.5 * (x1 - x0).cross(x2 - x0).norm();
    area3 += a3[f];
    area2 += 0.5 * ((u1 - u0).x() * (u2 - u0).y() - (u1 - u0).y() * (u2 - u0).x());
  }
  const double k = std::sqrt(area3 / std::abs(area2));
  // Angle distortion s1/s2 from the singular values of the Jacobian, which
  // here come from the eigenvalues of the first fundamental form of the map.
  double angle_sum = 0, area_energy = 0;
  for (int f = 0; f < m; ++f) {
    const Eigen::Vector3d x0 = d.V.row(d.F(f, 0)), x1 = d.V.row(d.F(f, 1)), x2 = d.V.row(d.F(f, 2));
    const Eigen::Vector2d u0 = k * UV.row(d.F(f, 0)), u1 = k * UV.row(d.F(f, 1)), u2 = k * UV.row(d.F(f, 2));
    Eigen::Matrix<double, 3, 2> X;
    X << x1 - x0, x2 - x0;
    Eigen::Matrix2d U;
    U << u1 - u0, u2 - u0;
    const Eigen::Matrix2d G3 = X.transpose() * X;  // metric of the face
    const Eigen::Matrix2d G2 = U.transpose() * U;  // metric of its image
    const Eigen::Vector2cd ev = (G3.inverse() * G2).eigenvalues();
    const double l1 = std::max(ev[0].real(), ev[1].real()), l2 = std::min(ev[0].real(), ev[1].real());
    angle_sum += a3[f] * std::sqrt(l1 / l2);
    const double a2 = 0.5 * ((u1 - u0).x() * (u2 - u0).y() - (u1 - u0).y() * (u2 - u0).x());
    area_energy += (a2 / a3[f] - 1) * (a2 / a3[f] - 1);
  }
  std::set<std::pair<int, int>> edges;
  for (int f = 0; f < m; ++f)
    for (int c = 0; c < 3; ++c) {
      const int i = d.F(f, c), j = d.F(f, (c + 1) % 3);
      edges.insert({std::min(i, j), std::max(i, j)});
    }
  double edge_energy = 0, ratio_max = 0;
  for (const auto& [i, j] : edges) {
    const double r = (k * k) * (UV.row(i) - UV.row(j)).squaredNorm() / (d.V.row(i) - d.V.row(j)).squaredNorm();
    edge_energy += (r - 1) * (r - 1);
    ratio_max = std::max(ratio_max, r);
  }

  const DistortionSummary one = with_threads(1, [&] { return summarize_distortion(d.V, d.F, UV); });
  const DistortionSummary two = with_threads(2, [&] { return summarize_distortion(d.V, d.F, UV); });
  EXPECT_NEAR(one.scale_factor, k, 1e-12 * k);
  EXPECT_NEAR(one.angle_distortion.mean, angle_sum / area3, 1e-9);
  EXPECT_NEAR(one.area_energy, area_energy, 1e-9 * area_energy);
  EXPECT_NEAR(one.edge_length_energy, edge_energy, 1e-9 * edge_energy);
  EXPECT_NEAR(one.edge_length_distortion.max, ratio_max, 1e-12 * ratio_max);
  EXPECT_EQ(one.flipped_triangles, 0);
  // Bit for bit, whatever the threads.
  EXPECT_EQ(one.scale_factor, two.scale_factor);
  EXPECT_EQ(one.angle_distortion.mean, two.angle_distortion.mean);
  EXPECT_EQ(one.area_distortion.mean, two.area_distortion.mean);
  EXPECT_EQ(one.stretch_l2.mean, two.stretch_l2.mean);
  EXPECT_EQ(one.stretch_linf.max, two.stretch_linf.max);
  EXPECT_EQ(one.edge_length_distortion.mean, two.edge_length_distortion.mean);
  EXPECT_EQ(one.edge_length_energy, two.edge_length_energy);
  EXPECT_EQ(one.area_energy, two.area_energy);
}

// The weight matrix against Eigen's triplet assembly of the same per-face
// weights: the same pattern (the vertex adjacency and the diagonal) on any
// number of threads, and the same sums up to the order of addition.
TEST(PipelineStages, AssemblyEqualsATripletAssembly) {
  const MeshData d = big_patch();
  WeightOptions w;
  w.method = Method::Mixed;  // not symmetric: K_ij and K_ji differ
  w.lambda = 0.3;
  w.mu = 0.7;
  std::vector<Eigen::Triplet<double>> t;
  for (int f = 0; f < d.F.rows(); ++f) {
    const Eigen::Matrix3d W = face_weights(d.V, d.F, f, w);
    for (int c = 0; c < 3; ++c)
      for (int e = 0; e < 3; ++e)
        if (c != e) {
          t.emplace_back(d.F(f, c), d.F(f, e), -W(c, e));
          t.emplace_back(d.F(f, c), d.F(f, c), W(c, e));
        }
  }
  for (int v = 0; v < d.V.rows(); ++v) t.emplace_back(v, v, 0.0);
  SparseMatrix plain(d.V.rows(), d.V.rows());
  plain.setFromTriplets(t.begin(), t.end());
  for (int threads : {1, 2, 3}) {
    const SparseMatrix K = with_threads(threads, [&] { return assemble_weight_matrix(d.V, d.F, w); });
    ASSERT_EQ(K.nonZeros(), plain.nonZeros()) << threads;
    ASSERT_TRUE(K.isCompressed());
    for (int j = 0; j <= K.cols(); ++j) ASSERT_EQ(K.outerIndexPtr()[j], plain.outerIndexPtr()[j]) << j;
    for (Eigen::Index k = 0; k < K.nonZeros(); ++k) {
      ASSERT_EQ(K.innerIndexPtr()[k], plain.innerIndexPtr()[k]) << k;
      ASSERT_NEAR(K.valuePtr()[k], plain.valuePtr()[k], 1e-12 * (1 + std::abs(plain.valuePtr()[k]))) << k;
    }
  }
}

// Face lines the plain-triangle reader takes and those it hands to the
// general corner loop, mixed in one file: the same triangles as written, and
// each malformed line named by file and line.
TEST(PipelineStages, ObjFaceLinesPlainAndOtherwise) {
  const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n";
  const MeshData d = read_mesh_from_memory(head +
                                               "f 1 2 3\n"
                                               "f\t2 4 3 \r\n"
                                               "f 01 2 4 # a comment\n"
                                               "f 1 2 3 4\n"
                                               "f -4 -3 -2\n",
                                           "t.obj");
  // The quad is fanned (1 2 3, 1 3 4); negative indices count back from the
  // 4 vertices.
  MatrixX3i want(6, 3);
  want << 0, 1, 2, 1, 3, 2, 0, 1, 3, 0, 1, 2, 0, 2, 3, 0, 1, 2;
  EXPECT_EQ(d.F, want);
  EXPECT_EQ(d.face_line, (std::vector<int>{9, 10, 11, 12, 12, 13}));
  EXPECT_EQ(d.TC.rows(), 0);  // not every face has texture indices
  const MeshData t = read_mesh_from_memory(head + "f 1/1 2/2 3/3\nf 2/2 4/4 3/3\n", "t.obj");
  EXPECT_EQ(t.TC.rows(), 4);
  EXPECT_EQ(t.FTC, t.F);

  const std::pair<std::string, std::string> bad[] = {
      {"f 1 2 3\nf 1 2 0\n", "t.obj:10: face vertex index 0 is invalid"},
      {"f 1 2 3\nf 1 2 99999999999\n", "t.obj:10: face vertex index 99999999999 is too large"},
      {"f 1 2 x\n", "t.obj:9: expected a vertex index in face, found 'x'"},
      {"f 1 2\n", "t.obj:9: face has 2 vertices"},
      {"f 1 2 3\nf 1 2 9\n", "t.obj:10: face index 9 out of range"},
  };
  for (const auto& [faces, message] : bad) {
    try {
      read_mesh_from_memory(head + faces, "t.obj");
      ADD_FAILURE() << faces;
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input);
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
}

void expect_same_topology(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(a.V, b.V);
  EXPECT_EQ(a.F, b.F);
  EXPECT_EQ(a.validation.reoriented_faces, b.validation.reoriented_faces);
  EXPECT_EQ(a.topology.twin, b.topology.twin);
  EXPECT_EQ(a.topology.vertex_out, b.topology.vertex_out);
  EXPECT_EQ(a.topology.is_boundary, b.topology.is_boundary);
  EXPECT_EQ(a.topology.boundary_loops, b.topology.boundary_loops);
  EXPECT_EQ(a.topology.face_component, b.topology.face_component);
}

// Twins found by a map of directed edges, against the topology's.
TEST(PipelineStages, ValidationTakesOverTheArraysAndFindsTheSameTwins) {
  MeshData d = big_patch();
  for (Eigen::Index f = 0; f < d.F.rows(); f += 7) std::swap(d.F(f, 1), d.F(f, 2));  // some to reorient
  const Mesh copied = make_mesh(d);
  EXPECT_GT(copied.validation.reoriented_faces, 0);
  MeshData moved_from = d;
  const Mesh taken = detail::make_mesh_taking(std::move(moved_from));
  expect_same_topology(copied, taken);
  EXPECT_EQ(moved_from.V.rows(), 0);  // taken over, not copied
  const Mesh one = with_threads(1, [&] { return make_mesh(d); });
  expect_same_topology(copied, one);

  std::map<std::pair<int, int>, int> directed;
  for (int h = 0; h < 3 * static_cast<int>(copied.F.rows()); ++h)
    directed[{copied.source(h), copied.target(h)}] = h;
  for (int h = 0; h < 3 * static_cast<int>(copied.F.rows()); ++h) {
    const auto it = directed.find({copied.target(h), copied.source(h)});
    ASSERT_EQ(copied.topology.twin[h], it == directed.end() ? -1 : it->second) << h;
  }
}

std::string validation_message(const MeshData& d) {
  try {
    make_mesh(d);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    return e.what();
  }
  return "";
}

// Faults in both halves of the faces (one per thread): the message is the
// one a serial scan gives, by precedence of the fault, then file order.
TEST(PipelineStages, ValidationReportsTheSameFaultOnAnyThreads) {
  const MeshData good = big_patch();
  const int m = static_cast<int>(good.F.rows());
  MeshData d = good;
  d.F.row(10) << d.F(10, 0), d.F(10, 0), d.F(10, 2);  // degenerate indices in the first half
  d.F(m - 5, 1) = static_cast<int>(d.V.rows()) + 3;    // out of range in the second half
  for (int threads : {1, 2}) {
    const std::string msg = with_threads(threads, [&] { return validation_message(d); });
    EXPECT_NE(msg.find("face 10 repeats vertex"), std::string::npos) << msg;
  }
  MeshData c = good;
  c.V.row(c.F(m - 5, 2)) << 1, std::numeric_limits<double>::quiet_NaN(), 0;  // second half
  c.V.row(c.F(20, 1)) = c.V.row(c.F(20, 0));                                // zero area, first half
  for (int threads : {1, 2}) {
    const std::string msg = with_threads(threads, [&] { return validation_message(c); });
    EXPECT_NE(msg.find("vertex " + std::to_string(c.F(m - 5, 2)) + " has a non-finite coordinate"),
              std::string::npos)
        << msg;
  }
  MeshData z = good;
  z.V.row(z.F(m - 9, 1)) = z.V.row(z.F(m - 9, 0));
  z.V.row(z.F(30, 2)) = z.V.row(z.F(30, 0));
  for (int threads : {1, 2}) {
    const std::string msg = with_threads(threads, [&] { return validation_message(z); });
    EXPECT_NE(msg.find(" is degenerate"), std::string::npos) << msg;
    // The first degenerate face in file order: face 30 or an earlier one
    // sharing the moved vertex.
    const std::size_t at = msg.find("face ");
    ASSERT_NE(at, std::string::npos) << msg;
    EXPECT_LE(std::stoi(msg.substr(at + 5)), 30) << msg;
  }
}

// The pipeline writes while it measures: the file is the one write_mesh
// writes for the outcome, it reads back to the same doubles, and the summary
// is the one computed on its own.
TEST(PipelineStages, PipelineWritesWhileItMeasures) {
  TempDir dir;
  GenerateOptions g;
  g.rings = 40;
  const MeshData in = generate_wavy_patch(g);
  const std::string path = dir / "in.obj", out = dir / "out.obj", again = dir / "again.obj";
  write_mesh(path, in.V, in.F, MatrixX2d());
  ParamRequest request;
  request.output = out;
  const ParamOutcome o = parameterize_file(path, request);
  EXPECT_GT(o.write_ms, 0);
  EXPECT_GT(o.metrics_ms, 0);
  write_mesh(again, o.mesh.V, o.mesh.F, o.map.UV);
  EXPECT_EQ(slurp(out), slurp(again));
  const MeshData back = read_mesh(out);
  EXPECT_EQ(back.V, o.mesh.V);  // shortest round-trip text: the same doubles
  EXPECT_EQ(back.TC, o.map.UV);
  const DistortionSummary s = summarize_distortion(o.mesh.V, o.mesh.F, o.map.UV);
  EXPECT_EQ(o.distortion.angle_distortion.mean, s.angle_distortion.mean);
  EXPECT_EQ(o.distortion.edge_length_energy, s.edge_length_energy);
  EXPECT_EQ(o.distortion.area_energy, s.area_energy);
  EXPECT_EQ(o.distortion.scale_factor, s.scale_factor);

  // Without an output: nothing written, the same summary.
  request.output.clear();
  const ParamOutcome quiet = parameterize_file(path, request);
  EXPECT_EQ(quiet.write_ms, 0);
  EXPECT_EQ(quiet.distortion.angle_distortion.mean, s.angle_distortion.mean);

  // A write that fails is an output error and leaves no file.
  request.output = dir / "missing/out.obj";
  try {
    parameterize_file(path, request);
    ADD_FAILURE() << "expected an output error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Output) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "missing"));
}

}  // namespace
}  // namespace intrinsic
