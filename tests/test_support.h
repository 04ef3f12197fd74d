// Shared helpers for the tests: small meshes built in code, rigid motions,
// and access to the shared real meshes (a missing mesh fails the test).
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "intrinsic/generate.h"
#include "intrinsic/topology.h"

namespace intrinsic::test {

inline std::string shared_mesh(const std::string& name) { return std::string(INTRINSIC_SHARED_MESHES) + "/" + name; }

inline MatrixX3d rigid_motion(const MatrixX3d& V) {
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) * Eigen::AngleAxisd(-1.9, Eigen::Vector3d::UnitZ()))
          .toRotationMatrix();
  MatrixX3d W = (V * R.transpose()).rowwise() + Eigen::RowVector3d(10.5, -3.25, 7.0);
  return W;
}

inline double diameter(const MatrixX2d& UV) {
  return (UV.colwise().maxCoeff() - UV.colwise().minCoeff()).norm();
}

inline double diameter3(const MatrixX3d& V) {
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

}  // namespace intrinsic::test
