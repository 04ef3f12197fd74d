// Parameterizer's kept state, shared with BoundaryEditor and
// BoundaryObjective (which read the partition, the blocks and the
// factorization to build responses and adjoint gradients). Internal: not
// installed, not part of the API. docs/maths.md §2-§5.
#pragma once

#include <chrono>
#include <memory>

#include "core/placement.h"
#include "core/saddle_solve.h"
#include "intrinsic/error.h"
#include "intrinsic/parameterizer.h"
#include "solve/eliminated_system.h"

namespace intrinsic {
namespace detail {
inline double elapsed_ms(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace detail

struct Parameterizer::Impl {
  const Mesh* mesh = nullptr;
  ParamOptions o;
  int n = 0;  // original vertex count; filled-hole centres come after
  int filled_holes = 0;
  std::unique_ptr<detail::EliminatedSystem> sys;
  Eigen::MatrixXd UB;              // fixed positions, rows in partition().fixed_vertices order
  std::vector<FixedVertex> fixed;  // the same as a list (vertices, not unknowns)
  Placement placement = Placement::Unit;
  HolesApplied holes = HolesApplied::None;
  int factorizations = 0, constraint_setups = 0;
  StageTimings timings;

  std::vector<LinearConstraint> rows;
  std::vector<int> active, fixed_only;  // rows with free terms / only fixed terms
  SparseMatrix CB;                      // active rows' terms on fixed vertices
  detail::SaddleSolve saddle;

  bool have_X = false;
  Eigen::MatrixXd X, lambda;

  // Natural layout (docs/maths.md §3): the 2n x 2n system with blocked
  // unknowns (u_v at index v, v_v at n + v) and one right-hand-side column;
  // the partition, UB (a column) and X are over those 2n unknowns, and each
  // constraint gives a u row and a v row with the same weights
  // (C = blockdiag(C, C)). Used for the natural boundary (the fixed unknowns
  // are the pins) and for natural holes with a conformal term (the fixed
  // unknowns are the outer loop). No holes are filled in this layout.
  bool natural = false;
  bool natural_boundary = false;
  std::vector<FixedVertex> pins;  // natural boundary: the pins as given (or the default pair), before placing

  // Construction (parameterizer_build.cpp).
  void build(const std::vector<FixedVertex>& given);
  void build_fixed(const std::vector<FixedVertex>& given);
  void build_natural(const std::vector<FixedVertex>& given);
  void factor(SparseMatrix&& K, const std::vector<char>& is_fixed, const std::vector<char>& is_used,
              bool symmetric, std::chrono::steady_clock::time_point t_assemble,
              std::shared_ptr<detail::AnalysisAhead> ahead = nullptr);
  std::shared_ptr<detail::AnalysisAhead> analyse_ahead(const SparseMatrix& K_pattern, const std::vector<char>& is_fixed,
                                                       const std::vector<char>& is_used) const;
  detail::PlacementRule initial_placement_rule();
  void place_initially();
  HolesApplied holes_applied() const;

  // Solving and unpacking (parameterizer_impl.cpp).
  const Partition& p() const { return sys->partition(); }
  int num_free() const { return sys->free_count(); }
  int free_vertex_count() const { return natural ? num_free() / 2 : num_free(); }
  Eigen::Vector2d fixed_uv(const Eigen::MatrixXd& ub, int v) const;
  void set_fixed_uv(Eigen::MatrixXd& ub, int v, const Eigen::Vector2d& uv) const;
  void place(const detail::Similarity& s);
  void update_fixed_list();
  Eigen::MatrixXd solve_linear(const Eigen::MatrixXd& R, const Eigen::MatrixXd& T, Eigen::MatrixXd* l = nullptr) const;
  Eigen::MatrixXd active_targets() const;
  Eigen::MatrixXd solve_for(const Eigen::MatrixXd& ub, Eigen::MatrixXd* l = nullptr) const;
  MatrixX2d full_uv(const Eigen::MatrixXd& x, const Eigen::MatrixXd& ub) const;
  void check_fixed_only(const Eigen::MatrixXd& ub) const;
  void setup_constraints();
  double residual() const;
  ParamResult result() const;
  [[noreturn]] void throw_diagnosed(const Error& e) const;
};

}  // namespace intrinsic
