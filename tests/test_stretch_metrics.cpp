// What a person sees (docs/maths.md §9.8): summarize_stretch's Sander L2 and
// L-infinity, area-weighted percentiles of max(s1, 1/s2) and mean anisotropy,
// against a formulation written here (another face frame, Eigen's SVD, the
// root mean square by hand, percentiles by brute force), analytic cases and
// invariances; the atlas's own summary; and the `metrics` / `atlas` reports'
// "stretch", seam_length and small_charts.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "intrinsic/atlas.h"
#include "intrinsic/generate.h"
#include "intrinsic/io.h"
#include "intrinsic/metrics.h"
#include "test_support.h"

namespace intrinsic {
namespace {

const double kInf = std::numeric_limits<double>::infinity();

// ---- The reference: per face, a frame built on edge x2 - x0 and the normal,
// the Jacobian inverted through it, singular values by Eigen's JacobiSVD.
struct Reference {
  double sander_l2 = 0, sander_linf = 0, p50 = 0, p95 = 0, p99 = 0, max = 0, anisotropy = 0;
};

Eigen::Vector2d singular_values_ref(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV, int f, double k) {
  const Eigen::Vector3d x0 = V.row(F(f, 0)), x1 = V.row(F(f, 1)), x2 = V.row(F(f, 2));
  const Eigen::Vector3d b1 = (x2 - x0).normalized();
  const Eigen::Vector3d n = (x1 - x0).cross(x2 - x0).normalized();
  const Eigen::Vector3d b2 = n.cross(b1);
  Eigen::Matrix2d X, U;
  X << (x1 - x0).dot(b1), (x2 - x0).dot(b1), (x1 - x0).dot(b2), (x2 - x0).dot(b2);
  U.col(0) = k * (UV.row(F(f, 1)) - UV.row(F(f, 0))).transpose();
  U.col(1) = k * (UV.row(F(f, 2)) - UV.row(F(f, 0))).transpose();
  return Eigen::JacobiSVD<Eigen::Matrix2d>(U * X.inverse()).singularValues();
}

// The smallest per-face value whose faces at or below it hold fraction p of the area, by brute force.
double percentile_ref(const std::vector<double>& value, const std::vector<double>& area, double p) {
  double total = 0;
  for (double a : area) total += a;
  double best = kInf;
  for (double x : value) {
    double below = 0;
    for (size_t g = 0; g < value.size(); ++g)
      if (value[g] <= x) below += area[g];
    if (below >= p * total * (1 - 1e-12) && x < best) best = x;
  }
  return best;
}

// Faces of non-zero area and non-zero UV area only (the cases the reference is used on).
Reference reference(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV) {
  double a3 = 0, a2 = 0;
  std::vector<double> area(F.rows());
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d x0 = V.row(F(f, 0)), x1 = V.row(F(f, 1)), x2 = V.row(F(f, 2));
    Eigen::Matrix2d U;
    U.col(0) = (UV.row(F(f, 1)) - UV.row(F(f, 0))).transpose();
    U.col(1) = (UV.row(F(f, 2)) - UV.row(F(f, 0))).transpose();
    area[f] = 0.5 * (x1 - x0).cross(x2 - x0).norm();
    a3 += area[f];
    a2 += 0.5 * std::abs(U.determinant());
  }
  const double k = std::sqrt(a3 / a2);
  Reference r;
  std::vector<double> stretch(F.rows());
  double sum_l2 = 0, sum_aniso = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector2d s = singular_values_ref(V, F, UV, f, k);
    const double l2 = std::sqrt((1 / (s[0] * s[0]) + 1 / (s[1] * s[1])) / 2);
    sum_l2 += area[f] * l2 * l2;
    sum_aniso += area[f] * s[0] / s[1];
    r.sander_linf = std::max(r.sander_linf, 1 / s[1]);
    stretch[f] = std::max(s[0], 1 / s[1]);
    r.max = std::max(r.max, stretch[f]);
  }
  r.sander_l2 = std::sqrt(sum_l2 / a3);
  r.anisotropy = sum_aniso / a3;
  r.p50 = percentile_ref(stretch, area, 0.5);
  r.p95 = percentile_ref(stretch, area, 0.95);
  r.p99 = percentile_ref(stretch, area, 0.99);
  return r;
}

