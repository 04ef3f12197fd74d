// The per-tab solve engine of `intrinsic serve` (edit_session.h).
#include "serve/edit_session.h"

#include <chrono>

#include <nlohmann/json.hpp>

#include "intrinsic/error.h"

namespace intrinsic::app {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// What must be equal for a request to reuse the session's factorization:
// everything but the moves, the constraints and (natural map) the pin positions.
std::string options_key(const SolveRequest& r) {
  const WeightOptions w = r.weights.options();
  nlohmann::json pins = nlohmann::json::array();
  for (const FixedVertex& p : r.pins) pins.push_back(p.vertex);
  return nlohmann::json{{"method", static_cast<int>(w.method)}, {"lambda", w.lambda}, {"mu", w.mu},
                        {"boundary", r.boundary}, {"pins", pins}}
      .dump();
}

// The same rows (vertices and weights) as the kept ones: only targets differ.
bool same_rows(const std::vector<LinearConstraint>& a, const std::vector<LinearConstraint>& b) {
  if (a.empty() || a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); ++k)
    if (a[k].terms != b[k].terms) return false;
  return true;
}

ParamOptions to_param_options(const SolveRequest& r) {
  ParamOptions o;
  o.weights = r.weights.options();
  o.boundary = r.boundary == "square"    ? BoundaryShape::Square
               : r.boundary == "natural" ? BoundaryShape::Natural
                                         : BoundaryShape::Circle;
  o.pins = r.pins;
  return o;
}

}  // namespace

EditSession::~EditSession() { reset(); }

void EditSession::reset() {
  editor_.reset();
  parameterizer_.reset();
  key_.clear();
  constraints_key_.clear();
  base_.clear();
  base_index_.clear();
  moved_.clear();
}

SolveAnswer EditSession::solve(const SolveRequest& r) {
  const std::string key = options_key(r);
  try {
    SolveAnswer a;
    if (key != key_ || !parameterizer_) {
      a = rebuild(r, key);
    } else {
      const auto t0 = std::chrono::steady_clock::now();
      const std::string path = r.constraints_key == constraints_key_ ? "" : update_constraints(r);
      a = r.boundary == "natural" ? move_pins(r) : move_fixed(r);
      if (!path.empty()) {
        a.path = path;
        a.update_ms = ms_since(t0);
      }
    }
    a.factorizations = parameterizer_->factorizations();
    return a;
  } catch (...) {
    reset();  // a failed update may leave the editor half-moved: start again next time
    throw;
  }
}

std::vector<FixedVertex> EditSession::boundary_after(const SolveRequest& r) {
  if (r.boundary == "natural") throw_usage("the natural map has no fixed boundary");
  solve(r);
  return editor_->boundary();
}

// Same factorization, other constraints. The editor's responses depend on
// the constraint rows (they keep the rows met), so it starts again from the
// Parameterizer's current boundary: the moves carry over.
std::string EditSession::update_constraints(const SolveRequest& r) {
  editor_.reset();
  std::vector<LinearConstraint> rows;
  if (!r.constraints.empty()) rows = resolve_constraints(mesh_, r.constraints);
  std::string path = "constraints";
  if (same_rows(rows, parameterizer_->constraints())) {
    std::vector<Eigen::Vector2d> targets;
    for (const LinearConstraint& c : rows) targets.push_back(c.target);
    parameterizer_->set_constraint_targets(targets);
    path = "targets";
  } else {
    parameterizer_->set_constraints(std::move(rows));
  }
  constraints_key_ = r.constraints_key;
  if (r.boundary != "natural") editor_ = std::make_unique<BoundaryEditor>(*parameterizer_);
  return path;
}

SolveAnswer EditSession::rebuild(const SolveRequest& r, const std::string& key) {
  reset();
  const auto t0 = std::chrono::steady_clock::now();
  auto p = std::make_unique<Parameterizer>(mesh_, to_param_options(r));
  if (!r.constraints.empty()) p->set_constraints(r.constraints);
  SolveAnswer a;
  a.path = "factor";
  if (r.boundary == "natural") {
    a.uv = p->solve().UV;
    a.pins = p->boundary();
    parameterizer_ = std::move(p);
    key_ = key;
    constraints_key_ = r.constraints_key;
    a.update_ms = ms_since(t0);
    return a;
  }
  parameterizer_ = std::move(p);
  editor_ = std::make_unique<BoundaryEditor>(*parameterizer_);
  base_ = editor_->boundary();
  base_index_.assign(mesh_.V.rows(), -1);
  for (size_t k = 0; k < base_.size(); ++k) base_index_[base_[k].vertex] = static_cast<int>(k);
  key_ = key;
  constraints_key_ = r.constraints_key;
  if (!r.moves.empty()) {
    editor_->move(r.moves);
    for (const FixedVertex& m : r.moves) moved_.push_back(m.vertex);
  }
  a.uv = editor_->uv();
  a.update_ms = ms_since(t0);
  return a;
}

// Moves are absolute positions relative to the base boundary: vertices the
// previous request moved and this one does not list go back to the base.
SolveAnswer EditSession::move_fixed(const SolveRequest& r) {
  std::vector<FixedVertex> positions = r.moves;
  std::vector<char> listed(mesh_.V.rows(), 0);
  for (const FixedVertex& m : r.moves) listed[m.vertex] = 1;
  for (const int v : moved_)
    if (!listed[v]) positions.push_back(base_[base_index_[v]]);
  SolveAnswer a;
  if (!positions.empty()) editor_->move(positions);
  moved_.clear();
  for (const FixedVertex& m : r.moves) moved_.push_back(m.vertex);
  a.uv = editor_->uv();
  a.update_ms = positions.empty() ? 0.0 : editor_->last_update().ms;
  a.path = !positions.empty() && editor_->last_update().resolved ? "resolve" : "responses";
  return a;
}

// Same pins (the key holds their vertices): a new right-hand side, no
// refactorization. No pins given: the map as built.
SolveAnswer EditSession::move_pins(const SolveRequest& r) {
  const auto t0 = std::chrono::steady_clock::now();
  SolveAnswer a;
  a.uv = r.pins.empty() ? parameterizer_->solve().UV : parameterizer_->solve_with_boundary(r.pins).UV;
  a.update_ms = ms_since(t0);
  a.path = "resolve";
  a.pins = parameterizer_->boundary();
  return a;
}

}  // namespace intrinsic::app
