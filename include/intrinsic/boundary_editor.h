// Realtime boundary manipulation (paper section 4.2; docs/maths.md §6). The
// map is linear in the fixed positions, so moving fixed vertex p by d_p
// changes every UV by d_p * b_p, where b_p (the impulse response, a "Green
// function") is the map for p at 1 and every other fixed vertex at 0, with
// the constraint targets at 0 (constraints stay met under superposition).
// An update is UV += sum over moved p of b_p d_p^T: no solve, no factorization.
//
// Two bases:
//   Full  the paper's: every b_p precomputed (n_boundary blocked multi-column
//         solves with the Parameterizer's factorization); memory
//         n_boundary x #V doubles, refused above EditOptions::memory_budget.
//   Lazy  b_p computed on the first move of p and cached (within the same
//         budget); the precompute is free and memory follows what the user
//         actually drags.
// Either falls back to one solve with the kept factorization (2 right-hand
// sides) when more than `resolve_above` vertices move at once or responses
// would be computed for more than that many vertices: superposing k responses
// costs 2 k #V flops, a solve about the same as k of a few dozen.
#pragma once

#include <cstddef>
#include <cstdint>
#include <unordered_map>

#include "intrinsic/parameterizer.h"

namespace intrinsic {

enum class BasisMode { Full, Lazy };

struct EditOptions {
  BasisMode basis = BasisMode::Lazy;
  std::size_t memory_budget = std::size_t(2) << 30;  // bytes for responses
  int resolve_above = 64;  // vertices moved at once (or new lazy responses) above which to re-solve
};

struct EditStats {
  double ms = 0;          // time of the update
  int moved = 0;          // fixed vertices whose position changed
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

  const MatrixX2d& uv() const { return uv_; }
  // Current positions of all fixed vertices.
  std::vector<FixedVertex> boundary() const;
  double precompute_ms() const { return precompute_ms_; }
  const EditStats& last_update() const { return last_; }
  std::size_t basis_bytes() const;
  int responses() const;  // responses held (all fixed vertices for Full)

 private:
  void compute_responses(const std::vector<int>& fixed_columns, Eigen::MatrixXd& out) const;
  void resolve();
  void sync_parameterizer();

  Parameterizer& p_;
  EditOptions options_;
  MatrixX2d uv_;
  Eigen::MatrixXd UB_;
  Eigen::MatrixXd basis_;                          // Full: #V x n_fixed
  std::unordered_map<int, Eigen::VectorXd> lazy_;  // Lazy: fixed column -> response over #V
  double precompute_ms_ = 0;
  EditStats last_;
};

}  // namespace intrinsic