void expect_close(double a, double b, double rel = 1e-9) { EXPECT_NEAR(a, b, rel * std::max(1.0, std::abs(b))); }

void expect_matches(const StretchSummary& s, const Reference& r, double rel = 1e-9) {
  expect_close(s.sander_l2, r.sander_l2, rel);
  expect_close(s.sander_linf, r.sander_linf, rel);
  expect_close(s.face_stretch_p50, r.p50, rel);
  expect_close(s.face_stretch_p95, r.p95, rel);
  expect_close(s.face_stretch_p99, r.p99, rel);
  expect_close(s.face_stretch_max, r.max, rel);
  expect_close(s.anisotropy_mean, r.anisotropy, rel);
}

void expect_same(const StretchSummary& a, const StretchSummary& b, double rel = 1e-9) {
  expect_close(a.sander_l2, b.sander_l2, rel);
  expect_close(a.sander_linf, b.sander_linf, rel);
  expect_close(a.face_stretch_p50, b.face_stretch_p50, rel);
  expect_close(a.face_stretch_p95, b.face_stretch_p95, rel);
  expect_close(a.face_stretch_p99, b.face_stretch_p99, rel);
  expect_close(a.face_stretch_max, b.face_stretch_max, rel);
  expect_close(a.anisotropy_mean, b.anisotropy_mean, rel);
}

// The wavy patch with UVs its projection onto z = 0 plus noise: uneven
// stretch, every face valid.
struct Layout {
  MatrixX3d V;
  MatrixX3i F;
  MatrixX2d UV;
};
Layout noisy_wave() {
  GenerateOptions g;
  g.rings = 10;
  const MeshData m = generate_wavy_patch(g);
  Layout l{m.V, m.F, m.V.leftCols(2)};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-0.01, 0.01);
  for (Eigen::Index i = 0; i < l.UV.rows(); ++i) l.UV.row(i) += Eigen::RowVector2d(d(rng), d(rng));
  return l;
}

TEST(StretchMetrics, MatchesAnIndependentFormulation) {
  const Layout l = noisy_wave();
  const StretchSummary s = summarize_stretch(l.V, l.F, l.UV);
  EXPECT_EQ(s.faces, l.F.rows());
  EXPECT_EQ(s.collapsed_faces, 0);
  expect_matches(s, reference(l.V, l.F, l.UV));
  // Not the area-weighted mean of the per-face L2 (what stretch_l2.mean is), but at least it.
  EXPECT_GE(s.sander_l2, summarize_distortion(l.V, l.F, l.UV).stretch_l2.mean - 1e-12);
  EXPECT_GE(s.face_stretch_p50, 1.0);
  EXPECT_LE(s.face_stretch_p50, s.face_stretch_p95);
  EXPECT_LE(s.face_stretch_p95, s.face_stretch_p99);
  EXPECT_LE(s.face_stretch_p99, s.face_stretch_max);
}

TEST(StretchMetrics, AnisotropicScaleKnownSingularValues) {
  // Every face of a flat disk mapped by diag(2, 1/2) (area-preserving): s1 = 2, s2 = 1/2.
  GenerateOptions g;
  g.rings = 6;
  const MeshData m = generate_flat_disk(g);
  MatrixX2d UV(m.V.rows(), 2);
  UV.col(0) = 2 * m.V.col(0);
  UV.col(1) = 0.5 * m.V.col(1);
  for (const MatrixX3d& V : {m.V, test::rigid_motion(m.V)}) {
    const StretchSummary s = summarize_stretch(V, m.F, UV);
    expect_close(s.scale_factor, 1);
    expect_close(s.sander_l2, std::sqrt((1 / 4.0 + 4.0) / 2));
    expect_close(s.sander_linf, 2);
    expect_close(s.anisotropy_mean, 4);
    for (double x : {s.face_stretch_p50, s.face_stretch_p95, s.face_stretch_p99, s.face_stretch_max})
      expect_close(x, 2);
  }
}

