// The natural conformal map's system (paper section 4.2, eq. 7;
// docs/maths.md §3): the 2n x 2n matrix of the conformal energy E_D - A, the
// area term natural holes add, and the default pins. The Parameterizer
// solves it; nothing else does.
//
// Unknown ordering of every 2n x 2n matrix here ("blocked"): index v is u_v,
// index n + v is v_v, for v = 0 .. n-1 (n = V.rows(), used or not; unused
// vertices have empty rows and columns).
#pragma once

#include <utility>
#include <vector>

#include "intrinsic/boundary.h"
#include "solve/linear_solver.h"
#include "intrinsic/parameterize.h"

namespace intrinsic {

// The coupling of u and v in twice the Hessian of the signed parameter area
// A = 1/2 sum over boundary half-edges a->b of (u_a v_b - u_b v_a), over the
// given loops (each a vertex list in half-edge order, interior on the left,
// as Topology::boundary_loops): B(a, b) = +1 and B(b, a) = -1 per half-edge
// (n x n, antisymmetric; twice the Hessian is [0 B; -B 0] in blocked
// ordering, docs/maths.md §3.6). Interior edges cancel in A, so only
// boundary vertices couple u and v.
SparseMatrix area_coupling(int num_vertices, const std::vector<std::vector<int>>& loops);

// The 2n x 2n matrix [K -B; B K] (blocked ordering) straight into compressed
// storage: the real form of K + iB (docs/maths.md §3.6). B's pattern must
// lie within K's (boundary edges are mesh edges).
SparseMatrix real_form_matrix(const SparseMatrix& K, const SparseMatrix& B);

// Q = 2 * Hessian of E_D - A over the whole mesh, E_D = 1/4 sum cot |u_a - u_b|^2:
// Q = real_form_matrix(K, area_coupling(all loops)), K the cotangent matrix of
// assemble_weight_matrix. Row v of Q U = 0 is eq. 4 at interior vertices and
// eq. 7 at boundary vertices (u row first, v row at n + v). Q is symmetric
// positive semi-definite; its kernel holds the translations (and, on a flat
// mesh, the similarities), so pinning two vertices makes it definite.
// Blocked ordering.
SparseMatrix assemble_natural_system(const Mesh& mesh);

// The two vertices of the list farthest apart in 3D, smaller index first.
// Exact: all pairs, pruned by a bounding-sphere bound (|x_i - x_j| <= r_i +
// r_j around the centroid), so typical loops cost far fewer than m^2/2
// distance evaluations; the worst case stays O(m^2). Distances within a
// relative 1e-12 of the largest are ties (so rounding, e.g. after scaling
// the input, cannot choose between mirror-image pairs), broken by the
// smallest index pair. Throws Error(Input) for fewer than two vertices.
std::pair<int, int> farthest_pair(const MatrixX3d& V, std::vector<int> vertices);

// The default pins of the natural map: the farthest pair of the outer loop
// (the longest in 3D). On a disk these are the two boundary vertices farthest
// apart. With holes the outer loop is used, not all loops: pins on two
// different loops folded fairing-cross.off (6 flipped triangles, 0 with
// outer-loop pins) and stanford-bunny.obj (11 vs 3); see docs/holes.md.
std::pair<int, int> default_pin_pair(const Mesh& mesh);

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

}  // namespace intrinsic
