// The stages of intrinsic::atlas (atlas.h), one file each: atlas_options.cpp
// (the options taken apart and checked), chart_stage.cpp (compute_charts and
// charts_from_ids: everything up to packing), cleaning.cpp (face adjacency
// for the computation), segmentation.cpp (region growing and splits),
// given_charts.cpp (the user's chart ids), chart_mesh.cpp (a chart as a Mesh
// of its own), chart_flatten.cpp (the natural map and the validity checks),
// chart_merge.cpp, pack_stage.cpp (pack_charts: AtlasCharts to AtlasResult),
// atlas_packing.cpp (the packer, its steps one file each under packing/).
// Fixed thresholds: thresholds.h.
#pragma once

#include <functional>

#include <algorithm>
#include <array>
#include <vector>

#include "intrinsic/atlas.h"
#include "intrinsic/mesh.h"

namespace intrinsic::detail {

// The input seen by the computation. Half-edge c of face f runs from F(f,c)
// to F(f,(c+1)%3); glued[3f+c] is the face across it when exactly two
// non-degenerate faces share the edge and list it in opposite directions
// (after `reversed`), else -1 (a seam whatever the segmentation does). Every
// chart is therefore oriented as its faces are written.
struct CleanMesh {
  std::vector<char> good;  // per face: not degenerate
  std::vector<int> glued;  // per half-edge
  std::vector<char> reversed;  // per face: taken (and, with reorient, written) 0, 2, 1; all 0 without reorient
  std::vector<Eigen::Vector3d> normal;  // unit, per face as listed (zero for degenerate faces)
  std::vector<double> area;
  double surface_area = 0;  // the sum of `area`, in face order
  std::vector<Eigen::Vector3d> centroid;  // per face: the mean of its corners
  // Per face: its place among all faces ordered by their corners' positions
  // (each face's corners sorted, then compared lexicographically), and the
  // faces in that order. Traversals break ties by it, never by the face's
  // index, so the charts do not depend on the order faces and vertices are
  // listed in.
  std::vector<int> rank, ranked;
  std::vector<int> component;  // per face: connected component (faces sharing vertices)
  std::vector<double> component_diameter;  // per component: its bounding box's diagonal
  int components = 0;
  AtlasCleaning cleaning;
};

// Error(Usage) for options out of range (atlas_options.cpp).
void check_chart_options(const ChartOptions& options);
void check_pack_options(const PackOptions& options);

CleanMesh clean_mesh(const MeshData& input, const ChartOptions& options);

// `input` with vertices within relative_distance times the bounding box
// diagonal of each other merged in the faces (V unchanged; faces refer to the
// first such vertex), for the computation only; welded counts the vertices
// merged away. relative_distance <= 0: a copy.
MeshData weld_vertices(const MeshData& input, double relative_distance, int& welded);

// The position of a face in a chart's sorted face list, or -1: a table over
// all faces for large charts (one lookup per glued edge in the traversals),
// binary search for small ones (no table of the whole mesh per small chart).
class ChartFaceIndex {
 public:
  ChartFaceIndex(const std::vector<int>& faces, int mesh_faces) : faces_(faces) {
    if (faces.size() * 16 < static_cast<size_t>(mesh_faces)) return;
    table_.assign(mesh_faces, -1);
    for (size_t i = 0; i < faces.size(); ++i) table_[faces[i]] = static_cast<int>(i);
  }
  int operator()(int f) const {
    if (!table_.empty()) return table_[f];
    auto it = std::lower_bound(faces_.begin(), faces_.end(), f);
    return it != faces_.end() && *it == f ? static_cast<int>(it - faces_.begin()) : -1;
  }

