// The intrinsic family (fixed boundary, or the natural conformal map) as an
// object that keeps its factorization (paper sections 4.1 and 4.2;
// docs/maths.md §2-§5): the one solve path of every mode. parameterize() is
// Parameterizer(mesh, options).solve(); charts, optimal lambda, boundary
// optimization and the boundary editor all solve through it.
//
// What is kept and what each call costs:
//   construction           assemble K, eliminate the fixed vertices, factor
//                          K_II (the one sparse factorization), solve.
//   solve()                cached when nothing changed; else one 2-column solve.
//   solve_with_boundary()  same set of fixed vertices: new right-hand side only
//                          (-K_IB U_B), no refactorization. A different set
//                          changes K_II: re-partition and refactor.
//   set_constraints()      no sparse refactorization: the constraints enter by
//                          block elimination of the augmented (Lagrange)
//                          system, which costs one solve per constraint row
//                          and a small dense m x m factorization (counted in
//                          constraint_setups()). Changing only the targets
//                          (set_constraint_targets) is a new right-hand side.
//   clear_constraints()    free.
//   set_boundary_shape()   circle <-> square: the same fixed vertices (the
//                          outer loop), new positions placed as construction
//                          places them (Surface scale: one unconstrained
//                          solve); no refactorization.
// Counters: factorizations() counts sparse numeric factorizations over the
// object's life.
//
// Coordinates: the boundary is placed in output coordinates before any
// constraint is applied, and nothing is rescaled after a solve. Circle and
// square with ScaleMode::Unit go directly onto [0, 1]^2; ScaleMode::Surface
// scales the boundary (about the origin, as scale_to_surface_area) so that the
// unconstrained map has the surface's area. Constraint targets are therefore
// in the same coordinates as the output UVs, and the result with constraints
// is not rescaled (its area may differ from the surface's).
//
// Natural layout (docs/maths.md §3): with BoundaryShape::Natural (every loop
// natural, the pins fixed) or HoleRule::Natural on a mesh with holes and a
// method with a conformal term (the outer loop fixed), the factored system is
// the 2n x 2n one of docs/maths.md §3, unknowns (u_0..u_n, v_0..v_n), one
// right-hand-side column. Each constraint gives a u row and a v row with the
// same weights (C = blockdiag(C, C)) handed to the same detail::SaddleSolve;
// resolve_constraints is shared unchanged, and terms on pins or fixed
// vertices move to the target. Scale: with default pins the unconstrained
// natural map is placed in output coordinates first (ScaleMode::Unit: fitted
// into [0, 1]^2 by a similarity; Surface: pins at their
// 3D distance); given pins are output coordinates. The constrained result is
// not rescaled. solve_with_boundary() takes new pin positions (same pins: no
// refactorization); BoundaryEditor moves them through two responses per pin.
#pragma once

#include <memory>

#include "intrinsic/constraints.h"
#include "intrinsic/parameterize.h"

namespace intrinsic {

class BoundaryEditor;

class Parameterizer {
 public:
  // Keeps a reference to `mesh`, which must outlive the object. Throws as
  // parameterize() does.
  Parameterizer(const Mesh& mesh, const ParamOptions& options);
  ~Parameterizer();
  Parameterizer(Parameterizer&&) noexcept;
  Parameterizer& operator=(Parameterizer&&) noexcept;

  // The map for the current boundary and constraints. Throws Error(Numerical)
  // when the residual exceeds options.max_residual.
  ParamResult solve();
  // New positions (output coordinates) for every fixed vertex; see above for
  // when this refactors. Throws Error(Input) when a constraint's fixed-only
  // row disagrees with the new positions.
  ParamResult solve_with_boundary(const std::vector<FixedVertex>& fixed);
  // Circle or square for a Parameterizer built with the other of the two:
  // the boundary as Parameterizer(mesh, options with `shape`) would place it,
  // on the kept factorization (constraints kept). Error(Usage) for any other
  // shape or layout; Error(Input) when a constraint on fixed vertices only
  // disagrees with the new boundary (nothing changes then).
  void set_boundary_shape(BoundaryShape shape);

  // Resolves and adds constraints (replacing earlier ones). Throws
  // Error(Input): see resolve_constraints(), plus rows only on fixed vertices
  // that disagree with the boundary, and linearly dependent rows.
  void set_constraints(const Constraints& constraints);
  void set_constraints(std::vector<LinearConstraint> rows);
  // New targets for the same rows (in the order of constraints()).
  void set_constraint_targets(const std::vector<Eigen::Vector2d>& targets);
  void clear_constraints();
  const std::vector<LinearConstraint>& constraints() const;
  std::vector<ConstraintResidual> residuals(const MatrixX2d& UV) const;

  // Current fixed vertices and positions, in output coordinates (kept up to
  // date by solve_with_boundary and by a BoundaryEditor's moves).
  const std::vector<FixedVertex>& boundary() const;
  const Mesh& mesh() const;
  const ParamOptions& options() const;
  int free_vertices() const;
  int factorizations() const;
  int constraint_setups() const;

 private:
  friend class BoundaryEditor;
  friend class BoundaryObjective;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace intrinsic
