// Responses and superposition for realtime editing of the fixed positions
// and the constraint targets (paper section 4.2; docs/maths.md §6); see
// boundary_editor.h for the choices.
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
  const auto t0 = std::chrono::steady_clock::now();
  uv_ = p_.solve().UV;
  const Parameterizer::Impl& s = *p_.impl_;
  UB_ = s.UB;
  width_ = s.natural ? 2 : 1;
  if (options_.basis == BasisMode::Full) {
    const double bytes = double(width_) * double(uv_.rows()) * double(UB_.rows()) * sizeof(double);
    if (bytes > double(options_.memory_budget))
      throw_usage("the full response basis needs " + std::to_string(UB_.rows()) + " x " +
                  std::to_string(width_ * uv_.rows()) + " doubles = " + gib(bytes) + ", above the memory budget of " +
                  gib(double(options_.memory_budget)) + "; use the lazy basis or raise the budget");
    std::vector<int> all(UB_.rows());
    for (int j = 0; j < UB_.rows(); ++j) all[j] = j;
    compute_responses(Source::Fixed, all, basis_);
  }
  precompute_ms_ = detail::elapsed_ms(t0);
}

// Fixed column c: right-hand side -K_IB e_c, targets -C_B e_c, and 1 at the
// fixed unknown itself. Target column c: zero right-hand side, target e_c.
// Rows of `out`: the unknowns of the original vertices (u, then v in the
// natural layout); filled-hole centres are dropped.
void BoundaryEditor::compute_responses(Source source, const std::vector<int>& cols, Eigen::MatrixXd& out) const {
  const Parameterizer::Impl& s = *p_.impl_;
  const int rows = width_ * static_cast<int>(uv_.rows()), N = s.num_free(), mt = static_cast<int>(s.CB.rows());
  const int k = static_cast<int>(cols.size());
  out.setZero(rows, k);
  // Blocks of right-hand sides of at most ~64 MB: multi-column solves run
  // faster per column than single ones, without doubling peak memory.
  const int block = std::max(1, std::min(k, static_cast<int>((64 << 20) / (8 * std::max(N, 1)))));
  for (int j0 = 0; j0 < k; j0 += block) {
    const int kb = std::min(block, k - j0);
    Eigen::MatrixXd R = Eigen::MatrixXd::Zero(N, kb), T = Eigen::MatrixXd::Zero(mt, kb);
    for (int j = 0; j < kb; ++j) {
      const int c = cols[j0 + j];
      if (source == Source::Target) {
        T(c, j) = 1.0;
        continue;
      }
      for (SparseMatrix::InnerIterator it(s.sys->K_IB(), c); it; ++it) R(it.row(), j) = -it.value();
      if (mt > 0)
        for (SparseMatrix::InnerIterator it(s.CB, c); it; ++it) T(it.row(), j) = -it.value();
    }
    const Eigen::MatrixXd X = s.solve_linear(R, T);
    for (int i = 0; i < rows; ++i)
      if (s.p().free_index[i] >= 0) out.row(i).segment(j0, kb) = X.row(s.p().free_index[i]);
    if (source == Source::Fixed)
      for (int j = 0; j < kb; ++j) out(s.p().fixed_vertices[cols[j0 + j]], j0 + j) = 1.0;
  }
}

const double* BoundaryEditor::response(Source source, int column) const {
  if (source == Source::Target) return targets_.at(column).data();
  return options_.basis == BasisMode::Full ? basis_.col(column).data() : lazy_.at(column).data();
}

// Computes the lazy responses `changes` lack; false when that would be more
// than resolve_above inputs or exceed the memory budget (then: re-solve).
bool BoundaryEditor::ensure_responses(Source source, const std::vector<Change>& changes) {
  if (source == Source::Fixed && options_.basis == BasisMode::Full) return true;
  std::unordered_map<int, Eigen::VectorXd>& cache = source == Source::Fixed ? lazy_ : targets_;
  std::vector<int> missing;
  int inputs = 0;
  for (const Change& c : changes) {
    const size_t before = missing.size();
    for (const int col : {c.cu, c.cv})
      if (!cache.count(col) && std::find(missing.begin(), missing.end(), col) == missing.end()) missing.push_back(col);
    if (missing.size() > before) ++inputs;
  }
  const double held = double(lazy_.size() + targets_.size() + missing.size());
  if (inputs > options_.resolve_above || held * width_ * double(uv_.rows()) * sizeof(double) > double(options_.memory_budget))
    return false;
  if (missing.empty()) return true;
  Eigen::MatrixXd B;
  compute_responses(source, missing, B);
  for (size_t k = 0; k < missing.size(); ++k) cache[missing[k]] = B.col(static_cast<int>(k));
  last_.new_responses = static_cast<int>(missing.size());
  return true;
}

// UV += sum of response * displacement, in row blocks that stay in cache
// while every response streams through once (memory-bound otherwise). Fixed
// layout: u += d_u b, v += d_v b. Natural: the u column's response moves u
// (its first #V rows) and v (the next #V) by d_u, the v column's by d_v.
void BoundaryEditor::superpose(Source source, const std::vector<Change>& changes) {
  struct Term {
    const double* r;
    double w;
    int out;
  };
  const Eigen::Index n = uv_.rows();
  std::vector<Term> terms;
  for (const Change& c : changes) {
    const double *ru = response(source, c.cu), *rv = response(source, c.cv);
    if (width_ == 1) {
      terms.push_back({ru, c.d.x(), 0});
      terms.push_back({ru, c.d.y(), 1});
    } else {
      terms.push_back({ru, c.d.x(), 0});
      terms.push_back({ru + n, c.d.x(), 1});
      terms.push_back({rv, c.d.y(), 0});
      terms.push_back({rv + n, c.d.y(), 1});
    }
  }
  constexpr Eigen::Index kBlock = 2048;
  for (Eigen::Index r0 = 0; r0 < n; r0 += kBlock) {
    const Eigen::Index len = std::min(kBlock, n - r0);
    for (const Term& t : terms) {
      if (t.w == 0) continue;
      uv_.col(t.out).segment(r0, len) += t.w * Eigen::Map<const Eigen::VectorXd>(t.r + r0, len);
    }
  }
}

