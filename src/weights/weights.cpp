// Per-face weight contributions for each method (paper eqs. 4 and 6; Floater
// 2003 for mean-value coordinates). Kept apart from assembly so a new weight
// is one small function.
#include "intrinsic/weights.h"

#include <cmath>

#include "intrinsic/error.h"
#include "intrinsic/choice.h"

namespace intrinsic {

std::string method_name(Method m) { return choice_name(m); }

Method parse_method(const std::string& name) { return parse_choice<Method>(name, "method"); }

void check_weights(const WeightOptions& w) {
  if (w.method == Method::Mixed && w.lambda == 0 && w.mu == 0)
    throw_usage("mixed method needs lambda and mu not both zero");
  if (!std::isfinite(w.lambda) || !std::isfinite(w.mu)) throw_usage("lambda and mu must be finite");
}

bool is_symmetric(const WeightOptions& w) {
  switch (w.method) {
    case Method::Conformal:
    case Method::Tutte: return true;
    case Method::Mixed: return w.mu == 0.0;
    default: return false;
  }
}

double cotangent(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return a.dot(b) / a.cross(b).norm();
}

namespace {

// Cotangent of the interior angle at corner c of face f.
double corner_cot(const MatrixX3d& V, const MatrixX3i& F, int f, int c) {
  const Eigen::Vector3d x = V.row(F(f, c));
  const Eigen::Vector3d a = V.row(F(f, (c + 1) % 3)).transpose() - x;
  const Eigen::Vector3d b = V.row(F(f, (c + 2) % 3)).transpose() - x;
  return cotangent(a, b);
}

}  // namespace

Eigen::Matrix3d face_weights(const MatrixX3d& V, const MatrixX3i& F, int f, const WeightOptions& w) {
  Eigen::Matrix3d out = Eigen::Matrix3d::Zero();
  double cot[3];
  for (int c = 0; c < 3; ++c) cot[c] = corner_cot(V, F, f, c);
  auto sq_length = [&](int c, int d) { return (V.row(F(f, c)) - V.row(F(f, d))).squaredNorm(); };
  for (int c = 0; c < 3; ++c)
    for (int d = 0; d < 3; ++d) {
      if (c == d) continue;
      const int k = 3 - c - d;  // the third corner
      const double conformal = cot[k];
      const double authalic = cot[d] / sq_length(c, d);
      switch (w.method) {
        case Method::Conformal: out(c, d) = conformal; break;
        case Method::Authalic: out(c, d) = authalic; break;
        case Method::Mixed: out(c, d) = w.lambda * conformal + w.mu * authalic; break;
        case Method::Tutte: out(c, d) = 0.5; break;
        case Method::Floater: {
          // tan(theta/2) = sin/(1+cos) = 1/(cot + csc), with csc = sqrt(1+cot^2)
          const double half_tan = 1.0 / (cot[c] + std::sqrt(1.0 + cot[c] * cot[c]));
          out(c, d) = half_tan / std::sqrt(sq_length(c, d));
          break;
        }
      }
    }
  return out;
}

// How the command line, Python and the reports spell these (intrinsic/choice.h).
template <>
ChoiceTable<Method> choice_table<Method>() {
  static const Choice<Method> rows[] = {{Method::Conformal, "conformal"},
                                        {Method::Authalic, "authalic"},
                                        {Method::Mixed, "mixed"},
                                        {Method::Tutte, "tutte"},
                                        {Method::Floater, "floater"}};
  return make_choice_table(rows);
}

}  // namespace intrinsic