// Two separate right triangles in z = 0: legs a (area fraction fa of the
// total) with UV = alpha * (x, y), legs b with UV = beta * (x, y).
struct TwoFaces {
  MatrixX3d V{6, 3};
  MatrixX3i F{2, 3};
  MatrixX2d UV{6, 2};
  double k = 1;  // the normalisation the test expects
};
TwoFaces two_faces(double a, double alpha, double b, double beta) {
  TwoFaces t;
  t.V << 0, 0, 0, a, 0, 0, 0, a, 0, 10, 0, 0, 10 + b, 0, 0, 10, b, 0;
  t.F << 0, 1, 2, 3, 4, 5;
  t.UV.topRows(3) = alpha * t.V.topRows(3).leftCols(2);
  t.UV.bottomRows(3) = beta * t.V.bottomRows(3).leftCols(2);
  t.k = std::sqrt((a * a + b * b) / (alpha * alpha * a * a + beta * beta * b * b));
  return t;
}

double stretch_of(double s) { return std::max(s, 1 / s); }  // a uniformly scaled face: s1 = s2 = s

TEST(StretchMetrics, PercentilesPickTheFaceHoldingTheArea) {
  {
    // 90% of the area at scale alpha = 1, 10% at beta = 2.
    const TwoFaces t = two_faces(3, 1, 1, 2);
    const StretchSummary s = summarize_stretch(t.V, t.F, t.UV);
    const double sa = stretch_of(t.k), sb = stretch_of(2 * t.k);
    ASSERT_LT(sa, sb);
    expect_close(s.face_stretch_p50, sa);
    expect_close(s.face_stretch_p95, sb);
    expect_close(s.face_stretch_p99, sb);
    expect_close(s.face_stretch_max, sb);
    expect_close(s.sander_l2, std::sqrt(0.9 / (t.k * t.k) + 0.1 / (4 * t.k * t.k)));
    expect_close(s.sander_linf, 1 / t.k);
    expect_close(s.anisotropy_mean, 1);
    expect_matches(s, reference(t.V, t.F, t.UV));
  }
  {
    // 96% at the lower stretch, 4% at a much higher one: p95 is the lower, p99 the higher.
    const TwoFaces t = two_faces(std::sqrt(0.96), 1, std::sqrt(0.04), 0.1);
    const StretchSummary s = summarize_stretch(t.V, t.F, t.UV);
    const double sa = stretch_of(t.k), sb = stretch_of(0.1 * t.k);
    ASSERT_LT(sa, sb);
    expect_close(s.face_stretch_p50, sa);
    expect_close(s.face_stretch_p95, sa);
    expect_close(s.face_stretch_p99, sb);
    expect_close(s.face_stretch_max, sb);
    expect_close(s.sander_linf, 1 / (0.1 * t.k));
    expect_matches(s, reference(t.V, t.F, t.UV));
  }
}

TEST(StretchMetrics, UnchangedByUvScaleAndRigidMotions) {
  const Layout l = noisy_wave();
  const StretchSummary s = summarize_stretch(l.V, l.F, l.UV);
  MatrixX2d scaled = 37.5 * l.UV;
  scaled.col(0).array() += 3;
  expect_same(summarize_stretch(l.V, l.F, scaled), s);
  expect_same(summarize_stretch(test::rigid_motion(l.V), l.F, l.UV), s);
  MatrixX2d mirrored = l.UV;
  mirrored.col(0) *= -1;  // a mirrored layout: the same texels
  expect_same(summarize_stretch(l.V, l.F, mirrored), s);
  const double c = std::cos(0.8), si = std::sin(0.8);
  Eigen::Matrix2d R;
  R << c, -si, si, c;
  expect_same(summarize_stretch(l.V, l.F, l.UV * R.transpose()), s);
}

