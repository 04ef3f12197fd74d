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
// Unions are solved lazily, in the order the pass applies them: a union one
// of whose charts an earlier union of the pass has just changed is not
// solved (it would be thrown away), nor solved later only to learn whether
// the pair is hopeless: its charts are no longer those it was proposed
// with, and the pair is proposed afresh if it is still the best. Solving
// those stale unions at the next pass (to keep the charts exactly those of
// solving every union proposed) was 28-62% of the union faces solved on
// spot, truck, cheburashka, horse_quad and decimated-max (truck 63k -> 46k,
// horse_quad 149k -> 57k), for the same charts, utilization and stretch on
// four of them and one chart fewer on cheburashka.
// A last phase merges past the per-chart bound, unions under 1% of the
// surface only, while the whole atlas's 95th percentile of face stretch stays
// within it (docs/maths.md §9.7): a small closed part (ogre's ~30 small
// pieces, 4-11 charts each) cannot keep every piece under the bound, while
// one or two charts above it are a small share of the atlas's surface.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <numeric>
#include <set>

#include "atlas/atlas_internal.h"
#include "atlas/batch_workers.h"
#include "atlas/thresholds.h"
#include "util/parallel_for.h"

namespace intrinsic::detail {
namespace {

using Pair = std::pair<int, int>;
Pair key(int c, int d) { return {std::min(c, d), std::max(c, d)}; }

// A union as proposed: its faces and the limits it is judged by, fixed when
// it is proposed (the same whenever it is solved).
struct UnionTask {
  std::vector<int> faces;  // sorted
  std::vector<int> from;   // the faces of the chart merged in (sorted)
  std::vector<int> cuts;   // both charts' cuts (ChartMesh::cuts)
  int component = 0;
  double limit = INFINITY, face_limit = INFINITY;
  double min_fill = 0;  // of its smallest box (ChartBox::fill)
};

struct UnionResult {
  FlatChart merged;
  bool valid = false;
  double stretch = INFINITY;  // of the union's map, when it flattened
};

// The half-edges (both sides) of every piece of the border between the
// chart merged in and the other but the longest: the cuts that keep a union
// closing a tube (two charts meeting along two separate borders) a disk.
// Empty when the border is one piece.
std::vector<int> tube_cuts(const MeshData& input, const CleanMesh& clean, const UnionTask& task) {
  std::vector<std::pair<int, int>> border;  // (half-edge in `from`, its twin)
  for (int f : task.from)
    for (int c = 0; c < 3; ++c) {
      const int g = clean.glued[3 * f + c];
      if (g < 0 || std::binary_search(task.from.begin(), task.from.end(), g) ||
          !std::binary_search(task.faces.begin(), task.faces.end(), g) ||
          std::binary_search(task.cuts.begin(), task.cuts.end(), 3 * f + c))
        continue;
      for (int e = 0; e < 3; ++e)
        if (clean.glued[3 * g + e] == f &&
            std::minmax(input.F(g, e), input.F(g, (e + 1) % 3)) == std::minmax(input.F(f, c), input.F(f, (c + 1) % 3)))
          border.emplace_back(3 * f + c, 3 * g + e);
    }
  // Pieces: border edges joined at shared vertices (union-find on edges).
  std::vector<int> parent(border.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  std::map<int, int> at_vertex;
  for (size_t i = 0; i < border.size(); ++i)
    for (int end = 0; end < 2; ++end) {
      const int h = border[i].first, v = input.F(h / 3, (h % 3 + end) % 3);
      auto [it, fresh] = at_vertex.emplace(v, static_cast<int>(i));
      if (!fresh) parent[root(static_cast<int>(i))] = root(it->second);
    }
  std::map<int, double> length;
  for (size_t i = 0; i < border.size(); ++i) {
    const int h = border[i].first;
    length[root(static_cast<int>(i))] += (input.V.row(input.F(h / 3, h % 3)) - input.V.row(input.F(h / 3, (h % 3 + 1) % 3))).norm();
  }
  if (length.size() < 2) return {};
  int keep = length.begin()->first;
  for (const auto& [r, l] : length)
    if (l > length[keep]) keep = r;
  std::vector<int> cuts = task.cuts;
  for (size_t i = 0; i < border.size(); ++i)
    if (root(static_cast<int>(i)) != keep) cuts.push_back(border[i].first), cuts.push_back(border[i].second);
  std::sort(cuts.begin(), cuts.end());
  return cuts;
}

UnionResult solve_union(const MeshData& input, const CleanMesh& clean, const ChartOptions& options,
                        const UnionTask& task) {
  UnionResult r;
  r.merged.mesh = chart_mesh(input, clean, task.faces, task.cuts);
  r.merged.summary.component = task.component;
  ChartStatus status = flatten_chart(r.merged, options.chart_map, options.degenerate_ratio);
  if (status == ChartStatus::NotDisk) {
    // Two charts closing a tube: the union stays open along all but the
    // longest piece of their border (a pipe becomes one strip).
    std::vector<int> cuts = tube_cuts(input, clean, task);
    if (!cuts.empty()) {
      r.merged = FlatChart();
      r.merged.mesh = chart_mesh(input, clean, task.faces, std::move(cuts));
      r.merged.summary.component = task.component;
      status = flatten_chart(r.merged, options.chart_map, options.degenerate_ratio);
    }
  }
  if (status != ChartStatus::Valid) return r;
  r.stretch = r.merged.summary.face_stretch_p95;
  const bool packs = static_cast<long>(task.faces.size()) < kSparseMinFaces ||
                     packs_well(chart_box(r.merged), clean.surface_area, clean.component_diameter[task.component]);
  r.valid = within_stretch(r.merged.summary, task.limit, task.face_limit) && r.merged.box_fill >= task.min_fill && packs;
  return r;
}

// What one merge phase remembers about failed pairs (true: hopeless, never
// retried; false: retried once a chart changes).
struct PairMemory {
  double bound = INFINITY;
  std::map<Pair, bool> failed;
  bool hopeless(double stretch) const {
    return std::isfinite(stretch) && stretch - 1 > kHopelessStretchFactor * (bound - 1);
  }
};

struct MergeContext {
  const MeshData& input;
  const CleanMesh& clean;
  const ChartOptions& options;
  BatchWorkers& workers;
  // Edges whose faces' normals are closer than this (the segmentation's
  // sharp angle) join charts; across sharper ones (a box's edges, a
  // panel's folded rim) charts stay apart, as texture artists cut there.
  double cos_sharp = -2;
};

// The neighbour chart `c` shares most glued edges with, counting only edges
// that are not sharp (but every edge of a sliver), among the pairs not
// failed; -1 if none.
int best_neighbour(const MergeContext& ctx, const std::vector<int>& owner, const FlatChart& chart, int c,
                   const PairMemory& memory) {
  std::map<int, int> shared;
  // A sliver (under min_chart_faces) may join across a sharp edge: alone it
  // is a chart no one wants.
  const double cos_sharp = static_cast<int>(chart.mesh.faces.size()) < ctx.options.min_chart_faces ? -2 : ctx.cos_sharp;
  for (int f : chart.mesh.faces)
    for (int k = 0; k < 3; ++k) {
      const int g = ctx.clean.glued[3 * f + k];
      if (g >= 0 && owner[g] >= 0 && owner[g] != c && ctx.clean.normal[f].dot(ctx.clean.normal[g]) >= cos_sharp)
        ++shared[owner[g]];
    }
  int best = -1, most = 0;
  for (const auto& [d, n] : shared)
    if (n > most && !memory.failed.count(key(c, d))) best = d, most = n;
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
  UnionTask task;
  bool solved = false;
  UnionResult result;
};

// The state of one pass: the charts, which of them changed in it, the merges made.
struct Pass {
  std::vector<FlatChart>& charts;
  std::vector<char>& gone;
  std::vector<int>& owner;
  PairMemory& memory;
  AtlasStretch* atlas;
  std::vector<char> touched;
  int merges = 0, live = 0;
};

// Proposals from every live chart (smallest first), within the work budget.
std::vector<Proposal> propose(const MergeContext& ctx, double bound, int wanted, long& budget, Pass& pass) {
  const std::vector<FlatChart>& charts = pass.charts;
  std::vector<int> order;
  for (size_t c = 0; c < charts.size(); ++c)
    if (!pass.gone[c]) order.push_back(static_cast<int>(c));
  pass.live = static_cast<int>(order.size());
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return charts[a].mesh.faces.size() < charts[b].mesh.faces.size(); });
  std::vector<Proposal> props;
  std::set<Pair> proposed;
  for (int c : order) {
    const int d = best_neighbour(ctx, pass.owner, charts[c], c, pass.memory);
    if (d < 0 || !proposed.insert(key(c, d)).second) continue;
    if (pass.atlas && charts[c].summary.area_3d + charts[d].summary.area_3d > pass.atlas->max_union_area) {
      pass.memory.failed[key(c, d)] = true;  // too large for this phase, and charts only grow
      continue;
    }
    const long size = static_cast<long>(charts[c].mesh.faces.size() + charts[d].mesh.faces.size());
    if (size > budget) break;  // the work bound: each union is solved once more
    budget -= size;
    Proposal p{c, d, {}, false, {}};
    p.task.faces = charts[d].mesh.faces;
    p.task.faces.insert(p.task.faces.end(), charts[c].mesh.faces.begin(), charts[c].mesh.faces.end());
    std::sort(p.task.faces.begin(), p.task.faces.end());
    p.task.from = charts[c].mesh.faces;
    std::merge(charts[c].mesh.cuts.begin(), charts[c].mesh.cuts.end(), charts[d].mesh.cuts.begin(),
               charts[d].mesh.cuts.end(), std::back_inserter(p.task.cuts));
    p.task.component = charts[d].summary.component;
    // Slivers below min_chart_faces may go up to their neighbour's own stretch.
    const bool small = static_cast<int>(charts[c].mesh.faces.size()) < ctx.options.min_chart_faces;
    p.task.limit = small ? std::max(bound, charts[d].summary.face_stretch_p95) : bound;
    // Down to max_charts (wanted > 0) only validity bounds a union.
    p.task.face_limit = wanted > 0 ? INFINITY : ctx.options.max_face_stretch;
    // Compact charts pack: a union may not fill its box much less than its
    // two charts fill theirs (area-weighted), so a thin trim is not merged
    // onto a panel at an angle, nor two panels into an L (thresholds.h).
    // Down to max_charts the user asked for fewer charts, whatever shape.
    const double ac = charts[c].summary.area_3d, ad = charts[d].summary.area_3d;
    if (wanted == 0 && ac + ad > 0)
      p.task.min_fill = std::min(kMergeMinFill, kMergeFillKeep * (ac * charts[c].box_fill + ad * charts[d].box_fill) / (ac + ad));
    props.push_back(std::move(p));
  }
  return props;
}

// Solves, in parallel, the unsolved proposals from `next` on whose charts no
// earlier undecided proposal holds: whatever the earlier ones decide, these
// are needed (their charts cannot change before their turn).
void solve_needed(const MergeContext& ctx, std::vector<Proposal>& props, size_t next, const Pass& pass) {
  std::vector<char> held(pass.charts.size(), 0);
  std::vector<Proposal*> batch;
  for (size_t i = next; i < props.size(); ++i) {
    Proposal& p = props[i];
    if (pass.touched[p.c] || pass.touched[p.d]) continue;  // will not be applied
    // Solved or not, an undecided proposal may still change its charts.
    if (!p.solved && !held[p.c] && !held[p.d]) batch.push_back(&p);
    held[p.c] = held[p.d] = 1;
  }
  // Largest first, each core taking the next union when it is free
  // (batch_workers.h): dealt in turn, one large union kept its core busy
  // while the other waited at the join. Each result goes to its own
  // proposal, so nothing depends on the timing.
  std::stable_sort(batch.begin(), batch.end(),
                   [](const Proposal* a, const Proposal* b) { return a->task.faces.size() > b->task.faces.size(); });
  ctx.workers.run(static_cast<std::int64_t>(batch.size()), [&](std::int64_t i) {
    batch[i]->result = solve_union(ctx.input, ctx.clean, ctx.options, batch[i]->task);
    batch[i]->solved = true;
  });
}

// Applies one solved proposal whose charts have not changed in this pass.
void decide(Proposal& p, Pass& pass) {
  PairMemory& memory = pass.memory;
  if (!p.result.valid) {
    memory.failed[key(p.c, p.d)] = memory.hopeless(p.result.stretch);  // true: hopeless, never retried
    return;
  }
  std::vector<FlatChart>& charts = pass.charts;
  if (AtlasStretch* atlas = pass.atlas) {
    atlas->add(charts[p.c], -1), atlas->add(charts[p.d], -1), atlas->add(p.result.merged, +1);
    if (atlas->p95() > atlas->limit) {
      atlas->add(p.result.merged, -1), atlas->add(charts[p.c], +1), atlas->add(charts[p.d], +1);
      memory.failed[key(p.c, p.d)] = false;  // over the atlas's budget: retried if a chart changes
      return;
    }
  }
  pass.touched[p.c] = pass.touched[p.d] = 1;
  for (int f : charts[p.c].mesh.faces) pass.owner[f] = p.d;
  charts[p.d] = std::move(p.result.merged);
  charts[p.c] = {};
  pass.gone[p.c] = 1;
  ++pass.merges, --pass.live;
}

// One pass: proposals from every live chart (smallest first), then, in
// their order, each applied when acceptable; the unions solved in parallel
// batches of those surely needed. Returns the merges made.
int merge_pass(const MergeContext& ctx, double bound, int wanted, long& budget, std::vector<FlatChart>& charts,
               std::vector<char>& gone, std::vector<int>& owner, PairMemory& memory, AtlasStretch* atlas = nullptr) {
  Pass pass{charts, gone, owner, memory, atlas, std::vector<char>(charts.size(), 0)};
  std::vector<Proposal> props = propose(ctx, bound, wanted, budget, pass);
  for (size_t next = 0; next < props.size(); ++next) {
    Proposal& p = props[next];
    if (wanted > 0 && pass.live <= wanted) break;
    // Solved against a chart that has just changed, it would not be kept.
    if (pass.touched[p.c] || pass.touched[p.d]) continue;
    if (!p.solved) solve_needed(ctx, props, next, pass);
    decide(p, pass);
  }
  // Pairs with a changed chart may succeed now (unless hopeless).
  for (auto it = memory.failed.begin(); it != memory.failed.end();)
    it = !it->second && (pass.touched[it->first.first] || pass.touched[it->first.second]) ? memory.failed.erase(it)
                                                                                          : std::next(it);
  return pass.merges;
}

// Past the per-chart bound (still valid unions under 1% of the surface
// only), smallest chart first, while the atlas's mean stays within
// options.max_stretch.
void merge_within_atlas_stretch(const MergeContext& ctx, std::vector<FlatChart>& charts, std::vector<char>& gone,
                                std::vector<int>& owner) {
  const MeshData& input = ctx.input;
  const CleanMesh& clean = ctx.clean;
  AtlasStretch atlas;
  atlas.limit = ctx.options.max_stretch;
  for (size_t c = 0; c < charts.size(); ++c)
    if (!gone[c]) atlas.add(charts[c], +1);
  // Already over (only slivers' merges up to their neighbour's stretch can do that): nothing to spend.
  if (!(atlas.p95() <= atlas.limit)) return;
  // Only small unions: the packer puts small charts into the gaps of large
  // ones, while large merged charts pack worse (thresholds.h).
  atlas.max_union_area = kBudgetUnionShare * atlas.total;
  PairMemory memory;  // bound INFINITY: nothing is hopeless
  // Work budget: a base, plus a multiple of the faces of the small parts
  // this phase is for (thresholds.h).
  std::vector<long> part_faces(clean.components, 0);
  for (int f = 0; f < static_cast<int>(input.F.rows()); ++f)
    if (clean.good[f]) ++part_faces[clean.component[f]];
  long small_faces = 0;
  for (long n : part_faces)
    if (n * kSmallPartDivisor < static_cast<long>(input.F.rows())) small_faces += n;
  long budget = kAtlasBudgetFaces + std::min(kSmallPartFactor * small_faces, kAtlasBudgetMaxExtra);
  while (merge_pass(ctx, INFINITY, 0, budget, charts, gone, owner, memory, &atlas) > 0) {
  }
}

}  // namespace