 private:
  const std::vector<int>& faces_;
  std::vector<int> table_;
};

// Cuts the user's seams (seam_edges.cpp): no face is glued across one.
// Throws Error(Input) "seam edge INDEX: ..." for the first seam
// find_seam_problem refuses.
void cut_seams(const MeshData& input, const std::vector<SeamEdge>& seams, CleanMesh& clean);

// Cuts every glued edge whose faces' normals are more than hard_angle_deg
// apart (a hard edge: no chart spans it). Returns the edges cut.
int cut_hard_edges(double hard_angle_deg, CleanMesh& clean);

// Charts as lists of face indices (sorted), each connected through glued edges.
std::vector<std::vector<int>> segment(const MeshData& input, const CleanMesh& clean, const ChartOptions& options);
// Two connected halves grown from two far-apart faces of the chart (at least two faces).
std::array<std::vector<int>, 2> split_in_two(const CleanMesh& clean, const std::vector<int>& faces);

// A chart with its own vertices: the corners of its faces, glued across its
// interior edges (so non-manifold vertices and edges of the input come apart).
struct ChartMesh {
  std::vector<int> faces;   // input faces, sorted
  std::vector<int> corner;  // per face corner (3 * k + c): local vertex
  MeshData data;            // local vertices (positions of their input vertex), faces as written (reversed ones 0, 2, 1)
  long open_edges = 0;      // half-edges not glued to another face of the chart: must all be boundary edges
  double boundary_length = 0;  // 3D length of those half-edges
  // Glued half-edges (3 f + c, both sides of each edge, sorted) kept open
  // inside the chart: a seam left where a merge closed a tube (two charts
  // meeting along two separate borders).
  std::vector<int> cuts;
};
ChartMesh chart_mesh(const MeshData& input, const CleanMesh& clean, const std::vector<int>& faces,
                     std::vector<int> cuts = {});

// Why a chart cannot be shipped as it is.
enum class ChartStatus { Valid, NotDisk, Refused, SolveFailed, Flipped, BoundaryCrossing, Sparse, Stretch };

struct FlatChart {
  ChartMesh mesh;
  MatrixX2d UV;  // per local vertex; UV area equals 3D area
  AtlasChart summary;
  // Per face of the chart (mesh.faces order): max(s1, 1/s2) at the chart's
  // own scale (the atlas's texel density) and the face's 3D area.
  std::vector<double> face_stretch, face_area;
  // The fraction of its smallest bounding box the flattened chart fills
  // (chart_box): merges keep charts compact by it.
  double box_fill = 1;
};

// Flattens `chart` (the map `map` chooses, by default the natural conformal
// map; the triangle's own plane for a single face) and checks it: a disk, no
// flipped or collapsed triangle, a simple boundary, every interior vertex
// wound once.
ChartStatus flatten_chart(FlatChart& chart, const ChartMapOptions& map, double degenerate_ratio);

// A chart's distortion within `bound` (95% of its surface stretched or
// shrunk by at most that factor) and no face past `face_bound`: the test of
// every split and merge.
inline bool within_stretch(const AtlasChart& chart, double bound, double face_bound) {
  return chart.face_stretch_p95 <= bound && chart.face_stretch_max <= face_bound;
}

// The area-weighted quantile q of per-face stretch: the smallest value x
// such that the faces with stretch <= x hold at least q of the area.
double weighted_quantile(const std::vector<double>& value, const std::vector<double>& weight, double q);

// Merges neighbouring charts while the union flattens validly within
// options.max_stretch (chart_merge.cpp), then (atlas_stretch_budget) past it
// while the whole atlas's mean stays within it, then past it down to
// options.max_charts when that is set.
void merge_charts(const MeshData& input, const CleanMesh& clean, const ChartOptions& options,
                  std::vector<FlatChart>& charts);

// A chart's smallest bounding box (whose side lies on a convex hull edge)
// and the fraction of it the chart fills (UV area = 3D area).
struct ChartBox {
  double longer = 0, shorter = 0, fill = 1;
};
ChartBox chart_box(const FlatChart& chart);
// The same before the chart is flattened, from its projection onto the
// plane of its mean normal (lengths only shrink there, so a chart sparse in
// projection is about as sparse flattened; its natural map would be solved
// only to be split).
ChartBox planar_chart_box(const ChartMesh& chart);
// What the packer takes without waste: a chart filling at least half its
// box (not a ring, a C, an L or a spiral), whose longer side is at most
// kMaxSideOverSurface times the side of a square of the whole surface's
// area (a longer one forces a larger square than the charts fill), unless
// it is a strip not much longer than its part is across in 3D (`part_diameter`,
// its connected component's bounding box diagonal: a pipe, a handle) and a
// good share of the surface, which packs lengthwise, never cut across
// (thresholds.h).
bool packs_well(const ChartBox& box, double surface_area, double part_diameter);

// Scales all charts by one factor, turns them and packs their texel masks
// with padding on a bitmap (atlas_packing.cpp, packing/), and fits the layout into
// [0,1]^2 (UVs changed in place). Returns the utilization; `overlapping` is
// 0: a mask is only placed where its dilated texels meet no taken texel.
// With options.texels_per_unit > 0 the charts keep that density instead and
// go onto pages of `resolution` texels (page k at u in [k, k + 1]; `pages`
// gets each chart's page and each page's utilization); the return value is
// then the mean utilization of the pages.
struct PageLayout {
  std::vector<int> chart_page;
  std::vector<double> page_utilization;
  std::vector<int> shrunk;  // charts scaled down to fit one page
};
double pack_flat_charts(std::vector<FlatChart>& charts, const PackOptions& options, PageLayout* pages = nullptr);

// The input's own texture coordinates as charts for pack_charts
// (repack_uvs.cpp): faces connected through shared UV rows (MeshData::FTC)
// form a chart, its UVs as they are (UV area counted as area_3d, so the
// utilization is of the UV layout); with `keep_overlaps`, charts whose UV
// triangles overlap each other become one. Error(Input) without UVs.
AtlasCharts charts_of_uvs(const MeshData& input, bool keep_overlaps);

// Per-corner UV rows for the faces no chart holds (face_chart -1: zero area
// or a repeated vertex), each with zero UV area: laid along a UV edge of a
// chart (or of such a face placed before) where that keeps every UV edge
// between at most two faces, else collapsed onto a UV of one of its vertices
// (zero_row when none has one). A corner given another vertex's UV gets a
// new row of UV (a copy), so each row belongs to one vertex. V, F: the
// output's vertices and faces (FUV in F's corner order).
// The user's chart ids cut into pieces connected through glued edges
// (given_charts.cpp), each a sorted face list, in order of their lowest
// face; degenerate faces are in none. `splits` gets, per given chart, its
// pieces beyond the first. Throws Error(Usage) naming the face for an id
// below -1 or -1 on a face that is not degenerate (the length is checked by
// the caller, before cleaning).
std::vector<std::vector<int>> given_pieces(const CleanMesh& clean, const std::vector<int>& face_chart, int& splits);

// Face groups kept in one chart (ChartOptions::face_group; face_groups.cpp).
// `flatten` flattens lists of faces into valid charts (splitting where it
// must), as the charts stage does.
using FlattenCharts = std::function<std::vector<FlatChart>(std::vector<std::vector<int>>)>;
void check_face_groups(const std::vector<int>& group, int faces);
// Returns the number of groups still split after the last round.
int keep_groups_whole(const std::vector<int>& group, const CleanMesh& clean, std::vector<FlatChart>& charts,
                      const FlattenCharts& flatten);

void place_degenerate_faces(const MatrixX3d& V, const MatrixX3i& F, const std::vector<int>& face_chart, MatrixX2d& UV,
                            MatrixX3i& FUV, int zero_row);

// atlas_per_mesh.cpp: AtlasScope::PerMesh, one atlas per glTF mesh or OBJ
// object of `document` (the one beside `input`), put side by side in one
// result.
AtlasResult atlas_per_mesh(const MeshData& input, const MeshDocument& document, const AtlasOptions& options);

}  // namespace intrinsic::detail
