// Segmentation into disk charts (each one can then be flattened): region
// growing from seeds over glued edges, a face joining a chart while its normal
// stays within a cone around the chart's mean normal and never across a sharp
// edge (the charts are then close to height fields, where the natural map of
// paper section 4.2 rarely folds). Seeds are taken on the frontier of the
// charts grown so far, so charts grow outward like a front. Charts that turn
// out not to be disks, or whose map is invalid, are split in two by
// split_in_two (atlas.cpp). Then one Lloyd step regrows every chart at once
// from its most interior face, flat regions taken whole, for compact charts
// (docs/maths.md §9.6b). Ties are broken by the faces' rank by position
// (CleanMesh::rank), so the charts do not depend on the listing order.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <deque>
#include <queue>

#include "atlas/atlas_internal.h"
#include "atlas/thresholds.h"

namespace intrinsic::detail {
namespace {

// The glued neighbours of face f, in increasing rank (-1 last): the
// traversals below then depend neither on where each face's listing starts,
// its winding (a face written reversed lists its edges in another order),
// nor on the order of the faces (CleanMesh::rank).
std::array<int, 3> neighbours(const CleanMesh& m, int f) {
  std::array<int, 3> g = {m.glued[3 * f], m.glued[3 * f + 1], m.glued[3 * f + 2]};
  std::sort(g.begin(), g.end(),
            [&](int a, int b) { return (a < 0 ? INT32_MAX : m.rank[a]) < (b < 0 ? INT32_MAX : m.rank[b]); });
  return g;
}


struct Grower {
  const MeshData& in;
  const CleanMesh& m;
  double cos_cone, cos_sharp;
  std::vector<int> label;  // chart per face, -1 unassigned
  std::deque<int> frontier;

