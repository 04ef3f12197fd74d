// Meshes that come with their own UVs (OBJ vt, PLY u,v). A vertex may carry
// several texture coordinates (a seam), so per-face work re-indexes the faces
// by texture coordinate, copying each position once per coordinate. Shared by
// `metrics` and `render`.
#pragma once

#include <string>


#include "intrinsic/mesh.h"
#include "intrinsic/metrics.h"

namespace intrinsic {

struct UvMesh {
  MatrixX3d V;   // the position of each texture coordinate's corners (#TC rows, then the extra ones)
  MatrixX3i F;   // the input's FTC (re-pointed to the extra rows where needed)
  MatrixX2d UV;  // the input's TC, then the extra rows' copies; one row per row of V
  Eigen::Index input_vertices = 0;  // rows of V in the file, for reports
};

// A coordinate used by corners at different positions gets a row per
// position (appended). Throws Error(Input) naming the file when it has no
// texture coordinates or a texture index is out of range.
UvMesh split_by_texcoord(const MeshData& data);

// The UVs with every chart that `metrics` found mirrored as a whole reflected
// (u -> -u) back, so distortion figures and their normalisation (total UV
// area) see each chart in its own orientation and count only local folds as
// flipped. A texture coordinate takes the chart of the first face using it.
MatrixX2d unmirrored_uv(const UvMesh& m, const UvAtlasMetrics& atlas);

// 3D length of the seams (docs/maths.md §9.8): per edge of the faces, named
// by its two 3D positions (so vertices split at seams, as in soups, meet
// again), the number of distinct UV pairs on it minus one, times its length.
// The mesh's own boundary (one face) adds nothing; non-finite rows are skipped.
double seam_length(const UvMesh& m);

// Charts (degenerate ones excluded) whose UV area covers fewer than
// `min_texels` texels of a `resolution`^2 texture over [0,1]^2, or over the
// UVs' bounding square when they leave [0,1]^2 (as utilization).
int small_charts(const UvMesh& m, const UvAtlasMetrics& atlas, int resolution, double min_texels);


}  // namespace intrinsic
