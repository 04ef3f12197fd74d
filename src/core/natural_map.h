// The natural conformal map (paper section 4.2, eq. 7; SPEC section 3) and
// the pieces other solvers reuse: the 2n x 2n system of the conformal energy
// E_D - A, the default pins, and the elimination of pinned unknowns.
//
// Unknown ordering of every 2n x 2n matrix here ("blocked"): index v is u_v,
// index n + v is v_v, for v = 0 .. n-1 (n = V.rows(), used or not; unused
// vertices have empty rows and columns). A caller adding Lagrange point
// constraints (SPEC section 4) appends its rows and columns after index 2n.
#pragma once

#include <utility>
#include <vector>

#include "intrinsic/boundary.h"
#include "intrinsic/linear_solver.h"
#include "intrinsic/parameterize.h"

namespace intrinsic {

// Twice the Hessian of the signed parameter area A = 1/2 sum over boundary
// half-edges a->b of (u_a v_b - u_b v_a), restricted to the given loops (each
// a vertex list in half-edge order, interior on the left, as
// Topology::boundary_loops). Interior edges cancel in A, so only boundary
// vertices couple u and v. 2n x 2n, blocked ordering.
SparseMatrix area_hessian(int num_vertices, const std::vector<std::vector<int>>& loops);

// K (n x n) on both diagonal blocks of a 2n x 2n matrix.
SparseMatrix block_diagonal2(const SparseMatrix& K);

// Q = 2 * Hessian of E_D - A over the whole mesh, E_D = 1/4 sum cot |u_a - u_b|^2:
// Q = [K 0; 0 K] - area_hessian(all loops), K the cotangent matrix of
// assemble_weight_matrix. Row v of Q U = 0 is eq. 4 at interior vertices and
// eq. 7 at boundary vertices (u row first, v row at n + v). Q is symmetric
// positive semi-definite; its kernel holds the translations (and, on a flat
// mesh, the similarities), so pinning two vertices makes it definite.
// Blocked ordering.
SparseMatrix assemble_natural_system(const Mesh& mesh);

// The two vertices of the list farthest apart in 3D, smaller index first.
// Exact: all pairs, pruned by a bounding-sphere bound (|x_i - x_j| <= r_i +
// r_j around the centroid), so typical loops cost far fewer than m^2/2
// distance evaluations; the worst case stays O(m^2). Ties go to the smallest
// index pair. Throws Error(Input) for fewer than two vertices.
std::pair<int, int> farthest_pair(const MatrixX3d& V, std::vector<int> vertices);

// The default pins of the natural map: the farthest pair of the outer loop
// (the longest in 3D). On a disk these are the two boundary vertices farthest
// apart. With holes the outer loop is used, not all loops: pins on two
// different loops folded fairing-cross.off (6 flipped triangles, 0 with
// outer-loop pins) and stanford-bunny.obj (11 vs 3); see docs/holes.md.
std::pair<int, int> default_pin_pair(const Mesh& mesh);

// Result of eliminating fixed vertices from a 2n x 2n system Q U = 0.
struct PinnedSolution {
  MatrixX2d UV;  // #V x 2, unused vertices at (0, 0)
  std::string solver;
  double residual = 0;
  int free_vertices = 0, fixed_vertices = 0, factorizations = 0, iterations = 0;
  double factor_ms = 0, solve_ms = 0;

  // Copies the solution and its diagnostics into a result (scale, pins and
  // holes are the caller's).
  void fill(ParamResult& r) const {
    r.UV = UV;
    r.solver = solver;
    r.residual = residual;
    r.free_vertices = free_vertices;
    r.fixed_vertices = fixed_vertices;
    r.factorizations = factorizations;
    r.iterations = iterations;
    r.timings.factor_ms = factor_ms;
    r.timings.solve_ms = solve_ms;
  }
};

// Solves Q U = 0 (blocked ordering) with the vertices in `fixed` held at
// their positions (both coordinates): the fixed unknowns move to the right-hand
// side, the remaining block is factored once. `symmetric` selects Cholesky.
// Throws Error(Numerical) on a singular system or a residual above max_residual.
PinnedSolution solve_pinned(const SparseMatrix& Q, const std::vector<FixedVertex>& fixed,
                            const std::vector<char>& is_used, SolverKind kind, bool symmetric, double max_residual);

// Throws Error(Usage) unless the weights are conformal (mixed with mu = 0
// counts): eq. 7 comes from the conformal energy.
void check_natural_method(const WeightOptions& weights);

// The pins of the natural map: options.pins checked (at least two, existing
// used vertices, each once, finite, not all at one point), or the default
// pair (default_pin_pair) at (0, 0) and (d, 0), d their 3D distance.
std::vector<FixedVertex> natural_pins(const Mesh& mesh, const ParamOptions& options);

// The factor of the area term HoleRule::Natural adds on hole loops: the weight
// of the conformal energy in the method's rows. 0 for methods with no
// conformal part (authalic, Tutte, Floater), whose holes stay free.
double natural_hole_weight(const WeightOptions& weights);

// True when HoleRule::Natural changes the system: the mesh's first component
// has holes and the method a conformal part.
bool solves_natural_holes(const Mesh& mesh, const ParamOptions& options);

// The natural conformal map of a one-component mesh with a boundary
// (called by parameterize for BoundaryShape::Natural).
ParamResult natural_map(const Mesh& mesh, const ParamOptions& options);

}  // namespace intrinsic
