// Whole assets: a packed, overlap-free UV atlas of any triangle
// mesh, closed, higher-genus or messy. The input is cleaned for the
// computation only (zero-area faces set aside, non-manifold edges and vertices
// split, inconsistently oriented edges cut, so every chart keeps its faces'
// input winding and is laid out counter-clockwise in it), segmented into disk
// charts, each chart flattened by the natural conformal map of the paper (section 4.2,
// eq. 7; docs/maths.md §3) through the one Parameterizer and refined toward
// an isometry (docs/maths.md §9.9), checked (no flipped triangle, simple
// boundary, the stretch bound of §9.7) and split until valid, then packed into
// [0,1]^2 at one texel density (paper section 1.3: an atlas of charts).
// The input's vertices and faces are never changed: seams exist only in the
// per-corner UV indices.
#pragma once

#include <string>
#include <vector>

#include "intrinsic/boundary_optimization.h"
#include "intrinsic/mesh_data.h"
#include "intrinsic/metrics.h"
#include "intrinsic/optimal_lambda.h"
#include "intrinsic/parameterize.h"

namespace intrinsic {

// How faces are grouped into charts before the validity splits.
enum class Segmentation {
  NormalCones,  // region growing: normals within max_normal_deviation of the chart's mean, never across sharp edges
  Components,   // one chart per manifold piece (then split only where needed)
};

// How a chart was flattened.
enum class ChartMethod {
  Natural,            // the natural conformal map (Parameterizer, BoundaryShape::Natural)
  Triangle,           // a single triangle laid flat in its own plane (its natural map, up to a similarity)
  FixedBoundary,      // ChartMapOptions' weights with its circle or square boundary
  OptimalLambda,      // the mixed map at the chart's optimal lambda (paper section 5.1)
  OptimizedBoundary,  // the fixed-boundary map after boundary optimization (paper section 5.2)
};
// "natural", "triangle", "fixed-boundary", "optimal-lambda", "optimized-boundary"
const char* chart_method_name(ChartMethod m);

// The map of every chart: any map of `intrinsic param`.
// The default is the natural conformal map. With a circle or square
// boundary the chart's boundary is fixed (arc-length spacing) and `weights`
// chooses the interior map; `optimizer` then optionally picks lambda or
// moves the boundary per chart. Either way the chart is then checked and
// split as for the natural map, so a method with more distortion or folds
// gives more charts, never an invalid one.
enum class ChartOptimizer { None, OptimalLambda, OptimizeBoundary };
struct ChartMapOptions {
  WeightOptions weights;                         // fixed boundaries only
  BoundaryShape boundary = BoundaryShape::Natural;  // Natural, Circle or Square
  ChartOptimizer optimizer = ChartOptimizer::None;  // needs Circle or Square
  LambdaEnergy lambda_energy = LambdaEnergy::EdgeLength;        // OptimalLambda
  BoundaryEnergy boundary_energy = BoundaryEnergy::EdgeLength;  // OptimizeBoundary
  // Natural boundary only: local/global isometric refinement steps after the
  // natural conformal map (docs/maths.md §9.9). The conformal map lets area
  // drift across a curved chart (a texel grows or shrinks); the refinement
  // trades that for a little shear, keeping every triangle's orientation,
  // and is dropped when the chart's boundary would touch itself. 0: the
  // natural conformal map as it is.
  int isometric_iterations = 10;
};

// An edge the user wants cut (`--seams FILE`): two vertex indices of the input.
struct SeamEdge {
  int a = 0, b = 0;
};

struct AtlasOptions {
  ChartMapOptions chart_map;  // how each chart is flattened (default: the natural conformal map)
  Segmentation segmentation = Segmentation::NormalCones;
  double max_normal_deviation_deg = 60;  // NormalCones: face normal vs the chart's mean normal
  double sharp_angle_deg = 70;           // segmentation: region growing never crosses a sharper edge (merges may)
  // Hard edges: where the faces' normals turn by more than this many
  // degrees the edge is always a seam, through every stage (merges and the
  // chart limit included), as lightmaps want. 0: none.
  double hard_angle_deg = 0;
  // The distortion bound, on what a texel sees: per face the stretch
  // max(s1, 1/s2) of the map at the atlas's one texel density (s1 >= s2 the
  // singular values; 1.08: stretched or shrunk by 8%). A chart whose
  // area-weighted 95th percentile of it exceeds max_stretch, or with any
  // face above max_face_stretch, is split; neighbouring charts are merged
  // while the union stays within both. Then, with atlas_stretch_budget,
  // valid unions under 1% of the surface are merged past max_stretch
  // (never past max_face_stretch), smallest chart first, while the whole
  // atlas's 95th percentile stays within it (docs/maths.md §9.7).
  double max_stretch = 1.08;
  // No face of a chart may be stretched or shrunk more than this
  // (max(s1, 1/s2) at the atlas's one texel density): no bound on the
  // average can then hide a broken chart.
  double max_face_stretch = 2;
  // See max_stretch; false: every merged chart stays within max_stretch.
  bool atlas_stretch_budget = true;
  // Charts with fewer faces may be merged up to their neighbour's own
  // stretch when that is above max_stretch. 0: no merging at all (unless
  // max_charts asks for it).
  int min_chart_faces = 20;
  // Texture size the padding is measured in (texels of the [0,1]^2 square).
  int resolution = 1024;
  double padding = 2;  // texels between charts; half of it (rounded up to whole texels) around the border
  // A face with area below this fraction of its longest edge squared (or a
  // repeated vertex) is degenerate: it gets UVs but takes no part in a solve.
  double degenerate_ratio = 1e-12;
  // Weld vertices closer than this fraction of the bounding box diagonal
  // (coincident corners of unwelded exports, split at every normal or UV
  // seam) for the computation only: the output keeps the input's vertices,
  // and welded corners share texture coordinates. 0: no welding.
  double weld = 1e-7;
  // Reverse the faces listed against their piece's majority orientation in
  // the output (AtlasResult::F), so charts may span them, as `param`'s
  // validation does (the "inconsistent orientation fixed"). Off
  // (`--keep-winding`): the output keeps the input's winding and such edges
  // are seams (a mesh with faces listed at random then falls into many
  // charts). Either way no chart is mirrored against the faces written.
  bool reorient = true;
  // The user's seams: every listed edge is cut (a chart boundary in the
  // output); charts are then the pieces between seams, split only where a
  // piece is not a disk or its map is invalid (no stretch or packing splits).
  std::vector<SeamEdge> seams;
  // At most this many charts (0: no limit): after the stretch-bounded merges,
  // neighbouring charts are merged, smallest first, past max_stretch while
  // the union stays valid. A bound that validity cannot meet is exceeded.
  int max_charts = 0;
};

struct AtlasChart {
  int component = 0;  // connected component of the input (faces sharing vertices)
  int faces = 0, vertices = 0;  // vertices: the chart's own copies (corners glued across its interior edges)
  ChartMethod method = ChartMethod::Natural;
  int flipped = 0;  // always 0 in a result: flipped charts are split
  double angle_distortion_mean = 1, stretch_l2_mean = 1;  // docs/maths.md §9, area-weighted means
  double stretch_l2_rms = 1;    // Sander's L2 of the chart: root mean square of per-face L2, 3D-area weighted
  double face_stretch_p95 = 1;  // per-face max(s1, 1/s2), area-weighted 95th percentile
  double face_stretch_max = 1;  // largest per-face max(s1, 1/s2) (a texel's worst stretch or shrink)
  bool refined = false;         // the isometric refinement was kept
  double area_3d = 0;
  // 3D length of the chart's boundary: its edges not shared with another of
  // its faces (seams and the mesh's own boundary alike; docs/maths.md §9.6).
  double boundary_length = 0;
  bool rotated = false;  // turned for packing
};

// What cleaning found; each is handled for the computation and never changes
// the output's faces (reorient aside: it reverses some).
struct AtlasCleaning {
  int degenerate_faces = 0;       // zero area or repeated vertex: zero UV area (docs/maths.md §9.6), chart -1
  int nonmanifold_edges = 0;      // edges with more than two faces: every face there gets a seam
  int nonmanifold_vertices = 0;   // vertices whose corners fall into several charts' pieces without a seam edge
  int inconsistent_edges = 0;  // two faces listing the edge in the same direction
  int reversed_faces = 0;      // reorient: faces listed against their piece's majority, written reversed
  // Edges cut so every chart is consistently oriented as written: the
  // inconsistent ones, or with reorient those still inconsistent after it
  // (a Moebius band keeps one).
  int orientation_cuts = 0;
  int unreferenced_vertices = 0;  // written unchanged, no UV
  int welded_vertices = 0;        // --weld: vertices merged into an earlier one within the distance
  int hard_edges = 0;             // --hard-angle: edges cut because their faces' normals turn more
};

// Why charts were split (each split counted once, by the first check that failed).
struct AtlasSplits {
  int not_disk = 0;           // several boundary loops, closed, or Euler characteristic not 1
  int refused = 0;            // make_mesh refused the chart's own mesh (e.g. a pinched vertex)
  int solve_failed = 0;       // the natural map's solve failed
  int flipped = 0;            // a flipped or collapsed triangle, or an interior vertex wound twice
  int boundary_crossing = 0;  // the boundary crosses itself
  // Filling under 15% of the square on its box's longer side (64 faces or
  // more, at least 0.5% of the surface): once flattened, or already in its
  // projection onto its mean plane (then split before its map is solved).
  int sparse = 0;
  int stretch = 0;            // valid, but its mean L2 stretch above max_stretch
};

struct AtlasTimings {
  double clean_ms = 0, segment_ms = 0, flatten_ms = 0, merge_ms = 0, pack_ms = 0, total_ms = 0;
};

struct AtlasResult {
  MatrixX2d UV;       // texture coordinates, all in [0,1]^2
  // The faces to write: the input's, except that with reorient the
  // reversed_faces are listed 0, 2, 1. FUV follows this corner order.
  MatrixX3i F;
  MatrixX3i FUV;      // #F x 3: per face corner, a row of UV
  std::vector<int> face_chart;  // per face; -1 for degenerate faces
  std::vector<AtlasChart> charts;
  int components = 0;
  int splits = 0;          // charts split: not disks, flipped, boundary crossing, or too sparse for packing
  AtlasSplits split_reasons;
  double utilization = 0;  // UV area of the charts / area of [0,1]^2
  // Area-weighted mean of the per-chart L2 stretch (each chart's own
  // area-weighted mean of the per-triangle L2 of docs/maths.md §9.3, every
  // chart at UV area = 3D area before packing). Not Sander's L2, which is
  // the root mean square, nor what max_stretch bounds: see `stretch`.
  double stretch_l2_mean = 1;
  // What a person sees of the packed atlas (docs/maths.md §9.8):
  // summarize_stretch of the output's per-corner UVs.
  StretchSummary stretch;
  // 3D length of the seams in the output: per edge of the input's faces (a
  // vertex pair), the number of distinct per-corner UV pairs on it minus one,
  // times its length. The mesh's own boundary is no seam; a manifold edge cut
  // counts once (docs/maths.md §9.6; bench/atlas_compare.py measures xatlas so).
  double seam_length = 0;
  int flipped = 0;         // non-degenerate faces with signed UV area <= 0 in their chart's orientation (0 by construction)
  int overlapping = 0;     // charts whose texel masks meet another's (0 by construction of the packer)
  AtlasCleaning cleaning;
  AtlasTimings timings;
};

// The first of `seams` that atlas() refuses (index -1: none): a vertex out
// of range, or a pair that is not an edge of a face of `mesh`. The one check
// of seams (src/atlas/seam_edges.cpp): atlas() throws Error(Input) "seam edge
// INDEX: MESSAGE" with it; the seams file reader names the file and line.
struct SeamProblem {
  int index = -1;
  std::string message;  // e.g. "vertices 0 and 3 are not an edge of any face"
};
SeamProblem find_seam_problem(const MeshData& mesh, const std::vector<SeamEdge>& seams);


// The atlas of `input` (faces as given: triangles). Throws Error(Input) for
// an empty mesh, an out-of-range index or a non-finite coordinate,
// Error(Usage) for options out of range. Deterministic.
AtlasResult atlas(const MeshData& input, const AtlasOptions& options = {});

}  // namespace intrinsic
