// Merging neighbouring charts (fewer, larger charts, shorter seams). Region
// growing and the validity splits leave more charts than the distortion
// bound needs. In passes, every chart proposes the neighbour it shares most
// glued edges with; the unions are flattened (in parallel, the same map and
// checks as every chart: chart_flatten.cpp) and kept, smallest chart first,
// when valid and within the stretch bound (within_stretch: 95% of the
// union's surface stretched by at most max_stretch, no face past
// max_face_stretch). A pair that failed is not tried again until one of its
// charts has changed, and never again when its union's stretch was far over
// the bound (more than four times as far above 1): on the assets such pairs
// failed on every retry as the neighbour grew (spot: a union at 2.29 retried
// at 2.07, 2.06, 1.89), and their solves used up the work budget that other
// pairs can use. The unions solved are bounded in total size (a work budget).
// A last phase merges past the per-chart bound, unions under 1% of the
// surface only, while the whole atlas's 95th percentile of face stretch stays
// within it (docs/maths.md §9.7): a small closed part (ogre's ~30 small
// pieces, 4-11 charts each) cannot keep every piece under the bound, while
// one or two charts above it are a small share of the atlas's surface.
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include "atlas/atlas_internal.h"
#include "atlas/thresholds.h"
#include "util/parallel_for.h"

namespace intrinsic::detail {
namespace {

// The neighbour chart `c` shares most glued edges with, among those not in `skip`; -1 if none.
int best_neighbour(const CleanMesh& clean, const std::vector<int>& owner, const FlatChart& chart, int c,
                   const std::map<std::pair<int, int>, bool>& skip) {
  std::map<int, int> shared;
  for (int f : chart.mesh.faces)
    for (int k = 0; k < 3; ++k) {
      const int g = clean.glued[3 * f + k];
      if (g >= 0 && owner[g] >= 0 && owner[g] != c) ++shared[owner[g]];
    }
  int best = -1, most = 0;
  for (const auto& [d, n] : shared)
    if (n > most && !skip.count({std::min(c, d), std::max(c, d)})) best = d, most = n;
  return best;
}

// The whole atlas's per-face stretch as a histogram of 3D area (bins of
// 0.001 above 1, the last one open), updated merge by merge: the atlas's
// 95th percentile after a merge without revisiting every face. It may not
// exceed `limit` (each bin counts at its upper edge: never under).
struct AtlasStretch {
  static constexpr double kBin = 1e-3;
  static constexpr int kBins = 4096;
  std::vector<double> area = std::vector<double>(kBins, 0.0);
  double total = 0;
  double limit = INFINITY;
  double max_union_area = INFINITY;

