// Impulse responses and superposition for realtime boundary editing (paper
// section 4.2; docs/maths.md §6); see boundary_editor.h for the choices.
#include "intrinsic/boundary_editor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "intrinsic/error.h"
#include "core/parameterizer_impl.h"

namespace intrinsic {
namespace {

std::string gib(double bytes) {
  std::ostringstream s;
  s.precision(3);
  s << bytes / double(1 << 30) << " GiB";
  return s.str();
}

}  // namespace

BoundaryEditor::BoundaryEditor(Parameterizer& parameterizer, const EditOptions& options)
    : p_(parameterizer), options_(options) {
  if (p_.impl_->natural)
    throw_usage("the boundary editor works with fixed boundaries and fill or free holes; the natural boundary "
                "and natural holes couple u and v and have no per-vertex responses here");
  const auto t0 = std::chrono::steady_clock::now();
  uv_ = p_.solve().UV;
  const Parameterizer::Impl& s = *p_.impl_;
  UB_ = s.UB;
  if (options_.basis == BasisMode::Full) {
    const double bytes = double(uv_.rows()) * double(UB_.rows()) * sizeof(double);
    if (bytes > double(options_.memory_budget))
      throw_usage("the full response basis needs " + std::to_string(UB_.rows()) + " x " +
                  std::to_string(uv_.rows()) + " doubles = " + gib(bytes) + ", above the memory budget of " +
                  gib(double(options_.memory_budget)) + "; use the lazy basis or raise the budget");
    std::vector<int> all(UB_.rows());
    for (int j = 0; j < UB_.rows(); ++j) all[j] = j;
    compute_responses(all, basis_);
  }
  precompute_ms_ = detail::elapsed_ms(t0);
}

void BoundaryEditor::compute_responses(const std::vector<int>& cols, Eigen::MatrixXd& out) const {
  const Parameterizer::Impl& s = *p_.impl_;
  const int n = static_cast<int>(uv_.rows()), N = s.num_free(), m = static_cast<int>(s.active.size());
  const int k = static_cast<int>(cols.size());
  out.setZero(n, k);
  // Blocks of right-hand sides of at most ~64 MB: multi-column solves run
  // faster per column than single ones, without doubling peak memory.
  const int block = std::max(1, std::min(k, static_cast<int>((64 << 20) / (8 * std::max(N, 1)))));
  for (int j0 = 0; j0 < k; j0 += block) {
    const int kb = std::min(block, k - j0);
    Eigen::MatrixXd R = Eigen::MatrixXd::Zero(N, kb), T = Eigen::MatrixXd::Zero(m, kb);
    for (int j = 0; j < kb; ++j) {
      const int c = cols[j0 + j];
      for (SparseMatrix::InnerIterator it(s.sys->K_IB(), c); it; ++it) R(it.row(), j) = -it.value();
      if (m > 0)
        for (SparseMatrix::InnerIterator it(s.CB, c); it; ++it) T(it.row(), j) = -it.value();
    }
    const Eigen::MatrixXd X = s.solve_linear(R, T);
    for (int v = 0; v < n; ++v)
      if (s.p().free_index[v] >= 0) out.row(v).segment(j0, kb) = X.row(s.p().free_index[v]);
    for (int j = 0; j < kb; ++j) out(s.p().fixed_vertices[cols[j0 + j]], j0 + j) = 1.0;
  }
}

void BoundaryEditor::resolve() {
  const Parameterizer::Impl& s = *p_.impl_;
  uv_ = s.full_uv(s.solve_for(UB_), UB_);
}

const MatrixX2d& BoundaryEditor::move(const std::vector<FixedVertex>& positions) {
  const auto t0 = std::chrono::steady_clock::now();
  const Parameterizer::Impl& s = *p_.impl_;
  Eigen::MatrixXd ub = UB_;
  std::vector<std::pair<int, Eigen::Vector2d>> deltas;  // fixed column, displacement
  std::vector<char> seen(UB_.rows(), 0);
  for (const FixedVertex& fv : positions) {
    const int j = fv.vertex >= 0 && fv.vertex < uv_.rows() ? s.p().fixed_index[fv.vertex] : -1;
    if (j < 0)
      throw_input("vertex " + std::to_string(fv.vertex) + " is not a fixed (boundary) vertex, so it cannot be moved");
    if (!fv.uv.allFinite()) throw_input("non-finite position for vertex " + std::to_string(fv.vertex));
    if (seen[j]) throw_input("vertex " + std::to_string(fv.vertex) + " is moved twice in one update");
    seen[j] = 1;
    const Eigen::Vector2d d = fv.uv - UB_.row(j).transpose();
    if (d.x() == 0 && d.y() == 0) continue;
    deltas.emplace_back(j, d);
    ub.row(j) = fv.uv.transpose();
  }
  s.check_fixed_only(ub);
  UB_ = ub;
  sync_parameterizer();
  last_ = EditStats{};
  last_.moved = static_cast<int>(deltas.size());

  // UV += sum_p b_p d_p^T, in row blocks that stay in cache while every
  // moved vertex's response streams through once (memory-bound otherwise).
  auto superpose = [&](const std::vector<const double*>& responses) {
    constexpr Eigen::Index kBlock = 2048;
    const Eigen::Index n = uv_.rows();
    for (Eigen::Index r0 = 0; r0 < n; r0 += kBlock) {
      const Eigen::Index len = std::min(kBlock, n - r0);
      auto u = uv_.col(0).segment(r0, len);
      auto v = uv_.col(1).segment(r0, len);
      for (size_t k = 0; k < deltas.size(); ++k) {
        const Eigen::Map<const Eigen::VectorXd> b(responses[k] + r0, len);
        u += deltas[k].second.x() * b;
        v += deltas[k].second.y() * b;
      }
    }
  };
  std::vector<const double*> responses;
  if (last_.moved > options_.resolve_above) {
    resolve();
    last_.resolved = true;
  } else if (options_.basis == BasisMode::Full) {
    for (const auto& [j, d] : deltas) responses.push_back(basis_.col(j).data());
    superpose(responses);
  } else {
    std::vector<int> missing;
    for (const auto& [j, d] : deltas)
      if (!lazy_.count(j)) missing.push_back(j);
    const double bytes = double(lazy_.size() + missing.size()) * double(uv_.rows()) * sizeof(double);
    if (static_cast<int>(missing.size()) > options_.resolve_above || bytes > double(options_.memory_budget)) {
      resolve();
      last_.resolved = true;
    } else {
      if (!missing.empty()) {
        Eigen::MatrixXd B;
        compute_responses(missing, B);
        for (size_t k = 0; k < missing.size(); ++k) lazy_[missing[k]] = B.col(static_cast<int>(k));
        last_.new_responses = static_cast<int>(missing.size());
      }
      for (const auto& [j, d] : deltas) responses.push_back(lazy_.at(j).data());
      superpose(responses);
    }
  }
  // The moved vertices themselves sit exactly where they were put.
  for (const auto& [j, d] : deltas) uv_.row(s.p().fixed_vertices[j]) = UB_.row(j);
  last_.ms = detail::elapsed_ms(t0);
  return uv_;
}

// The Parameterizer's boundary follows the editor's: boundary() reports the
// moved positions and a later solve() solves for them.
void BoundaryEditor::sync_parameterizer() {
  Parameterizer::Impl& s = *p_.impl_;
  s.UB = UB_;
  s.update_fixed_list();
  s.have_X = false;
}

std::vector<FixedVertex> BoundaryEditor::boundary() const {
  const Parameterizer::Impl& s = *p_.impl_;
  std::vector<FixedVertex> out(UB_.rows());
  for (int j = 0; j < UB_.rows(); ++j) out[j] = {s.p().fixed_vertices[j], UB_.row(j).transpose()};
  return out;
}

std::size_t BoundaryEditor::basis_bytes() const {
  return static_cast<std::size_t>(basis_.size() + static_cast<Eigen::Index>(lazy_.size()) * uv_.rows()) * sizeof(double);
}

int BoundaryEditor::responses() const {
  return options_.basis == BasisMode::Full ? static_cast<int>(basis_.cols()) : static_cast<int>(lazy_.size());
}

}  // namespace intrinsic
