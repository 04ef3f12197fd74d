// Weight sets against hand-computed values, and matrix invariants (rows sum
// to zero; conformal symmetric, authalic not).
#include <gtest/gtest.h>

#include "weights/assemble.h"
#include "intrinsic/weights.h"
#include "test_support.h"

namespace intrinsic {
namespace {

TEST(Weights, RightTriangleByHand) {
  MatrixX3d V(3, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0;  // right angle at 0, 45 degrees at 1 and 2
  MatrixX3i F(1, 3);
  F << 0, 1, 2;
  WeightOptions w;
  w.method = Method::Conformal;
  Eigen::Matrix3d C = face_weights(V, F, 0, w);
  EXPECT_NEAR(C(0, 1), 1.0, 1e-15);  // cot(angle at 2) = cot 45
  EXPECT_NEAR(C(1, 2), 0.0, 1e-15);  // cot(angle at 0) = cot 90
  EXPECT_NEAR(C(0, 2), 1.0, 1e-15);
  EXPECT_NEAR(C(2, 1), C(1, 2), 1e-15);
  w.method = Method::Authalic;
  Eigen::Matrix3d A = face_weights(V, F, 0, w);
  EXPECT_NEAR(A(0, 1), 1.0, 1e-15);  // cot(angle at 1) / |x0-x1|^2
  EXPECT_NEAR(A(1, 0), 0.0, 1e-15);  // cot(angle at 0) / 1
  EXPECT_NEAR(A(1, 2), 0.5, 1e-15);  // cot(angle at 2) / 2
  EXPECT_NEAR(A(2, 1), 0.5, 1e-15);
  EXPECT_NEAR(A(0, 2), 1.0, 1e-15);
  EXPECT_NEAR(A(2, 0), 0.0, 1e-15);
  w.method = Method::Floater;
  Eigen::Matrix3d M = face_weights(V, F, 0, w);
  EXPECT_NEAR(M(0, 1), std::tan(M_PI / 4), 1e-15);          // tan(90/2) / 1
  EXPECT_NEAR(M(1, 0), std::tan(M_PI / 8), 1e-15);          // tan(45/2) / 1
  EXPECT_NEAR(M(1, 2), std::tan(M_PI / 8) / std::sqrt(2), 1e-15);
  w.method = Method::Mixed;
  w.lambda = 2;
  w.mu = -0.5;
  Eigen::Matrix3d X = face_weights(V, F, 0, w);
  EXPECT_NEAR(X(1, 2), 2 * 0.0 - 0.5 * 0.5, 1e-15);
}

TEST(Weights, RegularHexagonOneRing) {
  // Centre vertex 0 with six unit neighbours: every angle is 60 degrees.
  MatrixX3d V(7, 3);
  V.row(0).setZero();
  MatrixX3i F(6, 3);
  for (int k = 0; k < 6; ++k) {
    V.row(k + 1) << std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0;
    F.row(k) << 0, k + 1, (k + 1) % 6 + 1;
  }
  for (Method m : {Method::Conformal, Method::Authalic}) {
    WeightOptions w;
    w.method = m;
    const SparseMatrix K = assemble_weight_matrix(V, F, w);
    for (int j = 1; j <= 6; ++j) EXPECT_NEAR(K.coeff(0, j), -2 / std::sqrt(3.0), 1e-14) << method_name(m);
    EXPECT_NEAR(K.coeff(0, 0), 12 / std::sqrt(3.0), 1e-13);
  }
}

TEST(Weights, RowsSumToZeroAndSymmetry) {
  const Mesh mesh = test::wavy(10);
  for (Method m : {Method::Conformal, Method::Authalic, Method::Mixed, Method::Tutte, Method::Floater}) {
    WeightOptions w;
    w.method = m;
    w.lambda = 0.4;
    w.mu = 0.6;
    const SparseMatrix K = assemble_weight_matrix(mesh.V, mesh.F, w);
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(K.cols());
    EXPECT_LT((K * ones).cwiseAbs().maxCoeff(), 1e-10 * Eigen::Map<const Eigen::VectorXd>(K.valuePtr(), K.nonZeros()).cwiseAbs().maxCoeff()) << method_name(m);
    const double asym = SparseMatrix(K - SparseMatrix(K.transpose())).norm() / K.norm();
    if (is_symmetric(w)) EXPECT_LT(asym, 1e-14) << method_name(m);
    else EXPECT_GT(asym, 1e-3) << method_name(m) << " should not be symmetric on an irregular mesh";
  }
}

}  // namespace
}  // namespace intrinsic
