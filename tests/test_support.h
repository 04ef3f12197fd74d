// Shared helpers for the tests: small meshes built in code, rigid motions,
// access to the shared real meshes (the corpus: tests in a suite named
// *Corpus, skipped where ../shared/meshes is absent), the
// intrinsic methods the constraint and editing tests loop over, surface
// points, and the check that a call is refused with a given error.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <zlib.h>

#include "intrinsic/constraints.h"
#include "intrinsic/error.h"
#include "intrinsic/generate.h"
#include "intrinsic/parameterize.h"
#include "intrinsic/mesh.h"

namespace intrinsic::test {

// A gzip member holding `data`, for the readers' transparent decompression.
inline std::string gzip(const std::string& data, int level = 6, int mem_level = 8) {
  z_stream zs{};
  EXPECT_EQ(deflateInit2(&zs, level, Z_DEFLATED, 15 + 16, mem_level, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&zs, data.size()) + 64, '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  zs.avail_in = static_cast<uInt>(data.size());
  zs.next_out = reinterpret_cast<Bytef*>(&out[0]);
  zs.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&zs, Z_FINISH), Z_STREAM_END);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

// Two irregular flat disks side by side (generate_two_disks, rings 8): a mesh
// of two components, validated with several components allowed.
inline Mesh two_disks() {
  GenerateOptions g;
  g.rings = 8;
  ValidateOptions vo;
  vo.allow_several_components = true;
  return make_mesh(generate_two_disks(g), vo);
}

// The corpus: the real meshes in ../shared/meshes beside the repository
// (CI always has them; a clone alone does not). A test that reads them lives
// in a suite whose name ends in "Corpus" (CMakeLists.txt gives those the
// ctest label `corpus`) and starts with REQUIRE_SHARED_MESHES(), which skips
// it, saying why, where the folder is absent. Where the folder is present, a
// missing mesh in it still fails the test: these are the reference inputs.
inline bool have_shared_meshes() { return std::filesystem::is_directory(INTRINSIC_SHARED_MESHES); }

inline bool in_corpus_suite() {
  const ::testing::TestInfo* t = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string suite = t ? t->test_suite_name() : "";
  return suite.size() >= 6 && suite.compare(suite.size() - 6, 6, "Corpus") == 0;
}

#define REQUIRE_SHARED_MESHES()                                                                              \
  do {                                                                                                       \
    if (!::intrinsic::test::have_shared_meshes())                                                            \
      GTEST_SKIP() << INTRINSIC_SHARED_MESHES " is absent: this test needs the shared real meshes (ctest "   \
                      "label corpus; the repository's own tests run on generated meshes)";                   \
  } while (0)

// The path of a shared mesh; only from a *Corpus suite, so that the ctest
// label and the skip cannot be forgotten.
inline std::string shared_mesh(const std::string& name) {
  if (!in_corpus_suite())
    ADD_FAILURE() << "shared_mesh(\"" << name << "\") outside a *Corpus test suite: name the suite *Corpus "
                  << "and start the test with REQUIRE_SHARED_MESHES()";
  return std::string(INTRINSIC_SHARED_MESHES) + "/" + name;
}

// The shared real meshes small enough to solve in every test that loops over
// them (every patch of meshstat.json but the half-million-vertex loop2).
inline const char* const kSharedMeshes[] = {
    "alligator.obj",          "animal.obj",    "beetle.off",          "camel_b.obj",
    "camelhead.off",          "cat_head.obj",  "face-bff.obj",        "fairing-cross.off",
    "inspired_mesh.obj",      "inverted-triangles.obj", "max-planck-partial.obj", "maze.obj",
    "snail.obj",              "stanford-bunny.obj"};

inline MatrixX3d rigid_motion(const MatrixX3d& V) {
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) * Eigen::AngleAxisd(-1.9, Eigen::Vector3d::UnitZ()))
          .toRotationMatrix();
  MatrixX3d W = (V * R.transpose()).rowwise() + Eigen::RowVector3d(10.5, -3.25, 7.0);
  return W;
}

