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

#include "intrinsic/choice.h"
#include "intrinsic/boundary_optimization.h"
#include "intrinsic/mesh_data.h"
#include "intrinsic/mesh_document.h"
#include "intrinsic/metrics.h"
#include "intrinsic/optimal_lambda.h"
#include "intrinsic/parameterize.h"

namespace intrinsic {

// How faces are grouped into charts before the validity splits.
enum class Segmentation {
  NormalCones,  // region growing: normals within max_normal_deviation of the chart's mean, never across sharp edges
  Components,   // one chart per manifold piece (then split only where needed)
};
template <>
ChoiceTable<Segmentation> choice_table<Segmentation>();

// How a chart was flattened.
enum class ChartMethod {
  Natural,            // the natural conformal map (Parameterizer, BoundaryShape::Natural)
  Triangle,           // a single triangle laid flat in its own plane (its natural map, up to a similarity)
  FixedBoundary,      // ChartMapOptions' weights with its circle or square boundary
  OptimalLambda,      // the mixed map at the chart's optimal lambda (paper section 5.1)
  OptimizedBoundary,  // the fixed-boundary map after boundary optimization (paper section 5.2)
};
template <>
ChoiceTable<ChartMethod> choice_table<ChartMethod>();
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
template <>
ChoiceTable<ChartOptimizer> choice_table<ChartOptimizer>();
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

// The charts stage (compute_charts): everything up to packing (AtlasOptions::
// charts in the one call); none of them
// depends on the texture's resolution or padding (the stretch and the
// sparse-chart test are measured at the charts' own scale, UV area = 3D area).
struct ChartOptions {
  ChartMapOptions chart_map;  // how each chart is flattened (default: the natural conformal map)
  Segmentation segmentation = Segmentation::NormalCones;
  double max_normal_deviation_deg = 60;  // NormalCones: face normal vs the chart's mean normal
  double sharp_angle_deg = 70;           // no chart spans a sharper edge (growing, merges; slivers excepted)
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
  // Faces that must share a chart: per face a group id (>= 0; -1: none),
  // e.g. the polygon each triangle came from. A host that stores one UV per
  // polygon corner (Blender's loops) cannot write a quad whose two triangles
  // lie in different charts: the shared corners would take one chart's UVs
  // and the other triangle would stretch across the atlas. After the charts
  // are valid, a group split between charts goes whole to the chart holding
  // most of its area and the charts that changed are flattened again (a few
  // rounds, as a re-flattened chart may be split anew); groups still split
  // are counted in AtlasCharts::split_groups. Empty: no groups.
  std::vector<int> face_group;
};

// The pack stage (pack_charts): all that only packing uses (AtlasOptions::
// pack in the one call).
struct PackOptions {
  // Texture size the padding is measured in (texels of the [0,1]^2 square).
  int resolution = 1024;
  double padding = 2;  // texels between charts; half of it (rounded up to whole texels) around the border
  // Texel density for lightmaps: > 0 gives every chart this many texels per
  // unit of surface length (one density for every chart and object of the
  // input, whatever else the input holds), charts on whole texels, on pages
  // of `resolution` texels filled in turn: page k is the UDIM tile 1001 + k,
  // u in [k, k + 1], v in [0, 1]. A chart larger than a page at that density
  // is scaled down to fit one (AtlasResult::shrunk_charts), never dropped or
  // split across pages. 0: one page, every chart scaled to fill it.
  double texels_per_unit = 0;
  // With texels_per_unit: more pages than this is refused with Error(Input)
  // (nothing written). 0: as many as needed.
  int max_pages = 0;
  // Charts keep the orientation they come with, turned only by quarter
  // turns (repacking an asset's own UVs); else each is first turned to its
  // smallest bounding box.
  bool keep_orientation = false;
};

// What one atlas covers: the whole input (one texture for everything, e.g. a
// lightmap), or each mesh of it on its own filling the unit square (a glTF
// document's meshes, an OBJ file's `o` objects, which the file's document
// tells: atlas of a MeshFile; src/atlas/atlas_per_mesh.cpp).
enum class AtlasScope { Whole, PerMesh };
template <>
ChoiceTable<AtlasScope> choice_table<AtlasScope>();

// The one-call form's options: the two stages' own, and what only the one
// call decides.
struct AtlasOptions {
  ChartOptions charts;  // the charts stage (compute_charts)
  PackOptions pack;     // the pack stage (pack_charts); keep_orientation comes from pack_only
  // Re-pack the input's own texture coordinates (MeshData::TC/FTC) instead
  // of cutting charts: its charts (faces connected through shared UV rows)
  // keep their shape, turned only by quarter turns, all scaled by one factor
  // and moved into a layout without overlaps (repack_uvs.cpp). Input charts
  // that overlap each other (mirrored halves sharing texels) are separated,
  // or with keep_overlaps packed together as they lie. Refused with
  // Error(Input) for an input without texture coordinates on every face.
  bool pack_only = false;
  bool keep_overlaps = false;
  // PerMesh: one atlas per mesh, each in [0,1]^2 (they overlap each other);
  // refused with Error(Usage) for an input without meshes to tell apart
  // (a MeshData alone has none).
  AtlasScope scope = AtlasScope::Whole;
};
// The pack stage's options as the one call runs them (pack, with
// keep_orientation set by pack_only).
PackOptions pack_options(const AtlasOptions& options);

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
  int split_groups = 0;    // as AtlasCharts::split_groups
  double utilization = 0;  // UV area of the charts / area of [0,1]^2 (with pages: their mean)
  // Pages (PackOptions::texels_per_unit > 0; else one page): per chart its
  // page (UDIM tile 1001 + page, u in [page, page + 1]), per page its
  // utilization, and the charts scaled down to fit one page.
  int pages = 1;
  std::vector<int> chart_page;
  std::vector<double> page_utilization;
  std::vector<int> shrunk_charts;
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
  // Pairs of faces whose UV triangles' interiors meet (in one chart or two),
  // counted exactly on the layout: 0, except input charts kept on each
  // other on request (AtlasOptions::keep_overlaps).
  int overlapping = 0;
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


// The charts stage's result: every chart flattened, checked and split until
// valid, at the surface's own scale (UV area = 3D area: the atlas's one texel
// density before packing), each in its own frame (charts overlap here), not
// yet packed. pack_charts packs it at any resolution and padding without
// recomputing a chart; it reads V, F, UV, FUV, face_chart and each chart's
// area_3d and copies the rest into its AtlasResult.
struct AtlasCharts {
  MatrixX3d V;   // the input's vertices (the packed atlas's degenerate faces, seams and stretch are measured on them)
  MatrixX3i F;   // the faces to write, as AtlasResult::F (with reorient, reversed_faces listed 0, 2, 1)
  // Per chart vertex: chart 0's rows first, then chart 1's, and so on (each
  // chart's rows one block, in chart order, every row used by its chart).
  MatrixX2d UV;
  MatrixX3i FUV;                // #F x 3 rows of UV in F's corner order; -1 for degenerate faces (pack_charts places them)
  std::vector<int> face_chart;  // per face; -1 for degenerate faces
  std::vector<AtlasChart> charts;  // boundary_length set; rotated is set by packing
  int components = 0;
  int splits = 0;  // as AtlasResult::splits; charts_from_ids also counts a given chart in k pieces as k - 1 not_disk splits
  AtlasSplits split_reasons;
  int split_groups = 0;  // face groups (ChartOptions::face_group) still in more than one chart
  double stretch_l2_mean = 1;  // as AtlasResult::stretch_l2_mean
  AtlasCleaning cleaning;
  AtlasTimings timings;  // clean, segment, flatten, merge and their total; pack_charts adds pack_ms to it
};

// The charts stage of atlas(): clean, segment, flatten and split, merge.
// Throws as atlas() does (Error(Input) for the mesh or a seam,
// Error(Usage) for options out of range). Deterministic.
AtlasCharts compute_charts(const MeshData& input, const ChartOptions& options = {});

// Your own charts: face_chart gives a chart id per face of `input` (any
// integers >= 0; -1 only for degenerate faces, which get no chart
// anyway). Segmentation and merging are skipped; each given chart is cut
// only where it must be: into its pieces connected across edges that the
// cleaning glued (seams, hard edges and orientation cuts of `options`
// included), and each piece split further only where it is not a disk or its
// map is invalid (no sparse or stretch splits, as for the user's seams),
// each split counted in split_reasons. Every output chart lies within one
// given chart, and a given chart that is a valid disk stays exactly one
// chart. Options used: chart_map, degenerate_ratio, weld, reorient, seams,
// hard_angle_deg (the segmentation, stretch, merge and max_charts fields are
// not). Throws Error(Usage) for ids of the wrong length, and naming the
// face for an id below -1 or -1 on a face that is not degenerate.
AtlasCharts charts_from_ids(const MeshData& input, const std::vector<int>& face_chart,
                            const ChartOptions& options = {});

// The pack stage of atlas(): scales all charts by one factor, turns and
// packs them into [0,1]^2 at options' resolution and padding, and places the
// degenerate faces. `charts` is not changed, so it can be packed again at
// another resolution. Throws Error(Usage) for options out of range or
// arrays of `charts` that do not fit together.
AtlasResult pack_charts(const AtlasCharts& charts, const PackOptions& options = {});

// The atlas of `input` (faces as given: triangles). Throws Error(Input) for
// an empty mesh, an out-of-range index or a non-finite coordinate,
// Error(Usage) for options out of range. Deterministic. Exactly
// pack_charts(compute_charts(input, chart_options(options)),
// pack_options(options)), every option checked before any work.
AtlasResult atlas(const MeshData& input, const AtlasOptions& options = {});
// The same for a file's mesh; with AtlasScope::PerMesh its meshes are those
// its document tells apart (a glTF document's meshes, an OBJ's `o` objects).
AtlasResult atlas(const MeshFile& input, const AtlasOptions& options = {});

}  // namespace intrinsic