  // Grows chart `id` from `seed`; returns its faces (sorted).
  std::vector<int> grow(int seed, int id) {
    using Item = std::pair<double, int>;  // (cost, rank): smallest cost first, then smallest rank
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    std::vector<int> faces;
    heap.emplace(0.0, m.rank[seed]);
    while (!heap.empty()) {
      const int f = m.ranked[heap.top().second];
      heap.pop();
      if (label[f] >= 0) continue;
      if (!faces.empty() && m.normal[f].dot(sum.normalized()) < cos_cone) continue;
      label[f] = id;
      faces.push_back(f);
      sum += m.area[f] * m.normal[f] + 1e-300 * m.normal[f];
      const Eigen::Vector3d mean = sum.normalized();
      for (int c = 0; c < 3; ++c) {
        const int g = m.glued[3 * f + c];
        if (g < 0 || label[g] >= 0 || m.normal[f].dot(m.normal[g]) < cos_sharp) continue;
        heap.emplace(1 - m.normal[g].dot(mean), m.rank[g]);
      }
    }
    for (int f : faces)
      for (int g : neighbours(m, f))
        if (g >= 0 && label[g] < 0) frontier.push_back(g);
    std::sort(faces.begin(), faces.end());
    return faces;
  }
};

// Breadth-first distances (in faces) from `source` inside the chart; the last face reached.
int farthest(const CleanMesh& m, const std::vector<int>& faces, const ChartFaceIndex& index, int source) {
  std::vector<char> seen(faces.size(), 0);
  std::deque<int> queue{source};
  seen[index(source)] = 1;
  int last = source;
  while (!queue.empty()) {
    last = queue.front();
    queue.pop_front();
    for (int g : neighbours(m, last)) {
      const int k = g < 0 ? -1 : index(g);
      if (k >= 0 && !seen[k]) seen[k] = 1, queue.push_back(g);
    }
  }
  return last;
}

// Straightens chart boundaries: a face with two of its three glued
// neighbours in one other chart (a tooth of a ragged boundary) moves there,
// unless one of those two edges is sharp. It has at most one neighbour left
// in its own chart, so that chart stays connected. A few passes, in face
// order of rank (deterministic, whatever order the faces are listed in).
void straighten(const CleanMesh& m, double cos_sharp, std::vector<int>& label) {
  for (int pass = 0; pass < 4; ++pass) {
    int moved = 0;
    for (int f : m.ranked) {
      if (label[f] < 0) continue;
      int other[3];
      for (int c = 0; c < 3; ++c) {
        const int g = m.glued[3 * f + c];
        other[c] = g >= 0 && label[g] >= 0 && label[g] != label[f] && m.normal[f].dot(m.normal[g]) >= cos_sharp
                       ? label[g] : -1;
      }
      int to = -1;
      for (int c = 0; c < 3 && to < 0; ++c)
        for (int d = c + 1; d < 3; ++d)
          if (other[c] >= 0 && other[c] == other[d]) to = other[c];
      if (to >= 0) label[f] = to, ++moved;
    }
    if (moved == 0) break;
  }
}


// Flat regions: faces joined across glued edges while their normals stay
// within kPlanarDeg degrees of the region's first face (in rank order).
// Each region's faces are listed together, the regions in rank order.
struct FlatRegions {
  std::vector<int> of;     // per face: region, -1 for bad faces
  std::vector<int> start;  // region r's faces are faces[start[r] .. start[r + 1])
  std::vector<int> faces;
};
FlatRegions flat_regions(const CleanMesh& m, double cos_sharp) {
  const int nf = static_cast<int>(m.good.size());
  const double cos_flat = std::cos(kPlanarDeg * M_PI / 180);
  FlatRegions r{std::vector<int>(nf, -1), {0}, {}};
  int count = 0;
  for (int seed : m.ranked) {
    if (!m.good[seed] || r.of[seed] >= 0) continue;
    r.of[seed] = count;
    const size_t first = r.faces.size();
    r.faces.push_back(seed);
    for (size_t i = first; i < r.faces.size(); ++i)
      for (int g : neighbours(m, r.faces[i]))
        if (g >= 0 && r.of[g] < 0 && m.normal[g].dot(m.normal[seed]) >= cos_flat &&
            m.normal[g].dot(m.normal[r.faces[i]]) >= cos_sharp)
          r.of[g] = count, r.faces.push_back(g);
    r.start.push_back(static_cast<int>(r.faces.size()));
    ++count;
  }
  return r;
}

// Each chart's most interior face (the farthest, in glued steps, from its
// border; the lowest rank on ties), from a search started at every border
// face at once.
std::vector<int> interior_faces(const CleanMesh& m, const std::vector<int>& label, int charts) {
  const int nf = static_cast<int>(label.size());
  std::vector<int> depth(nf, -1);
  std::deque<int> queue;
  for (int f : m.ranked) {
    if (label[f] < 0) continue;
    bool border = false;
    for (int c = 0; c < 3; ++c) border |= m.glued[3 * f + c] < 0 || label[m.glued[3 * f + c]] != label[f];
    if (border) depth[f] = 0, queue.push_back(f);
  }
  while (!queue.empty()) {
    const int f = queue.front();
    queue.pop_front();
    for (int g : neighbours(m, f))
      if (g >= 0 && depth[g] < 0 && label[g] == label[f]) depth[g] = depth[f] + 1, queue.push_back(g);
  }
  std::vector<int> seed(charts, -1);
  for (int f : m.ranked)
    if (label[f] >= 0 && (seed[label[f]] < 0 || depth[f] > depth[seed[label[f]]])) seed[label[f]] = f;
  return seed;
}

// One step of a Lloyd relaxation of the charts (as variational shape
// approximation does): every chart reseeded at its most interior face and
// all of them regrown at once, each face going to the chart that reaches it
// at the least cost: its normal's deviation from the chart's mean normal
// plus kCompactWeight times its path length from the seed over the chart's
// radius, within the chart's cone and never across a sharp edge; a flat
// region (flat_regions) is taken whole by the first chart to reach it, so a
// flat panel is never shared between charts. The charts
// become compact cells whose borders run along creases and bisectors, not
// along the ragged edge of a cone; each stays connected (a face joins from a
// neighbour of its own chart). Faces no chart reaches are left at -1.
std::vector<int> regrow(const CleanMesh& m, const FlatRegions& flat, const std::vector<int>& label, int charts,
                        double cos_cone, double cos_sharp) {
  const int nf = static_cast<int>(label.size());
  std::vector<Eigen::Vector3d> normal(charts, Eigen::Vector3d::Zero());
  std::vector<double> area(charts, 0.0);
  for (int f : m.ranked)
    if (label[f] >= 0) normal[label[f]] += m.area[f] * m.normal[f], area[label[f]] += m.area[f];
  for (Eigen::Vector3d& n : normal) n = n.norm() > 0 ? n.normalized() : n;
  struct Item {
    double cost;
    int rank, chart;
    double path;
    bool operator>(const Item& o) const { return cost != o.cost ? cost > o.cost : rank > o.rank; }
  };
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  const std::vector<int> seed = interior_faces(m, label, charts);
  for (int c = 0; c < charts; ++c)
    if (seed[c] >= 0) heap.push({0.0, m.rank[seed[c]], c, 0.0});
  std::vector<int> out(nf, -1);
  while (!heap.empty()) {
    const Item it = heap.top();
    heap.pop();
    const int first = m.ranked[it.rank];
    if (out[first] >= 0) continue;
    // A flat region goes whole to the chart that reaches it first.
    const int region = flat.of[first];
    const int* begin = &flat.faces[flat.start[region]];
    const int* end = &flat.faces[0] + flat.start[region + 1];
    const double radius = std::sqrt(area[it.chart] / M_PI) + 1e-300;
    for (const int* p = begin; p != end; ++p) out[*p] = it.chart;
    for (const int* p = begin; p != end; ++p) {
      const int f = *p;
      const double at = it.path + (m.centroid[f] - m.centroid[first]).norm();
      for (int g : neighbours(m, f)) {
        if (g < 0 || out[g] >= 0 || m.normal[f].dot(m.normal[g]) < cos_sharp) continue;
        const double deviation = 1 - m.normal[g].dot(normal[it.chart]);
        if (1 - deviation < cos_cone) continue;
        const double path = at + (m.centroid[g] - m.centroid[f]).norm();
        heap.push({deviation + kCompactWeight * path / radius, m.rank[g], it.chart, path});
      }
    }
  }
  return out;
}
}  // namespace

std::vector<std::vector<int>> segment(const MeshData& input, const CleanMesh& clean, const ChartOptions& options) {
  const int nf = static_cast<int>(input.F.rows());
  // With the user's seams the charts are the pieces between them.
  const bool components = options.segmentation == Segmentation::Components || !options.seams.empty();
  Grower g{input, clean, components ? -2.0 : std::cos(options.max_normal_deviation_deg * M_PI / 180),
           components ? -2.0 : std::cos(options.sharp_angle_deg * M_PI / 180), std::vector<int>(nf, -1), {}};
  std::vector<std::vector<int>> charts;
  int next = 0;  // lowest rank that may still be unassigned
  while (true) {
    int seed = -1;
    while (!g.frontier.empty() && seed < 0) {
      if (g.label[g.frontier.front()] < 0) seed = g.frontier.front();
      g.frontier.pop_front();
    }
    while (seed < 0 && next < nf) {
      const int f = clean.ranked[next];
      if (clean.good[f] && g.label[f] < 0) seed = f;
      ++next;
    }
    if (seed < 0) break;
    charts.push_back(g.grow(seed, static_cast<int>(charts.size())));
  }
  if (components) return charts;
  // Relaxed toward compact charts; faces the regrown charts leave out start
  // charts of their own, grown as above.
  int count = static_cast<int>(charts.size());
  const FlatRegions flat = flat_regions(clean, g.cos_sharp);
  for (int step = 0; step < kRelaxSteps; ++step) {
    g.label = regrow(clean, flat, g.label, count, g.cos_cone, g.cos_sharp);
    for (int f : clean.ranked)
      if (clean.good[f] && g.label[f] < 0) g.grow(f, count++);
  }
  straighten(clean, g.cos_sharp, g.label);
  std::vector<std::vector<int>> straight(count);
  for (int f = 0; f < nf; ++f)
    if (g.label[f] >= 0) straight[g.label[f]].push_back(f);
  straight.erase(std::remove_if(straight.begin(), straight.end(), [](const std::vector<int>& c) { return c.empty(); }),
                 straight.end());
  return straight;
}

std::array<std::vector<int>, 2> split_in_two(const CleanMesh& clean, const std::vector<int>& faces) {
  const ChartFaceIndex index(faces, static_cast<int>(clean.glued.size() / 3));
  // Faces by rank: the split does not depend on the faces' order.
  std::vector<int> by_rank = faces;
  std::sort(by_rank.begin(), by_rank.end(), [&](int x, int y) { return clean.rank[x] < clean.rank[y]; });
  const int a = farthest(clean, faces, index, by_rank.front());
  const int b = farthest(clean, faces, index, a);
  // Two fronts grown together by distance (Dijkstra over the path through
  // face centroids): each face goes to the nearer of a and b, so the cut
  // runs along their bisector, straighter than the diamond of face-count
  // layers; a face is reached from one of its own side, so both halves stay
  // connected.
  std::vector<int> side(faces.size(), -1);
  std::vector<double> dist(faces.size(), INFINITY);
  using Item = std::pair<double, int>;  // (distance, rank): nearest first, then smallest rank
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  dist[index(a)] = 0, side[index(a)] = 0, heap.emplace(0.0, clean.rank[a]);
  if (b != a) dist[index(b)] = 0, side[index(b)] = 1, heap.emplace(0.0, clean.rank[b]);
  while (!heap.empty()) {
    const double d = heap.top().first;
    const int f = clean.ranked[heap.top().second];
    heap.pop();
    const int kf = index(f);
    if (d > dist[kf]) continue;
    for (int g : neighbours(clean, f)) {
      const int k = g < 0 ? -1 : index(g);
      if (k < 0) continue;
      const double dg = d + (clean.centroid[g] - clean.centroid[f]).norm();
      if (dg < dist[k]) dist[k] = dg, side[k] = side[kf], heap.emplace(dg, clean.rank[g]);
    }
  }
  // Teeth: a face with two of its neighbours on the other side goes there
  // (it has at most one on its own, so its side stays connected), a few
  // passes in face order.
  for (int pass = 0; pass < 4; ++pass) {
    int moved = 0;
    for (int f : by_rank) {
      const int k = index(f);
      if (side[k] < 0 || faces[k] == a || faces[k] == b) continue;
      int other = 0;
      for (int g : neighbours(clean, faces[k])) {
        const int j = g < 0 ? -1 : index(g);
        other += j >= 0 && side[j] >= 0 && side[j] != side[k];
      }
      if (other >= 2) side[k] = 1 - side[k], ++moved;
    }
    if (moved == 0) break;
  }
  std::array<std::vector<int>, 2> halves;
  for (size_t k = 0; k < faces.size(); ++k) halves[side[k] == 1 ? 1 : 0].push_back(faces[k]);
  if (halves[1].empty()) {  // not connected or a == b: peel one face off (the last by rank)
    halves[1].push_back(by_rank.back());
    halves[0].erase(std::find(halves[0].begin(), halves[0].end(), by_rank.back()));
  }
  return halves;
}

}  // namespace intrinsic::detail
