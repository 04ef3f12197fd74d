// Distortion measures of a parameterization (docs/maths.md §9; paper 5.1 for
// the edge-length distortion). Per triangle, J is the 2x2 Jacobian of the map
// from the triangle's own 2D frame to the parameter plane, s1 >= s2 its
// singular values. Areas are normalised so that total parameter area equals
// total 3D area before any area-sensitive figure is computed, so the figures
// do not depend on the parameterization's overall scale.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "intrinsic/mesh.h"

namespace intrinsic {

struct FaceDistortion {
  // Singular values are of |J| (a flipped triangle still gets finite figures
  // and is counted in `flipped`); a triangle collapsed in the plane gets +inf.
  Eigen::VectorXd angle;         // s1 / s2 (1 = conformal)
  // max(s1*s2, 1/(s1*s2)) after normalisation (1 = area-preserving; 2 = the
  // triangle doubled or halved its area).
  Eigen::VectorXd area;
  // Sander et al. 2001 measure the map from the texture to the surface, whose
  // singular values are 1/s2 >= 1/s1:
  Eigen::VectorXd stretch_l2;    // sqrt((1/s1^2 + 1/s2^2) / 2)
  Eigen::VectorXd stretch_linf;  // 1/s2
  Eigen::VectorXd area_3d;       // 3D area, the aggregation weight
  std::vector<bool> flipped;     // det J <= 0
};

struct Stat {
  double min = 0, mean = 0, max = 0;  // mean weighted by 3D area; over finite values
};

struct DistortionSummary {
  int flipped_triangles = 0;
  Stat angle_distortion;
  Stat area_distortion;
  Stat stretch_l2;
  Stat stretch_linf;
  Stat edge_length_distortion;  // per edge: |u_i-u_j|^2/|x_i-x_j|^2 after normalisation (mean unweighted)
  int collapsed_triangles = 0;  // zero parameter area: infinite distortion, left out of the stats
  double scale_factor = 1;      // the normalisation applied to the UVs: sqrt(A_3D / |A_param|)
  double edge_length_energy = 0;  // sum_edges (ratio - 1)^2, paper section 5.1
  double area_energy = 0;         // sum_faces (A_param/A_3D - 1)^2
};

// Each undirected edge once, as (smaller, larger) vertex index, sorted.
Eigen::MatrixX2i unique_edges(const MatrixX3i& F);

// Edge-length and area energies of paper section 5.1 on UV exactly as given
// (no normalisation): the optimizers use these.
double edge_length_energy(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV);
double area_energy(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV);

// UV is #V x 2 (one coordinate per vertex, indexed like V).
FaceDistortion face_distortion(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV);
DistortionSummary summarize_distortion(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV);

}  // namespace intrinsic
