// Block elimination of the constrained (augmented) system; see saddle_solve.h.
#include "saddle_solve.h"

#include "intrinsic/error.h"

namespace intrinsic::detail {

void SaddleSolve::set(const Solve& solve, const SparseMatrix& C, const std::vector<std::string>& labels) {
  C_ = C;
  if (C.rows() == 0) { clear(); return; }
  Z_ = solve(Eigen::MatrixXd(C.transpose()));
  const Eigen::MatrixXd S = C * Z_;
  if (!S.allFinite()) throw_numerical("the constrained system has non-finite values (the free system is singular)");
  S_.compute(S);
  // Relative threshold: a row whose pivot is this small next to the largest
  // adds nothing the others do not already say.
  S_.setThreshold(1e-10);
  const int rank = static_cast<int>(S_.rank());
  if (rank < S.rows()) {
    const auto& perm = S_.colsPermutation().indices();
    std::string names;
    const int shown = std::min<int>(static_cast<int>(S.rows()) - rank, 5);
    for (int k = 0; k < shown; ++k) names += (k ? ", " : "") + labels.at(perm[rank + k]);
    if (S.rows() - rank > shown) names += ", ...";
    clear();
    throw_input("the constraints are linearly dependent (" + std::to_string(C.rows() - rank) + " of " +
                std::to_string(C.rows()) + " rows follow from the others); likely redundant: " + names +
                " (too many constraints in one face, or constraints on the same edge)");
  }
}

void SaddleSolve::clear() {
  C_.resize(0, C_.cols());
  Z_.resize(0, 0);
}

Eigen::MatrixXd SaddleSolve::apply(const Eigen::MatrixXd& x0, const Eigen::MatrixXd& T, Eigen::MatrixXd* lambda) const {
  if (C_.rows() == 0) {
    if (lambda) lambda->resize(0, x0.cols());
    return x0;
  }
  const Eigen::MatrixXd l = S_.solve(Eigen::MatrixXd(C_ * x0 - T));
  if (lambda) *lambda = l;
  return x0 - Z_ * l;
}

}  // namespace intrinsic::detail
