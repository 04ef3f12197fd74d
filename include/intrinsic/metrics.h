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

// What face_distortion needs of the 3D surface, for any map: per face the
// inverse of its edge matrix in the face's own 2D frame (row-major 2x2) and
// its area. Computed once, it serves many maps of the same mesh (the
// editor's answers); face_distortion(V, F, UV) is face_distortion of these.
struct FaceFrames {
  Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor> P_inverse;
  Eigen::VectorXd area_3d;
  double total_area_3d = 0;
};
FaceFrames face_frames(const MatrixX3d& V, const MatrixX3i& F);
FaceDistortion face_distortion(const FaceFrames& frames, const MatrixX3i& F, const MatrixX2d& UV);
// The number of faces face_distortion marks flipped, without the singular
// values (about a quarter of its cost: the editor's answers while dragging).
int count_flipped(const FaceFrames& frames, const MatrixX3i& F, const MatrixX2d& UV);
DistortionSummary summarize_distortion(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV);

// ---- What a person sees: Sander's L2 and per-face stretch (docs/maths.md §9.8)
// Texel-density figures of a whole UV layout at ONE normalisation: the UVs
// are scaled so that the total |UV area| equals the total 3D area (of the
// faces not collapsed), then each face is judged against that common texel
// density (a chart drawn small stretches the texture over its surface
// however conformal it is). Faces
// with zero 3D area (make_mesh's test) have no surface to texture and are
// left out; collapsed faces (zero UV area, exact test, or a non-finite UV)
// have infinite stretch: they count in the percentiles and maxima, and are
// left out of the means (sander_l2, anisotropy_mean).
struct StretchSummary {
  // sqrt(sum_f A3_f L2_f^2 / sum_f A3_f), L2_f = sqrt((1/s1^2 + 1/s2^2)/2):
  // the root-mean-square stretch of Sander et al. 2001 (texture -> surface).
  double sander_l2 = 1;
  double sander_linf = 1;  // max_f 1/s2 (+inf with a collapsed face)
  // Per face max(s1, 1/s2) >= 1: how far the texture is magnified (1/s2)
  // or minified (s1) in its worst direction. Percentiles are weighted by 3D
  // area: the smallest value x such that faces with stretch <= x hold at
  // least that fraction of the 3D area.
  double face_stretch_p50 = 1, face_stretch_p95 = 1, face_stretch_p99 = 1, face_stretch_max = 1;
  double anisotropy_mean = 1;  // area-weighted mean of s1/s2 (1 = conformal)
  int faces = 0;               // faces counted (non-zero 3D area), collapsed ones included
  int collapsed_faces = 0;     // among them, zero UV area: infinite stretch
  int degenerate_faces = 0;    // zero 3D area: left out
  double scale_factor = 1;     // the normalisation: sqrt(sum A3 / sum |A_uv|), collapsed faces left out
};

// UV is #V x 2, one coordinate per vertex (callers with per-corner UVs pass
// the mesh split by texture coordinate). All figures are unchanged by a
// uniform scale of UV and by a rigid motion of V or UV (a reflection included).
// Every figure is 1 when no face has 3D area, +inf when every face counted is collapsed.
StretchSummary summarize_stretch(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV);
// Per-corner UVs: corner c of face f has position V.row(F(f, c)) and UV
// UV.row(FUV(f, c)) (an atlas's output, AtlasResult::F / FUV).
StretchSummary summarize_stretch(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV, const MatrixX3i& FUV);

// ---- Atlases and other tools' outputs -------------------------------------
// Per-corner UVs: FT (#F x 3) indexes rows of UV, PT (#UV x 3) is the 3D
// position of each texture coordinate's corners (app/uv_mesh.h builds it from
// OBJ `f v/vt`, triangle soups with split vertices included). Texture
// coordinates with the same UV and the same position are the same corner, so
// a soup that repeats them per face still forms charts.

// One chart: faces connected through UV edges (two shared corners).
struct UvChart {
  int faces = 0;
  double uv_area = 0;  // sum of |UV triangle areas|
  double area_3d = 0;
  // The chart as a whole has negative UV orientation relative to the faces'
  // listing (the majority listing of the chart's edge-consistent orientation).
  bool mirrored = false;
  int flipped = 0;    // faces whose UV orientation is opposite to the chart's (local folds)
  int collapsed = 0;  // faces with zero UV area (and non-zero 3D area)
  // Every face has zero 3D area (e.g. a zero-area face whose UVs are
  // collapsed apart from its neighbours): no surface to texture, so not
  // counted among the charts of the report (docs/maths.md §9.5).
  bool degenerate = false;
};

struct UvAtlasMetrics {
  std::vector<int> face_chart;  // per face, the index into charts
  std::vector<char> face_folded;       // per face: locally flipped or collapsed
  std::vector<char> face_overlapping;  // per face: meets another face's interior
  std::vector<UvChart> charts;  // all UV-connected components, degenerate ones included
  int degenerate_charts = 0;    // components of zero-area faces only: charts.size() minus this is the chart count
  int mirrored_charts = 0, mirrored_faces = 0;  // whole charts mirrored (not counted in flipped_triangles)
  int flipped_triangles = 0;    // locally flipped, over all charts
  int collapsed_triangles = 0;  // zero UV area, non-zero 3D area
  int degenerate_faces = 0;     // zero 3D area (make_mesh's test): not counted as flipped
  // Faces whose UV triangle's interior meets another's (same or other chart),
  // by an exact orientation test, independent of any packer.
  int overlapping_triangles = 0;
  int overlapping_pairs_within_charts = 0, overlapping_pairs_between_charts = 0;
  double uv_area = 0;
  // UV area over the area of [0,1]^2 when every UV lies in [0,1]^2 (a packed
  // atlas), otherwise over the UVs' bounding square (side: the longer side
  // of their bounding box); utilization_in_unit_square says which.
  double utilization = 0;
  bool utilization_in_unit_square = true;
  double utilization_bbox = 0;  // UV area over the UVs' bounding rectangle
};

UvAtlasMetrics uv_atlas_metrics(const MatrixX3d& PT, const MatrixX3i& FT, const MatrixX2d& UV);

// Per face: 1 when its UV triangle's interior meets another face's. Exact
// (adaptive orientation predicate), a uniform grid over the UV box for speed;
// faces with zero UV area or non-finite UVs never overlap.
std::vector<char> overlapping_uv_triangles(const MatrixX3i& FT, const MatrixX2d& UV, int* pairs_within = nullptr,
                                           int* pairs_between = nullptr, const std::vector<int>* face_chart = nullptr);

// Sign (+1, 0, -1) of the orientation of (a, b, c), exact for any finite doubles
// (Shewchuk's filter with an exact expansion fallback).
int orient2d_sign(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

}  // namespace intrinsic