void merge_charts(const MeshData& input, const CleanMesh& clean, const ChartOptions& options,
                  std::vector<FlatChart>& charts) {
  std::vector<int> owner(input.F.rows(), -1);
  for (size_t c = 0; c < charts.size(); ++c)
    for (int f : charts[c].mesh.faces) owner[f] = static_cast<int>(c);
  std::vector<char> gone(charts.size(), 0);
  // The cores (at most 8), kept for every pass of every phase.
  BatchWorkers workers(parallel_parts(std::int64_t{1} << 30, 1));
  const bool cones = options.segmentation == Segmentation::NormalCones && options.seams.empty();
  const MergeContext ctx{input, clean, options, workers, cones ? std::cos(options.sharp_angle_deg * M_PI / 180) : -2.0};
  PairMemory memory;
  memory.bound = options.max_stretch;
  // Merging costs a solve of every union tried: a budget of faces in all
  // (smallest charts first), more for the slivers that merging is for
  // (thresholds.h).
  long small = 0;
  for (const FlatChart& c : charts) small += static_cast<long>(c.mesh.faces.size()) < kSliverFaces;
  long budget = kMergeBudgetFaces + kMergeBudgetPerSliver * small;
  while (merge_pass(ctx, options.max_stretch, 0, budget, charts, gone, owner, memory) > 0) {
  }
  auto live = [&] { return static_cast<int>(std::count(gone.begin(), gone.end(), 0)); };
  if (options.atlas_stretch_budget && options.seams.empty() && options.min_chart_faces > 0)
    merge_within_atlas_stretch(ctx, charts, gone, owner);
  // Over the chart limit: merge past the stretch bound (never past validity),
  // with a budget of its own.
  if (options.max_charts > 0 && live() > options.max_charts) {
    memory = PairMemory();  // bound INFINITY: nothing is hopeless
    budget = kMaxChartsBudgetFaces;
    while (live() > options.max_charts &&
           merge_pass(ctx, INFINITY, options.max_charts, budget, charts, gone, owner, memory) > 0) {
    }
  }
  std::vector<FlatChart> kept;
  for (size_t c = 0; c < charts.size(); ++c)
    if (!gone[c]) kept.push_back(std::move(charts[c]));
  charts = std::move(kept);
}

}  // namespace intrinsic::detail
