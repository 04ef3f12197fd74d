// The weight sets of the intrinsic family (paper section 3; docs/maths.md §1)
// and the two earlier methods the paper compares against (Tutte's uniform
// weights, Floater's mean-value coordinates), as per-face contributions.
//
// Every method here is "sum over neighbours j of w_ij (u_i - u_j) = 0" at a
// free vertex i. Each face (i, j, k) contributes to the weight of the ordered
// pair (i -> j); a weight is the sum of the contributions of the (one or two)
// faces on the edge:
//   conformal  cot(angle at k)                         -> cot alpha + cot beta   (eq. 4)
//   authalic   cot(angle at j) / |x_i - x_j|^2         -> (cot gamma + cot delta)/|x_i-x_j|^2 (eq. 6)
//   tutte      1/2                                     -> 1 per interior edge
//   floater    tan(angle at i / 2) / |x_i - x_j|       -> mean-value weights (Floater 2003)
//   mixed      lambda * conformal + mu * authalic      (section 3.4)
#pragma once

#include <string>

#include "intrinsic/choice.h"
#include "intrinsic/mesh.h"

namespace intrinsic {

enum class Method { Conformal, Authalic, Mixed, Tutte, Floater };
template <>
ChoiceTable<Method> choice_table<Method>();

struct WeightOptions {
  Method method = Method::Conformal;
  double lambda = 1.0;  // mixed only
  double mu = 0.0;      // mixed only
};

std::string method_name(Method m);
Method parse_method(const std::string& name);  // throws Error(Usage)

// True when w_ij = w_ji for every mesh (conformal, tutte, mixed with mu = 0):
// the eliminated system is then symmetric and Cholesky applies.
bool is_symmetric(const WeightOptions& w);

// Throws Error(Usage) for weights no map can use: mixed with lambda and mu
// both zero, or a non-finite lambda or mu.
void check_weights(const WeightOptions& w);

// Cotangent of the angle between a and b, as dot over cross norm (no
// trigonometry, no division by a near-zero sine of a small angle's complement).
double cotangent(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

// Contribution of face f to the ordered pairs of its corners:
// out(c, d) for c != d is the contribution to w_{F(f,c) F(f,d)}.
Eigen::Matrix3d face_weights(const MatrixX3d& V, const MatrixX3i& F, int f, const WeightOptions& w);

}  // namespace intrinsic