  void add(const FlatChart& c, double sign) {
    for (size_t f = 0; f < c.face_stretch.size(); ++f) {
      const double s = c.face_stretch[f];
      const int b = std::isfinite(s) ? std::min(kBins - 1, static_cast<int>((s - 1) / kBin)) : kBins - 1;
      area[b] += sign * c.face_area[f];
      total += sign * c.face_area[f];
    }
  }
  double p95() const {
    double below = 0;
    for (int b = 0; b < kBins; ++b) {
      below += area[b];
      if (below >= 0.95 * total) return b == kBins - 1 ? INFINITY : 1 + (b + 1) * kBin;
    }
    return INFINITY;
  }
};

struct Proposal {
  int c, d;  // merge c into d
  FlatChart merged;
  bool valid = false;
  double stretch = INFINITY;  // of the union's map, when valid
};

// One pass: proposals from every live chart (smallest first), unions solved
// in parallel, then the acceptable ones applied. Returns the merges made.
int merge_pass(const MeshData& input, const CleanMesh& clean, const ChartOptions& options, double bound,
               int wanted, long& budget, std::vector<FlatChart>& charts, std::vector<char>& gone,
               std::vector<int>& owner, std::map<std::pair<int, int>, bool>& failed, AtlasStretch* atlas = nullptr) {
  std::vector<int> order;
  for (size_t c = 0; c < charts.size(); ++c)
    if (!gone[c]) order.push_back(static_cast<int>(c));
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return charts[a].mesh.faces.size() < charts[b].mesh.faces.size(); });
  std::vector<Proposal> props;
  std::set<std::pair<int, int>> proposed;
  for (int c : order) {
    const int d = best_neighbour(clean, owner, charts[c], c, failed);
    if (d < 0 || !proposed.insert({std::min(c, d), std::max(c, d)}).second) continue;
    if (atlas && charts[c].summary.area_3d + charts[d].summary.area_3d > atlas->max_union_area) {
      failed[{std::min(c, d), std::max(c, d)}] = true;  // too large for this phase, and charts only grow
      continue;
    }
    const long size = static_cast<long>(charts[c].mesh.faces.size() + charts[d].mesh.faces.size());
    if (size > budget) break;  // the work bound: each union is solved once more
    budget -= size;
    props.push_back({c, d, {}, false});
  }
  const std::int64_t n = static_cast<std::int64_t>(props.size());
  const int parts = parallel_parts(n, 1);
  parallel_for_parts(parts, parts, [&](int part, std::int64_t, std::int64_t) {
    for (std::int64_t i = part; i < n; i += parts) {
      Proposal& p = props[i];
      std::vector<int> faces = charts[p.d].mesh.faces;
      faces.insert(faces.end(), charts[p.c].mesh.faces.begin(), charts[p.c].mesh.faces.end());
      std::sort(faces.begin(), faces.end());
      p.merged.mesh = chart_mesh(input, clean, faces);
      p.merged.summary.component = charts[p.d].summary.component;
      if (flatten_chart(p.merged, options.chart_map, options.degenerate_ratio) != ChartStatus::Valid) continue;
      p.stretch = p.merged.summary.face_stretch_p95;
      // Slivers below min_chart_faces may go up to their neighbour's own stretch.
      const bool small = static_cast<int>(charts[p.c].mesh.faces.size()) < options.min_chart_faces;
      const double limit = small ? std::max(bound, charts[p.d].summary.face_stretch_p95) : bound;
      // Down to max_charts (wanted > 0) only validity bounds a union.
      p.valid = within_stretch(p.merged.summary, limit, wanted > 0 ? INFINITY : options.max_face_stretch) &&
                (static_cast<long>(faces.size()) < kSparseMinFaces || packs_well(chart_box(p.merged), clean.surface_area));
    }
  });
  std::vector<char> touched(charts.size(), 0);
  int merges = 0, live = static_cast<int>(order.size());
  for (Proposal& p : props) {
    if (wanted > 0 && live <= wanted) break;
    if (!p.valid) {
      // true: hopeless, never retried
      failed[{std::min(p.c, p.d), std::max(p.c, p.d)}] = std::isfinite(p.stretch) && p.stretch - 1 > kHopelessStretchFactor * (bound - 1);
      continue;
    }
    if (touched[p.c] || touched[p.d]) continue;  // solved against a chart that has just changed: next pass
    if (atlas) {
      atlas->add(charts[p.c], -1), atlas->add(charts[p.d], -1), atlas->add(p.merged, +1);
      if (atlas->p95() > atlas->limit) {
        atlas->add(p.merged, -1), atlas->add(charts[p.c], +1), atlas->add(charts[p.d], +1);
        failed[{std::min(p.c, p.d), std::max(p.c, p.d)}] = false;  // over the atlas's budget: retried if a chart changes
        continue;
      }
    }
    touched[p.c] = touched[p.d] = 1;
    for (int f : charts[p.c].mesh.faces) owner[f] = p.d;
    charts[p.d] = std::move(p.merged);
    charts[p.c] = {};
    gone[p.c] = 1;
    ++merges, --live;
  }
  // Pairs with a changed chart may succeed now (unless hopeless).
  for (auto it = failed.begin(); it != failed.end();)
    it = !it->second && (touched[it->first.first] || touched[it->first.second]) ? failed.erase(it) : std::next(it);
  return merges;
}

