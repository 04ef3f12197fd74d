// One browser tab's state in `intrinsic serve`: its Parameterizer, the
// BoundaryEditor on it (fixed boundary) and the options they were built
// with. A request with the same options is answered from the kept
// factorization: moves through the editor's responses ("responses", or
// "resolve" when the editor re-solves), new pin positions by a new
// right-hand side ("resolve"); other options build a new Parameterizer
// ("factor"). Not thread-safe: the caller holds the session's mutex.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "intrinsic/boundary_editor.h"
#include "intrinsic/parameterizer.h"
#include "serve/solve_request.h"

namespace intrinsic::app {

struct SolveAnswer {
  MatrixX2d uv;
  double update_ms = 0;             // the solve or update only (not parsing, metrics, JSON)
  std::string path;                 // "responses" | "resolve" | "factor"
  std::vector<FixedVertex> pins;    // natural map: the pins used (output coordinates)
};

class EditSession {
 public:
  explicit EditSession(const Mesh& mesh) : mesh_(mesh) {}
  ~EditSession();
  // Throws intrinsic::Error as the library does; the session then keeps no
  // half-built state (the next request builds anew).
  SolveAnswer solve(const SolveRequest& request);

 private:
  SolveAnswer rebuild(const SolveRequest& r, const std::string& key);
  SolveAnswer move_fixed(const SolveRequest& r);
  SolveAnswer move_pins(const SolveRequest& r);
  void reset();

  const Mesh& mesh_;
  std::unique_ptr<Parameterizer> parameterizer_;
  std::unique_ptr<BoundaryEditor> editor_;  // fixed boundary only; destroyed before the parameterizer
  std::string key_;                         // options the parameterizer was built with
  std::vector<FixedVertex> base_;           // fixed boundary: the base positions (output coordinates)
  std::vector<int> base_index_;             // vertex -> index in base_, -1 when not fixed
  std::vector<int> moved_;                  // vertices the last request moved away from base_
};

}  // namespace intrinsic::app