TEST(StretchMetrics, CollapsedCountInMaximaAndPercentilesNotInMeans) {
  const TwoFaces t = two_faces(3, 1, 1, 2);
  const StretchSummary base = summarize_stretch(t.V, t.F, t.UV);
  // A third face, of 3D area 2 (of 7 in all), its UVs on one line; a fourth of zero 3D area.
  MatrixX3d V(12, 3);
  MatrixX2d UV(12, 2);
  MatrixX3i F(4, 3);
  V.topRows(6) = t.V;
  V.bottomRows(6) << 20, 0, 0, 22, 0, 0, 20, 2, 0, 30, 0, 0, 31, 0, 0, 32, 0, 0;
  UV.topRows(6) = t.UV;
  UV.bottomRows(6) << 0, 0, 1, 1, 2, 2, 0, 0, 1, 0, 0, 1;  // the degenerate face's UV area must not count
  F << t.F, Eigen::RowVector3i(6, 7, 8), Eigen::RowVector3i(9, 10, 11);
  const StretchSummary s = summarize_stretch(V, F, UV);
  EXPECT_EQ(s.faces, 3);
  EXPECT_EQ(s.collapsed_faces, 1);
  EXPECT_EQ(s.degenerate_faces, 1);
  expect_close(s.scale_factor, base.scale_factor);
  expect_close(s.sander_l2, base.sander_l2);
  expect_close(s.anisotropy_mean, base.anisotropy_mean);
  EXPECT_EQ(s.sander_linf, kInf);
  EXPECT_EQ(s.face_stretch_max, kInf);
  // Area: 4.5 (lower stretch), 0.5 (higher), 2 (infinite) of 7: p50 the lower, p95 and p99 infinite.
  expect_close(s.face_stretch_p50, base.face_stretch_p50);
  EXPECT_EQ(s.face_stretch_p95, kInf);
  EXPECT_EQ(s.face_stretch_p99, kInf);
}

TEST(StretchMetrics, PerCornerUvsReadEachCornersRow) {
  // The two-faces layout with shared position rows: corners point at UV rows.
  const TwoFaces t = two_faces(3, 1, 1, 2);
  MatrixX3i FUV(2, 3);
  FUV << 5, 4, 3, 2, 1, 0;  // UVs listed backwards: face 0 reads rows 5, 4, 3
  MatrixX2d UV(6, 2);
  for (int i = 0; i < 6; ++i) UV.row(5 - i) = t.UV.row(i);
  expect_same(summarize_stretch(t.V, t.F, UV, FUV), summarize_stretch(t.V, t.F, t.UV));
}

// The atlas's own summary: the reference on the output's per-corner soup.
TEST(StretchMetrics, AtlasCarriesItsSummary) {
  GenerateOptions g;
  g.rings = 10;
  const MeshData m = generate_bumpy_sphere(g);
  const AtlasResult r = atlas(m);
  const Eigen::Index n = r.F.rows();
  MatrixX3d P(3 * n, 3);
  MatrixX2d T(3 * n, 2);
  MatrixX3i S(n, 3);
  for (Eigen::Index f = 0; f < n; ++f)
    for (int c = 0; c < 3; ++c) {
      P.row(3 * f + c) = m.V.row(r.F(f, c));
      T.row(3 * f + c) = r.UV.row(r.FUV(f, c));
      S(f, c) = static_cast<int>(3 * f + c);
    }
  expect_matches(r.stretch, reference(P, S, T), 1e-8);
  // All charts at one texel density: the root mean square is at least the mean.
  EXPECT_GE(r.stretch.sander_l2, r.stretch_l2_mean - 1e-9);
}

// ---- The reports -----------------------------------------------------------

const char* const kStretchKeys[] = {"sander_l2",        "sander_linf",      "face_stretch_p50", "face_stretch_p95",
                                    "face_stretch_p99", "face_stretch_max", "anisotropy_mean"};

void expect_stretch_json(const nlohmann::json& j, const StretchSummary& s, double rel) {
  ASSERT_TRUE(j.is_object());
  std::set<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.insert(it.key());
  EXPECT_EQ(keys, std::set<std::string>(std::begin(kStretchKeys), std::end(kStretchKeys)));
  const double values[] = {s.sander_l2,        s.sander_linf,      s.face_stretch_p50, s.face_stretch_p95,
                           s.face_stretch_p99, s.face_stretch_max, s.anisotropy_mean};
  for (int i = 0; i < 7; ++i) expect_close(j[kStretchKeys[i]].get<double>(), values[i], rel);
}

TEST(StretchMetricsCli, MetricsPrintsTheLibrarysFigures) {
  test::TempDir dir;
  ASSERT_EQ(test::run_cli("generate wave --rings 10 -o " + (dir / "wave.obj"), dir).code, 0);
  ASSERT_EQ(test::run_cli("param " + (dir / "wave.obj") + " -o " + (dir / "out.obj") + " -q", dir).code, 0);
  const test::CliResult m = test::run_cli("metrics " + (dir / "out.obj"), dir);
  ASSERT_EQ(m.code, 0) << m.err;
  const nlohmann::json j = nlohmann::json::parse(m.out);
  const MeshData out = read_mesh(dir / "out.obj");
  expect_stretch_json(j["stretch"], summarize_stretch(out.V, out.F, out.TC, out.FTC), 1e-12);
  EXPECT_EQ(j["atlas"]["seam_length"].get<double>(), 0.0);  // one chart: only the mesh's own boundary
  EXPECT_EQ(j["atlas"]["small_charts"], 0);
  EXPECT_EQ(j["atlas"]["small_chart_texels"], 16);
}