// Past the per-chart bound (still valid unions under 1% of the surface
// only), smallest chart first, while the atlas's mean stays within
// options.max_stretch.
void merge_within_atlas_stretch(const MeshData& input, const CleanMesh& clean, const ChartOptions& options,
                                std::vector<FlatChart>& charts, std::vector<char>& gone, std::vector<int>& owner) {
  AtlasStretch atlas;
  atlas.limit = options.max_stretch;
  for (size_t c = 0; c < charts.size(); ++c)
    if (!gone[c]) atlas.add(charts[c], +1);
  // Already over (only slivers' merges up to their neighbour's stretch can do that): nothing to spend.
  if (!(atlas.p95() <= atlas.limit)) return;
  // Only small unions: the packer puts small charts into the gaps of large
  // ones, while large merged charts pack worse (thresholds.h).
  atlas.max_union_area = kBudgetUnionShare * atlas.total;
  std::map<std::pair<int, int>, bool> failed;
  // Work budget: a base, plus a multiple of the faces of the small parts
  // this phase is for (thresholds.h).
  std::vector<long> part_faces(clean.components, 0);
  for (int f = 0; f < static_cast<int>(input.F.rows()); ++f)
    if (clean.good[f]) ++part_faces[clean.component[f]];
  long small_faces = 0;
  for (long n : part_faces)
    if (n * kSmallPartDivisor < static_cast<long>(input.F.rows())) small_faces += n;
  long budget = kAtlasBudgetFaces + std::min(kSmallPartFactor * small_faces, kAtlasBudgetMaxExtra);
  while (merge_pass(input, clean, options, INFINITY, 0, budget, charts, gone, owner, failed, &atlas) > 0) {
  }
}

}  // namespace

void merge_charts(const MeshData& input, const CleanMesh& clean, const ChartOptions& options,
                  std::vector<FlatChart>& charts) {
  std::vector<int> owner(input.F.rows(), -1);
  for (size_t c = 0; c < charts.size(); ++c)
    for (int f : charts[c].mesh.faces) owner[f] = static_cast<int>(c);
  std::vector<char> gone(charts.size(), 0);
  std::map<std::pair<int, int>, bool> failed;
  // Merging costs a solve of every union tried: a budget of faces in all
  // (smallest charts first), more for the slivers that merging is for
  // (thresholds.h).
  long small = 0;
  for (const FlatChart& c : charts) small += static_cast<long>(c.mesh.faces.size()) < kSliverFaces;
  long budget = kMergeBudgetFaces + kMergeBudgetPerSliver * small;
  while (merge_pass(input, clean, options, options.max_stretch, 0, budget, charts, gone, owner, failed) > 0) {
  }
  auto live = [&] { return static_cast<int>(std::count(gone.begin(), gone.end(), 0)); };
  if (options.atlas_stretch_budget && options.seams.empty() && options.min_chart_faces > 0)
    merge_within_atlas_stretch(input, clean, options, charts, gone, owner);
  // Over the chart limit: merge past the stretch bound (never past validity),
  // with a budget of its own.
  if (options.max_charts > 0 && live() > options.max_charts) {
    failed.clear();
    budget = kMaxChartsBudgetFaces;
    while (live() > options.max_charts &&
           merge_pass(input, clean, options, INFINITY, options.max_charts, budget, charts, gone, owner, failed) > 0) {
    }
  }
  std::vector<FlatChart> kept;
  for (size_t c = 0; c < charts.size(); ++c)
    if (!gone[c]) kept.push_back(std::move(charts[c]));
  charts = std::move(kept);
}

}  // namespace intrinsic::detail
