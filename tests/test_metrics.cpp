// Distortion measures against linear maps whose singular values are known.
#include <gtest/gtest.h>

#include "intrinsic/metrics.h"
#include "test_support.h"

namespace intrinsic {
namespace {

Mesh flat_mesh() {
  GenerateOptions g;
  g.rings = 8;
  g.jitter = 0.5;
  return make_mesh(generate_flat_disk(g));
}

TEST(Metrics, IdentityAndSimilarityHaveNoDistortion) {
  const Mesh mesh = flat_mesh();
  for (double scale : {1.0, 0.01, 37.0}) {
    const MatrixX2d UV = scale * mesh.V.leftCols(2);
    const DistortionSummary s = summarize_distortion(mesh.V, mesh.F, UV);
    EXPECT_EQ(s.flipped_triangles, 0);
    EXPECT_NEAR(s.angle_distortion.max, 1.0, 1e-9);
    EXPECT_NEAR(s.area_distortion.min, 1.0, 1e-9);
    EXPECT_NEAR(s.area_distortion.max, 1.0, 1e-9);
    EXPECT_NEAR(s.stretch_l2.mean, 1.0, 1e-9);
    EXPECT_NEAR(s.stretch_linf.max, 1.0, 1e-9);
    EXPECT_NEAR(s.edge_length_distortion.max, 1.0, 1e-9);
    EXPECT_NEAR(s.edge_length_energy, 0.0, 1e-15 * mesh.F.rows() + 1e-12);
    EXPECT_NEAR(s.area_energy, 0.0, 1e-12);
    EXPECT_NEAR(s.scale_factor, 1 / scale, 1e-9 / scale);
  }
}

TEST(Metrics, AnisotropicStretchHasKnownSingularValues) {
  const Mesh mesh = flat_mesh();
  MatrixX2d UV = mesh.V.leftCols(2);
  UV.col(0) *= 4.0;  // J = diag(4, 1); normalised to diag(2, 0.5)
  const FaceDistortion d = face_distortion(mesh.V, mesh.F, UV);
  for (int f = 0; f < mesh.F.rows(); ++f) {
    EXPECT_NEAR(d.angle[f], 4.0, 1e-9);
    EXPECT_NEAR(d.area[f], 1.0, 1e-9);
  }
  for (int f = 0; f < mesh.F.rows(); ++f) {
    EXPECT_NEAR(d.stretch_linf[f], 2.0, 1e-9);  // 1 / s2
    EXPECT_NEAR(d.stretch_l2[f], std::sqrt(0.5 * (0.25 + 4.0)), 1e-9);
    EXPECT_FALSE(d.flipped[f]);
  }
}

TEST(Metrics, AreaDistortionIsSymmetricInGrowthAndShrinkage) {
  // Two separate unit right triangles; the first is doubled in size (area x4)
  // in the plane, the second kept. Normalising total area (5 -> 2) gives area
  // ratios 1.6 and 0.4, reported as 1.6 and 2.5.
  MatrixX3d V(6, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 0, 0, 6, 0, 0, 5, 1, 0;
  MatrixX3i F(2, 3);
  F << 0, 1, 2, 3, 4, 5;
  MatrixX2d UV = V.leftCols(2);
  UV.topRows(3) *= 2.0;
  const FaceDistortion d = face_distortion(V, F, UV);
  EXPECT_NEAR(d.area[0], 1.6, 1e-12);
  EXPECT_NEAR(d.area[1], 2.5, 1e-12);
  EXPECT_NEAR(d.angle[0], 1.0, 1e-12);
  const DistortionSummary s = summarize_distortion(V, F, UV);
  EXPECT_NEAR(s.area_distortion.min, 1.6, 1e-12);
  EXPECT_NEAR(s.area_distortion.max, 2.5, 1e-12);
  EXPECT_NEAR(s.area_distortion.mean, 0.5 * (1.6 + 2.5), 1e-12);
  EXPECT_NEAR(s.area_energy, 0.6 * 0.6 + 0.6 * 0.6, 1e-12);
}

TEST(Metrics, MirrorFlipsEveryTriangle) {
  const Mesh mesh = flat_mesh();
  MatrixX2d UV = mesh.V.leftCols(2);
  UV.col(1) *= -1;
  EXPECT_EQ(summarize_distortion(mesh.V, mesh.F, UV).flipped_triangles, mesh.F.rows());
  UV = mesh.V.leftCols(2);
  std::swap(UV(mesh.F(0, 0), 0), UV(mesh.F(0, 1), 0));
  std::swap(UV(mesh.F(0, 0), 1), UV(mesh.F(0, 1), 1));
  EXPECT_GE(summarize_distortion(mesh.V, mesh.F, UV).flipped_triangles, 1);
}

// count_flipped (the editor's drag answers) counts what face_distortion
// marks: every face of a mirror image, none of the identity, and on a map
// with a few vertices moved across their neighbours the same faces, counted
// here by hand from the signed UV areas.
TEST(Metrics, CountFlippedEqualsFaceDistortion) {
  const Mesh mesh = flat_mesh();
  const FaceFrames frames = face_frames(mesh.V, mesh.F);
  MatrixX2d UV = mesh.V.leftCols(2);
  EXPECT_EQ(count_flipped(frames, mesh.F, UV), 0);
  UV.col(1) *= -1;
  EXPECT_EQ(count_flipped(frames, mesh.F, UV), mesh.F.rows());
  UV = mesh.V.leftCols(2);
  for (int v = 0; v < UV.rows(); v += 7) UV.row(v) = UV.row((v + 3) % UV.rows());
  int by_hand = 0;
  for (int f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector2d a = UV.row(mesh.F(f, 0)), b = UV.row(mesh.F(f, 1)), c = UV.row(mesh.F(f, 2));
    by_hand += (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x() > 0 ? 0 : 1;
  }
  const FaceDistortion d = face_distortion(frames, mesh.F, UV);
  int marked = 0;
  for (const bool x : d.flipped) marked += x ? 1 : 0;
  EXPECT_GT(by_hand, 0);
  EXPECT_EQ(marked, by_hand);
  EXPECT_EQ(count_flipped(frames, mesh.F, UV), by_hand);
}

TEST(Metrics, EnergiesMatchDefinitionsByHand) {
  MatrixX3d V(3, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  MatrixX3i F(1, 3);
  F << 0, 1, 2;
  MatrixX2d UV(3, 2);
  UV << 0, 0, 2, 0, 0, 1;  // squared length ratios: 4/1, 5/2, 1/1
  EXPECT_NEAR(edge_length_energy(V, F, UV), 9.0 + 2.25 + 0.0, 1e-14);
  EXPECT_NEAR(area_energy(V, F, UV), 1.0, 1e-14);  // area ratio 2
  EXPECT_EQ(unique_edges(F).rows(), 3);
}

}  // namespace
}  // namespace intrinsic
