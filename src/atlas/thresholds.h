// The atlas's fixed thresholds, in one place: the sparse-chart test, the
// merge phases' limits and work budgets, the packer's bitmap. Each value
// with the reason (and, where one was made, the measurement) behind it.
// None of them is an option: they decide how much work is spent, not what a
// valid chart is (that is ChartOptions').
#pragma once

namespace intrinsic::detail {

// --- Sparse charts (packs_well, atlas_packing.cpp) ---
// A chart must fill at least this fraction of its smallest bounding box: a
// ring, a C, a spiral, an L or a panel with a trim at an angle fills less
// and wastes the rest of its box (no packer fills the inside of an L). At
// 0.15 the shared assets' median utilization was about 0.61; at 0.5 0.68,
// with 0.65 charts doubled on some (spot 21 -> 56) for 2-4% more.
constexpr double kMinBoxFill = 0.5;
// A chart at least kStripAspect times as long as it is wide and at most
// kStripPartDiameters times as long as its part is across in 3D (a pipe, a
// trim, a handle, bent or not) is a strip: never cut for its length (cut
// across, its texture would jump). A band winding around its part (3holes'
// rim, about pi times its diameter, closed into one strip by a merge) is
// cut like any long chart: kept, it set the square's side and left the
// layout 26% full.
// Only a strip holding at least kStripMinShare of the surface is spared
// (a pipe that is most of its asset cannot be laid out better without a
// cut across); a thin beam among many parts is cut like any long chart.
constexpr double kStripAspect = 3;
constexpr double kStripPartDiameters = 2;
constexpr double kStripMinShare = 0.25;
// A chart's box's longer side is at most this many times the side of a
// square of the whole surface's area, whatever the chart's own area: the
// square holding the layout is at least as long, so a longer chart alone
// would keep it under 1 / kMaxSideOverSurface^2 (44%) full (regr01's
// hairline beams, tested only when their boxes were large, left it 31%
// full; tested always, 49%).
constexpr double kMaxSideOverSurface = 1.5;
// Only charts of at least this many faces whose box covers at least this
// share of the surface's area are tested (and split) for sparseness: the
// packer puts small masks into the gaps of the large ones, so small boxes
// hardly matter (on a 1M-vertex sphere, 98 splits of slivers under 0.5%
// left the utilization unchanged to 13 digits, with 141 charts instead of
// 45), while a thin ring or arc of little area (a lid's rim) spans a box
// that keeps the layout half empty.
constexpr int kSparseMinFaces = 4;
constexpr double kSparseMinShare = 0.005;

// --- Segmentation (segmentation.cpp) ---
// Lloyd steps of the charts grown by normal cones: each regrows every chart
// at once from its most interior face.
constexpr int kRelaxSteps = 1;
// A face's cost of joining a chart in those steps: its normal's deviation
// (1 - cos) plus this times its path length from the seed over the chart's
// radius: 0 gives the cones' ragged cells, larger values rounder ones.
constexpr double kCompactWeight = 0.5;

// Faces whose normals are within this many degrees of a flat region's
// first face belong to it (a CAD part's faces are flat to rounding; a
// scan's neighbouring faces rarely stay within a degree for long).
constexpr double kPlanarDeg = 1;

// --- Merging (chart_merge.cpp) ---
// A union must fill at least kMergeFillKeep of the area-weighted box fill of
// its two charts, or kMergeMinFill of its own box (whichever is less: two
// ragged charts may still merge into a compact one).
constexpr double kMergeFillKeep = 0.9;
constexpr double kMergeMinFill = 0.8;
// A failed pair is never retried when its union's stretch was more than this
// many times as far above 1 as the bound: on the assets such pairs failed on
// every retry as the neighbour grew (spot: 2.29, then 2.07, 2.06, 1.89), and
// their solves used up the budget other pairs can use.
constexpr double kHopelessStretchFactor = 4;
// The stretch-bounded merges solve unions of at most this many faces in
// all (smallest charts first): meshes of up to about 20k faces merge fully,
// large ones stay fast (the splits have already made every chart valid) ...
constexpr long kMergeBudgetFaces = 150000;
// ... plus this many per chart under kSliverFaces faces (a sliver the
// validity splits left, about one union with a neighbour each): on beast
// (64k faces, many slivers) the base budget alone left 655 charts, 271 under
// 20 faces; with this 294, while igea's budget grows ~10%.
constexpr long kMergeBudgetPerSliver = 500;
constexpr long kSliverFaces = 100;
// The atlas-stretch phase merges unions under this share of the surface
// only: large merged charts pack worse (with no limit bumpy-cube,
// decimated-max and suzanne fell below xatlas's utilization: 67.1% -> 59.9%,
// 60.3 -> 53.7, 66.0 -> 62.1); small parts are what the phase is for.
constexpr double kBudgetUnionShare = 0.01;
// Its work budget: this many faces of unions, plus kSmallPartFactor times
// the faces of the small parts (components under 1 / kSmallPartDivisor of
// the faces), the extra at most kAtlasBudgetMaxExtra (1,000,000 in all).
// igea and the generated sphere (one component each) get the base: with
// 60,000 igea went 211 -> 171 charts but took 12-18% longer, with 20,000 196
// charts at about the same time. ogre (124k faces, ~30 small parts of
// 500-3300 faces): 326 charts.
constexpr long kAtlasBudgetFaces = 20000;
constexpr long kSmallPartFactor = 8;
constexpr long kSmallPartDivisor = 20;
constexpr long kAtlasBudgetMaxExtra = 980000;
// Merging down to max_charts has a budget of its own (no measurement is
// recorded for it: twice the first phase's base, as the user asked for
// fewer charts and pays for the solves).
constexpr long kMaxChartsBudgetFaces = 300000;

// --- Packing (atlas_packing.cpp) ---
// The packer's bitmap is at most this many texels wide: larger textures pack
// on a coarser grid (padding rounded up to whole cells of it): the bitmap's
// memory and the placement's scans grow with its area (no measurement of
// the utilization a finer grid would gain is recorded).
constexpr int kMaxPackBitmap = 1024;

// --- The scale search (packing/scale_search.cpp) ---
// The first scale tried: the charts' area would fill kStartFill^2 (72%) of
// the square, above the utilizations the packer reaches (at most about 70%
// on the assets: docs/cli.md), so the bracket steps down toward the answer.
constexpr double kStartFill = 0.85;
// Down from it by this factor per packing until a scale fits, at most
// kBracketTries packings (0.8^42: 1e-4 of the start) before the bitmap's
// side doubles (more charts than it holds with their padding).
constexpr double kBracketStep = 0.8;
constexpr int kBracketTries = 42;
// Then bisected until the largest fitting scale is known within kFineRatio
// (0.5%), at most kBisectSteps packings.
constexpr double kFineRatio = 1.005;
constexpr int kBisectSteps = 12;
// With the extra pose angles: two bisection steps up to this factor above
// the largest scale the smallest-box poses reached.
constexpr double kAnglesRange = 1.08;
// Bitmaps of at least kHalfBitmapMinSide texels are searched on a bitmap of
// half the side first (a quarter of the texels to place), to kCoarseRatio;
// then the full bitmap is tried down from kGuessAbove times twice that scale
// in steps of kGuessStep, at most kGuessTries packings (from one step below
// kGuessAbove: see kGuessTries), with no refinement
// after: on the shared assets the refinement and the angle packings doubled
// the packing time (truck 360 -> 770 ms, spot 120 -> 225 ms) for under 1%
// of utilization on most of them.
constexpr int kHalfBitmapMinSide = 256;
constexpr double kCoarseRatio = 1.02;
constexpr double kGuessAbove = 1.03;
constexpr double kGuessStep = 1.015;
// Two tries, at 1.03 / 1.015 and 1.03 / 1.015^2 times twice the coarse
// scale: on the 17 shared assets a layout better than the coarse one was
// found at the second step on 6, at the third on 9, at none on 2 (knight,
// screwdriver), and never at 1.03 itself, which is no longer tried (every
// asset's layout the same, one full packing fewer each).
constexpr int kGuessTries = 2;

// --- Texel masks (packing/texel_mask.cpp, packing/scale_search.cpp) ---
// Masks placed as their whole frame (BoxCursors in placement.cpp): frames
// their dilated texels fill to at least kBoxFill, and small frames (at most
// kBoxSide texels more than the padding on both sides), where the corners
// given up are a few texels.
constexpr double kBoxFill = 0.9;
constexpr int kBoxSide = 6;
// Masks with more frame texels than this get no inner box (Mask::inner):
// the search for the box is a pass over the frame per mask and pose, and
// the box only moves where a search starts (never where a chart lands).
// With 96 * 96 the packing's CPU time was 4-8% higher on decimated-knight,
// suzanne, truck, horse_quad, beast, bumpy-cube and spot (with 256 * 256
// 15-30% higher; with 0, none at all, the same as 48 * 48 on the first
// four).
constexpr long kInnerBoxArea = 48 * 48;

}  // namespace intrinsic::detail
