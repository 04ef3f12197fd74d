// An interactive editing session (one browser tab of `intrinsic serve`): its Parameterizer, the
// BoundaryEditor on it (fixed boundary or natural pins) and the options they
// were built with (paper section 4.2; docs/maths.md §5, §6). A request is
// answered from the kept factorization whenever the system matrix is
// unchanged:
//   responses    same options and constraint rows: moved boundary vertices,
//                moved pins and new constraint targets superposed from the
//                editor's responses (computed on an input's first move,
//                then kept; a natural map's pins with the build), no solve;
//   resolve      same, but one solve with the kept factorization (many
//                inputs moved at once, or circle <-> square: the same fixed
//                vertices at other positions);
//   constraints  other constraint rows (added, removed, a new line): the
//                constraint block re-set on the kept factorization (one
//                solve per constraint row, a small dense factorization);
//   factor       another method, lambda, mu, natural vs fixed boundary or
//                set of pins: a new Parameterizer (K itself changes).
// Not thread-safe: the caller holds the session's mutex.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "intrinsic/boundary_editor.h"
#include "intrinsic/constraints.h"
#include "intrinsic/parameterizer.h"

namespace intrinsic {

// One request to a session (the server reads it from `POST /api/solve`).
struct EditRequest {
  WeightOptions weights;                            // checked (pipeline.h weight_options)
  BoundaryShape boundary = BoundaryShape::Circle;   // Circle, Square or Natural
  std::vector<FixedVertex> pins;                    // natural only; empty: the default pins
  Constraints constraints;                          // face points already in mesh.F corner order
  std::string constraints_key;                      // canonical JSON of the constraints ("" when none)
  std::vector<FixedVertex> moves;                   // fixed boundary only: new positions of base boundary vertices
};

struct EditAnswer {
  MatrixX2d uv;
  double update_ms = 0;             // the solve or update only (not parsing, metrics, JSON)
  std::string path;                 // "responses" | "resolve" | "constraints" | "factor"
  std::vector<FixedVertex> pins;    // natural map: the pins used (output coordinates)
  int factorizations = 0;           // sparse factorizations of the session's Parameterizer so far
};

class EditSession {
 public:
  explicit EditSession(const Mesh& mesh) : mesh_(mesh) {}
  ~EditSession();
  // Throws intrinsic::Error as the library does; the session then keeps no
  // half-built state (the next request builds anew).
  EditAnswer solve(const EditRequest& request);
  // Fixed boundary: the positions of the outer loop (output coordinates)
  // after `request` (solved first). Error(Usage) for the natural map.
  std::vector<FixedVertex> boundary_after(const EditRequest& request);

 private:
  EditAnswer rebuild(const EditRequest& r, const std::string& key);
  std::string update_constraints(const EditRequest& r);
  EditAnswer move_fixed(const EditRequest& r);
  EditAnswer move_pins(const EditRequest& r);
  void set_base();
  void prepare_pins();
  void reset();

  const Mesh& mesh_;
  std::unique_ptr<Parameterizer> parameterizer_;
  std::unique_ptr<BoundaryEditor> editor_;  // destroyed before the parameterizer
  std::string key_;                         // options the parameterizer was built with (constraints aside)
  std::string constraints_key_;             // the constraints it holds now
  BoundaryShape shape_ = BoundaryShape::Circle;  // the boundary it holds now
  bool has_shape_ = false;                        // false until built (and after a failure)
  std::vector<FixedVertex> base_;           // fixed boundary: the base positions (output coordinates)
  std::vector<int> base_index_;             // vertex -> index in base_, -1 when not fixed
  std::vector<int> moved_;                  // vertices the last request moved away from base_
  std::vector<FixedVertex> default_pins_;   // natural map: the default pins as placed (kept across rebuilds)
};

}  // namespace intrinsic