// Signed UV area of face f, its corners in FUV's order.
inline double signed_uv_area(const MatrixX2d& UV, const MatrixX3i& FUV, int f) {
  const Eigen::Vector2d a = UV.row(FUV(f, 0)), b = UV.row(FUV(f, 1)), c = UV.row(FUV(f, 2));
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

inline double diameter(const MatrixX2d& UV) {
  return (UV.colwise().maxCoeff() - UV.colwise().minCoeff()).norm();
}

inline double diameter3(const MatrixX3d& V) {
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

// The generated curved, irregular disk most tests use.
inline Mesh wavy(int rings = 10, double jitter = GenerateOptions().jitter) {
  GenerateOptions g;
  g.rings = rings;
  g.jitter = jitter;
  return make_mesh(generate_wavy_patch(g));
}

// A curved disk with holes (the generated stand-in for the shared holed
// meshes): the wavy patch, rings 16, with the faces around up to three
// interior vertices removed (`holes` + 1 boundary loops).
inline MeshData holed_wavy(int holes) {
  GenerateOptions g;
  g.rings = 16;
  MeshData d = generate_wavy_patch(g);
  std::vector<char> drop(d.F.rows(), 0);
  const int centres[] = {3 * 10 * 9 + 5, 3 * 6 * 5 + 40, 3 * 12 * 11 + 20};
  for (int h = 0; h < holes; ++h)
    for (int f = 0; f < d.F.rows(); ++f)
      for (int c = 0; c < 3; ++c) drop[f] = drop[f] || d.F(f, c) == centres[h] + 1;
  MatrixX3i F(d.F.rows(), 3);
  int m = 0;
  for (int f = 0; f < d.F.rows(); ++f)
    if (!drop[f]) F.row(m++) = d.F.row(f);
  d.F = F.topRows(m);
  return d;
}

// The intrinsic family at its two ends and one mix.
struct MethodCase {
  Method m;
  double lambda, mu;
};
inline const MethodCase kMethods[] = {{Method::Conformal, 1, 0}, {Method::Authalic, 0, 1}, {Method::Mixed, 0.3, 0.7}};

inline ParamOptions options_for(const MethodCase& c) {
  ParamOptions o;
  o.weights.method = c.m;
  o.weights.lambda = c.lambda;
  o.weights.mu = c.mu;
  return o;
}

// The parameter position of a surface point, interpolated from UV.
inline Eigen::Vector2d value_at(const MatrixX2d& UV, const Mesh& mesh, const SurfacePoint& p) {
  if (p.vertex >= 0) return UV.row(p.vertex).transpose();
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  for (int c = 0; c < 3; ++c) x += p.bary[c] * UV.row(mesh.F(p.face, c)).transpose();
  return x;
}

// Three face points spread over the mesh and one used interior vertex from
// the middle of the vertex list.
inline std::vector<SurfacePoint> some_points(const Mesh& mesh) {
  std::vector<SurfacePoint> pts;
  for (int f : {3, static_cast<int>(mesh.F.rows()) / 2, static_cast<int>(mesh.F.rows()) - 20})
    pts.push_back(SurfacePoint::in_face(f, Eigen::Vector3d(0.2, 0.5, 0.3)));
  for (int v = static_cast<int>(mesh.V.rows()) / 3; v < mesh.V.rows(); ++v)
    if (!mesh.topology.is_boundary[v] && mesh.topology.is_used[v]) {
      pts.push_back(SurfacePoint::at_vertex(v));
      break;
    }
  return pts;
}

// `f()` must throw an intrinsic::Error of `kind` whose message contains
// `fragment`.
template <class F>
void expect_error(F&& f, ErrorKind kind, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one containing '" << fragment << "'";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), kind) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

}  // namespace intrinsic::test