TEST(StretchMetricsCli, AtlasReportMatchesMetricsOfItsOutput) {
  test::TempDir dir;
  ASSERT_EQ(test::run_cli("generate sphere --rings 10 -o " + (dir / "s.obj"), dir).code, 0);
  ASSERT_EQ(test::run_cli("atlas " + (dir / "s.obj") + " -o " + (dir / "a.obj") + " --report " + (dir / "a.json") +
                              " -q",
                          dir)
                .code,
            0);
  const nlohmann::json a = nlohmann::json::parse(test::slurp(dir / "a.json"));
  const MeshData out = read_mesh(dir / "a.obj");
  const StretchSummary s = summarize_stretch(out.V, out.F, out.TC, out.FTC);
  expect_stretch_json(a["stretch"], s, 1e-9);  // OBJ digits aside, the atlas's own figures
  const test::CliResult m = test::run_cli("metrics " + (dir / "a.obj"), dir);
  ASSERT_EQ(m.code, 0) << m.err;
  const nlohmann::json j = nlohmann::json::parse(m.out);
  expect_stretch_json(j["stretch"], s, 1e-12);
  expect_close(j["atlas"]["seam_length"].get<double>(), a["seam_length"].get<double>(), 1e-12);
}

TEST(StretchMetricsCli, SeamLengthAndSmallCharts) {
  test::TempDir dir;
  // A unit square, two faces sharing the diagonal (length sqrt 2).
  const std::string v = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  // Shared UVs: no seam. Vertices repeated per face (a soup) with equal UVs: no seam either.
  test::write_text(dir / "joined.obj", v + "vt 0 0\nvt 0.5 0\nvt 0.5 0.5\nvt 0 0.5\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
  test::write_text(dir / "soup.obj", v + v + "vt 0 0\nvt 0.5 0\nvt 0.5 0.5\nvt 0 0.5\nf 1/1 2/2 3/3\nf 5/1 7/3 8/4\n");
  // The second face moved right by 0.5 in UV: the diagonal is a seam; two charts of UV area 1/8.
  test::write_text(dir / "cut.obj",
                   v + "vt 0 0\nvt 0.5 0\nvt 0.5 0.5\nvt 0.5 0\nvt 0.5 0.5\nvt 1 0.5\nf 1/1 2/2 3/3\nf 1/4 3/5 4/6\n");
  auto atlas_of = [&](const std::string& name, const std::string& args) {
    const test::CliResult r = test::run_cli("metrics " + (dir / name) + args, dir);
    EXPECT_EQ(r.code, 0) << r.err;
    return nlohmann::json::parse(r.out)["atlas"];
  };
  EXPECT_EQ(atlas_of("joined.obj", "")["seam_length"].get<double>(), 0.0);
  EXPECT_EQ(atlas_of("soup.obj", "")["seam_length"].get<double>(), 0.0);
  const nlohmann::json cut = atlas_of("cut.obj", "");
  expect_close(cut["seam_length"].get<double>(), std::sqrt(2.0), 1e-15);
  EXPECT_EQ(cut["charts"], 2);
  EXPECT_EQ(cut["small_charts"], 0);  // 1/8 of 1024^2 texels each
  // At 8 x 8 texels each chart covers 8 < 16; at 12 x 12, 18 >= 16.
  EXPECT_EQ(atlas_of("cut.obj", " --resolution 8")["small_charts"], 2);
  EXPECT_EQ(atlas_of("cut.obj", " --resolution 12")["small_charts"], 0);
  // One chart of UV area 1/4: 16 texels at 8 x 8 (not fewer than 16), 12.25 at 7 x 7.
  EXPECT_EQ(atlas_of("joined.obj", " --resolution 8")["small_charts"], 0);
  EXPECT_EQ(atlas_of("joined.obj", " --resolution 7")["small_charts"], 1);
}

}  // namespace
}  // namespace intrinsic
