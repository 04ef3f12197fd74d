// Local/global isometric refinement of a chart's map (docs/maths.md §9.9):
// the "as-rigid-as-possible" energy sum_f A_f |J_f - R_f|^2 of Liu et al.
// 2008, minimised from a given valid map (the natural conformal map) by
// alternating a best rotation per face and one linear solve. The linear
// system is the conformal matrix K of docs/maths.md §1.4 with one vertex
// fixed, assembled and factored once; every iteration is a new right-hand
// side. The conformal map keeps angles and lets area drift across a curved
// chart; this trades that area drift for a little angle distortion, which is
// what a texel sees (per-face stretch max(s1, 1/s2)).
#pragma once

#include "intrinsic/mesh.h"

namespace intrinsic::detail {

struct IsometricRefinementOptions {
  int iterations = 10;
  // A step that flips or collapses a triangle (signed UV area at most this
  // fraction of its longest UV edge squared) is halved up to 4 times, then
  // the refinement stops at the last fold-free map.
  double degenerate_ratio = 1e-12;
};

struct IsometricRefinementResult {
  int iterations = 0;  // steps taken (each fold-free)
  double energy_before = 0, energy_after = 0;  // sum_f A_f |J_f - R_f|_F^2
};

// Refines UV (one row per vertex of mesh, a fold-free map of a disk) in
// place; UV stays fold-free. Throws nothing: a failed factorization leaves
// UV unchanged.
IsometricRefinementResult refine_isometric(const Mesh& mesh, MatrixX2d& UV,
                                           const IsometricRefinementOptions& options = {});

}  // namespace intrinsic::detail