void BoundaryEditor::apply(Source source, const std::vector<Change>& changes) {
  last_.moved = static_cast<int>(changes.size());
  if (changes.empty()) return;
  if (last_.moved > options_.resolve_above || !ensure_responses(source, changes)) {
    resolve();
    last_.resolved = true;
    return;
  }
  superpose(source, changes);
}

void BoundaryEditor::resolve() {
  const Parameterizer::Impl& s = *p_.impl_;
  uv_ = s.full_uv(s.solve_for(UB_), UB_);
}

const MatrixX2d& BoundaryEditor::move(const std::vector<FixedVertex>& positions) {
  const auto t0 = std::chrono::steady_clock::now();
  const Parameterizer::Impl& s = *p_.impl_;
  const int n = static_cast<int>(uv_.rows());
  Eigen::MatrixXd ub = UB_;
  std::vector<Change> changes;
  std::vector<int> moved;
  std::vector<char> seen(UB_.rows(), 0);
  for (const FixedVertex& fv : positions) {
    const int j = fv.vertex >= 0 && fv.vertex < n ? s.p().fixed_index[fv.vertex] : -1;
    if (j < 0)
      throw_input("vertex " + std::to_string(fv.vertex) + " is not a fixed (" +
                  (s.natural_boundary ? "pinned" : "boundary") + ") vertex, so it cannot be moved");
    if (!fv.uv.allFinite()) throw_input("non-finite position for vertex " + std::to_string(fv.vertex));
    if (seen[j]) throw_input("vertex " + std::to_string(fv.vertex) + " is moved twice in one update");
    seen[j] = 1;
    const Eigen::Vector2d d = fv.uv - s.fixed_uv(UB_, fv.vertex);
    if (d.x() == 0 && d.y() == 0) continue;
    changes.push_back({j, width_ == 2 ? s.p().fixed_index[n + fv.vertex] : j, d});
    moved.push_back(fv.vertex);
    s.set_fixed_uv(ub, fv.vertex, fv.uv);
  }
  s.check_fixed_only(ub);
  UB_ = ub;
  sync_parameterizer();
  last_ = EditStats{};
  apply(Source::Fixed, changes);
  // The moved vertices themselves sit exactly where they were put.
  for (const int v : moved) uv_.row(v) = s.fixed_uv(UB_, v).transpose();
  last_.ms = detail::elapsed_ms(t0);
  return uv_;
}

void BoundaryEditor::prepare(const std::vector<int>& vertices) {
  const Parameterizer::Impl& s = *p_.impl_;
  const int n = static_cast<int>(uv_.rows());
  std::vector<Change> changes;
  for (const int v : vertices) {
    const int j = v >= 0 && v < n ? s.p().fixed_index[v] : -1;
    if (j < 0) throw_input("vertex " + std::to_string(v) + " is not a fixed vertex, so it has no response");
    changes.push_back({j, width_ == 2 ? s.p().fixed_index[n + v] : j, Eigen::Vector2d::Zero()});
  }
  ensure_responses(Source::Fixed, changes);
}

// Only rows with free terms enter the system; the others are checked
// against the boundary by set_constraint_targets and move nothing.
const MatrixX2d& BoundaryEditor::move_targets(const std::vector<Eigen::Vector2d>& targets) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<Eigen::Vector2d> old;
  for (const LinearConstraint& c : p_.constraints()) old.push_back(c.target);
  p_.set_constraint_targets(targets);  // validates (and keeps the old targets on failure)
  const Parameterizer::Impl& s = *p_.impl_;
  last_ = EditStats{};
  std::vector<Change> changes;
  const int m = static_cast<int>(s.active.size());
  for (int r = 0; r < m; ++r) {
    const Eigen::Vector2d d = targets[s.active[r]] - old[s.active[r]];
    if (d.x() == 0 && d.y() == 0) continue;
    changes.push_back({r, width_ == 2 ? m + r : r, d});
  }
  apply(Source::Target, changes);
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
  std::vector<FixedVertex> out;
  for (const int v : s.p().fixed_vertices)
    if (width_ == 1 || v < uv_.rows()) out.push_back({v, s.fixed_uv(UB_, v)});
  return out;
}

std::size_t BoundaryEditor::basis_bytes() const {
  const Eigen::Index held = static_cast<Eigen::Index>(lazy_.size() + targets_.size()) * width_ * uv_.rows();
  return static_cast<std::size_t>(basis_.size() + held) * sizeof(double);
}

int BoundaryEditor::responses() const {
  return options_.basis == BasisMode::Full ? static_cast<int>(basis_.cols()) : static_cast<int>(lazy_.size());
}

// How the command line, Python and the reports spell these (intrinsic/choice.h).
template <>
ChoiceTable<BasisMode> choice_table<BasisMode>() {
  static const Choice<BasisMode> rows[] = {{BasisMode::Full, "full"}, {BasisMode::Lazy, "lazy"}};
  return make_choice_table(rows);
}

}  // namespace intrinsic
