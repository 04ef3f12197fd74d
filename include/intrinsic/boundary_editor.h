// Realtime manipulation (paper section 4.2; docs/maths.md §6). The map is
// linear in the fixed positions and affine in the constraint targets, so
// moving fixed vertex p by d_p changes every UV by the response of p times
// d_p, where the response (a "Green function") is the map for p at 1 and
// every other fixed position and every target at 0 (constraints stay met
// under superposition); changing a constraint's target by d_t likewise adds
// the response of that target (the map with that target at 1, all else 0).
// An update is a sum of responses: no solve, no factorization.
//
// Layouts: the fixed boundary (one scalar response per fixed vertex serves
// u and v), and the natural layout of the Parameterizer (natural boundary
// with its pins, or natural holes with the outer loop fixed; docs/maths.md
// §3), where u and v are coupled: two responses per fixed vertex (its u and
// its v unknown), each moving both coordinates. Constraint targets likewise
// have one response per row (fixed layout) or two (natural).
//
// Two bases for the fixed-vertex responses:
//   Full  the paper's: every response precomputed (blocked multi-column
//         solves with the Parameterizer's factorization); memory
//         n_columns x #V doubles, refused above EditOptions::memory_budget.
//   Lazy  a response computed on the first move of its vertex and cached
//         (within the same budget); the precompute is free and memory
//         follows what the user actually drags.
// Target responses are always lazy (computed on a row's first new target).
// Either falls back to one solve with the kept factorization (2 right-hand
// sides) when more than `resolve_above` vertices (or targets) move at once or
// responses would be computed for more than that many: superposing k
// responses costs 2 k #V flops, a solve about the same as k of a few dozen.
#pragma once

#include <cstddef>
#include <cstdint>
#include <unordered_map>

#include "intrinsic/choice.h"
#include "intrinsic/parameterizer.h"

namespace intrinsic {

enum class BasisMode { Full, Lazy };
template <>
ChoiceTable<BasisMode> choice_table<BasisMode>();

struct EditOptions {
  BasisMode basis = BasisMode::Lazy;
  std::size_t memory_budget = std::size_t(2) << 30;  // bytes for responses
  int resolve_above = 64;  // vertices moved at once (or new lazy responses) above which to re-solve
};

struct EditStats {
  double ms = 0;          // time of the update
  int moved = 0;          // fixed vertices (or constraint targets) whose position changed
  int new_responses = 0;  // responses computed during the update (lazy)
  bool resolved = false;  // true: solved with the kept factorization instead of superposing
};

class BoundaryEditor {
 public:
  // Starts from the Parameterizer's current boundary, constraints and map
  // (solving it if needed); keeps a reference to it, which must outlive the
  // editor and not be changed by others while the editor is used. Each move
  // updates the Parameterizer's boundary() too. Throws Error(Usage) when
  // the full basis exceeds the memory budget.
  BoundaryEditor(Parameterizer& parameterizer, const EditOptions& options = {});

  // Moves the listed fixed vertices to new positions (output coordinates;
  // others stay) and returns the updated #V x 2 UVs. Throws Error(Input) for
  // a vertex that is not fixed, a non-finite position, or a move that breaks
  // a constraint lying on fixed vertices only.
  const MatrixX2d& move(const std::vector<FixedVertex>& positions);
  // New targets (output coordinates) for the Parameterizer's constraint
  // rows, in the order of Parameterizer::constraints(); updates the
  // Parameterizer's targets too. Throws as set_constraint_targets().
  const MatrixX2d& move_targets(const std::vector<Eigen::Vector2d>& targets);
  // Lazy basis: computes now (one multi-column solve) and keeps the
  // responses of these fixed vertices, so that their first move is already
  // a superposition (e.g. the pins of a natural map, when it is built).
  // Within resolve_above and the memory budget; otherwise, and for the full
  // basis, nothing to do. Error(Input) for a vertex that is not fixed.
  void prepare(const std::vector<int>& vertices);

  const MatrixX2d& uv() const { return uv_; }
  // Current positions of all fixed vertices.
  std::vector<FixedVertex> boundary() const;
  double precompute_ms() const { return precompute_ms_; }
  const EditStats& last_update() const { return last_; }
  std::size_t basis_bytes() const;
  int responses() const;  // fixed-vertex responses held (all fixed columns for Full)
  int target_responses() const { return static_cast<int>(targets_.size()); }

 private:
  // One moved input: its two response columns (the u and v unknown of a
  // fixed vertex or target in the natural layout; the same column twice in
  // the fixed layout) and its displacement.
  struct Change {
    int cu = 0, cv = 0;
    Eigen::Vector2d d;
  };
  enum class Source { Fixed, Target };
  void compute_responses(Source source, const std::vector<int>& columns, Eigen::MatrixXd& out) const;
  bool ensure_responses(Source source, const std::vector<Change>& changes);
  void superpose(Source source, const std::vector<Change>& changes);
  void apply(Source source, const std::vector<Change>& changes);
  const double* response(Source source, int column) const;
  void resolve();
  void sync_parameterizer();

  Parameterizer& p_;
  EditOptions options_;
  MatrixX2d uv_;
  Eigen::MatrixXd UB_;
  int width_ = 1;                                  // response rows per vertex: 1, or 2 (natural layout: u then v)
  Eigen::MatrixXd basis_;                          // Full: width #V x n_fixed_columns
  std::unordered_map<int, Eigen::VectorXd> lazy_;  // Lazy: fixed column -> response over width #V
  std::unordered_map<int, Eigen::VectorXd> targets_;  // target column -> response over width #V
  double precompute_ms_ = 0;
  EditStats last_;
};

}  // namespace intrinsic
