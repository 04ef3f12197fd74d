// An interactive editing session, the per-tab solve engine of `intrinsic
// serve` (edit_session.h).
#include "intrinsic/edit_session.h"

#include <chrono>

#include <nlohmann/json.hpp>

#include "intrinsic/error.h"
#include "util/stopwatch.h"

namespace intrinsic {
using detail::ms_since;
namespace {

// What must be equal for a request to reuse the session's factorization:
// everything but the moves, the constraints, the pin positions and whether
// the fixed boundary is a circle or a square (the same fixed vertices: only
// their positions differ).
std::string options_key(const EditRequest& r, const std::vector<FixedVertex>& pin_list) {
  const WeightOptions& w = r.weights;
  nlohmann::json pins = nlohmann::json::array();
  for (const FixedVertex& p : pin_list) pins.push_back(p.vertex);
  return nlohmann::json{{"method", static_cast<int>(w.method)}, {"lambda", w.lambda}, {"mu", w.mu},
                        {"natural", r.boundary == BoundaryShape::Natural}, {"pins", pins}}
      .dump();
}

// The answer's path when one request takes several steps: the costliest.
std::string costlier(const std::string& a, const std::string& b) {
  auto rank = [](const std::string& p) { return p == "constraints" ? 2 : p == "resolve" ? 1 : 0; };
  return rank(a) >= rank(b) ? a : b;
}

// The same rows (vertices and weights) as the kept ones: only targets differ.
bool same_rows(const std::vector<LinearConstraint>& a, const std::vector<LinearConstraint>& b) {
  if (a.empty() || a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); ++k)
    if (a[k].terms != b[k].terms) return false;
  return true;
}

ParamOptions to_param_options(const EditRequest& r) {
  ParamOptions o;
  o.weights = r.weights;
  o.boundary = r.boundary;
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
  has_shape_ = false;
  base_.clear();
  base_index_.clear();
  moved_.clear();
}

EditAnswer EditSession::solve(const EditRequest& request) {
  // Natural map without pins: the default pins where the library placed
  // them, once known. The same map (it is unique for given pin positions),
  // and the session's editor then serves requests with and without pins.
  EditRequest with_pins;
  const bool fill = request.boundary == BoundaryShape::Natural && request.pins.empty() && !default_pins_.empty();
  if (fill) {
    with_pins = request;
    with_pins.pins = default_pins_;
  }
  const EditRequest& r = fill ? with_pins : request;
  const std::string key = options_key(r, r.pins);
  try {
    EditAnswer a;
    if (key != key_ || !parameterizer_) {
      a = rebuild(r, key);
    } else {
      const auto t0 = std::chrono::steady_clock::now();
      const std::string path = r.constraints_key == constraints_key_ ? "" : update_constraints(r);
      a = r.boundary == BoundaryShape::Natural ? move_pins(r) : move_fixed(r);
      if (!path.empty()) {
        a.path = costlier(path, a.path);
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

std::vector<FixedVertex> EditSession::boundary_after(const EditRequest& r) {
  if (r.boundary == BoundaryShape::Natural) throw_usage("the natural map has no fixed boundary");
  solve(r);
  return editor_->boundary();
}

// Same factorization, other constraints. New targets for the same rows go
// through the editor's target responses ("responses", or "resolve" when
// many move at once). Other rows: the editor's responses depend on the rows
// (they keep them met), so it starts again from the Parameterizer's current
// boundary ("constraints"): the moves carry over.
std::string EditSession::update_constraints(const EditRequest& r) {
  std::vector<LinearConstraint> rows;
  if (!r.constraints.empty()) rows = resolve_constraints(mesh_, r.constraints);
  if (same_rows(rows, parameterizer_->constraints())) {
    std::vector<Eigen::Vector2d> targets;
    for (const LinearConstraint& c : rows) targets.push_back(c.target);
    editor_->move_targets(targets);
    constraints_key_ = r.constraints_key;
    return editor_->last_update().resolved ? "resolve" : "responses";
  }
  editor_.reset();
  parameterizer_->set_constraints(std::move(rows));
  constraints_key_ = r.constraints_key;
  editor_ = std::make_unique<BoundaryEditor>(*parameterizer_);
  if (r.boundary == BoundaryShape::Natural) prepare_pins();
  return "constraints";
}

// Natural map: the pins' responses (two each) computed with the build or
// the constraint change, a click, so that the first pin drag is already a
// superposition.
void EditSession::prepare_pins() {
  std::vector<int> pins;
  for (const FixedVertex& p : parameterizer_->boundary()) pins.push_back(p.vertex);
  editor_->prepare(pins);
}

EditAnswer EditSession::rebuild(const EditRequest& r, const std::string& key) {
  reset();
  const auto t0 = std::chrono::steady_clock::now();
  auto p = std::make_unique<Parameterizer>(mesh_, to_param_options(r));
  if (!r.constraints.empty()) p->set_constraints(r.constraints);
  parameterizer_ = std::move(p);
  editor_ = std::make_unique<BoundaryEditor>(*parameterizer_);
  key_ = key;
  constraints_key_ = r.constraints_key;
  shape_ = r.boundary;
  has_shape_ = true;
  EditAnswer a;
  a.path = "factor";
  if (r.boundary == BoundaryShape::Natural) {
    prepare_pins();
    a.pins = parameterizer_->boundary();
    if (r.pins.empty()) {
      default_pins_ = a.pins;
      key_ = options_key(r, default_pins_);  // what the next request without pins asks for
    }
  } else {
    set_base();
    if (!r.moves.empty()) {
      editor_->move(r.moves);
      for (const FixedVertex& m : r.moves) moved_.push_back(m.vertex);
    }
  }
  a.uv = editor_->uv();
  a.update_ms = ms_since(t0);
  return a;
}

// The Parameterizer's boundary: after set_boundary_shape it is already the
// new shape while the editor still holds the old one.
void EditSession::set_base() {
  base_ = parameterizer_->boundary();
  base_index_.assign(mesh_.V.rows(), -1);
  for (size_t k = 0; k < base_.size(); ++k) base_index_[base_[k].vertex] = static_cast<int>(k);
}

// Moves are absolute positions relative to the base boundary: vertices the
// previous request moved and this one does not list go back to the base.
// Circle <-> square: the Parameterizer places the other shape on the kept
// factorization, and every fixed vertex moves (a re-solve in the editor,
// whose responses stay valid: they do not depend on the positions).
EditAnswer EditSession::move_fixed(const EditRequest& r) {
  const auto t0 = std::chrono::steady_clock::now();
  const bool reshape = !has_shape_ || r.boundary != shape_;
  if (reshape) {
    parameterizer_->set_boundary_shape(r.boundary);
    shape_ = r.boundary;
    has_shape_ = true;
    set_base();
  }
  std::vector<FixedVertex> positions = r.moves;
  std::vector<char> listed(mesh_.V.rows(), 0);
  for (const FixedVertex& m : r.moves) listed[m.vertex] = 1;
  if (reshape) {
    for (const FixedVertex& b : base_)
      if (!listed[b.vertex]) positions.push_back(b);
  } else {
    for (const int v : moved_)
      if (!listed[v]) positions.push_back(base_[base_index_[v]]);
  }
  EditAnswer a;
  if (!positions.empty()) editor_->move(positions);
  moved_.clear();
  for (const FixedVertex& m : r.moves) moved_.push_back(m.vertex);
  a.uv = editor_->uv();
  a.update_ms = positions.empty() ? 0.0 : reshape ? ms_since(t0) : editor_->last_update().ms;
  a.path = !positions.empty() && editor_->last_update().resolved ? "resolve" : "responses";
  return a;
}

// Same pins (the key holds their vertices): the natural map is linear in
// the pin positions, so the editor superposes two responses per moved pin.
// No pins given: the map as built.
EditAnswer EditSession::move_pins(const EditRequest& r) {
  EditAnswer a;
  if (!r.pins.empty()) editor_->move(r.pins);
  a.uv = editor_->uv();
  a.update_ms = r.pins.empty() ? 0.0 : editor_->last_update().ms;
  a.path = !r.pins.empty() && editor_->last_update().resolved ? "resolve" : "responses";
  a.pins = parameterizer_->boundary();
  return a;
}

}  // namespace intrinsic
