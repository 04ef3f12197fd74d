// Merging small charts (issue 13: "segmentation ... seams are short"; fewer
// charts): region growing and the validity splits leave slivers of a few
// faces. Each chart below the size limit, smallest first, is merged into the
// neighbour it shares most glued edges with, and the union is flattened again
// by the same natural map and checks (chart_flatten.cpp); the merge is kept
// only when the union is valid and its mean stretch stays within the bound.
#include <algorithm>
#include <map>
#include <numeric>

#include "atlas/atlas_internal.h"

namespace intrinsic::detail {
namespace {

// Neighbouring charts of chart `c` by number of shared glued edges, most first.
std::vector<int> neighbours(const CleanMesh& clean, const std::vector<int>& owner, const FlatChart& chart, int c) {
  std::map<int, int> shared;
  for (int f : chart.mesh.faces)
    for (int k = 0; k < 3; ++k) {
      const int g = clean.glued[3 * f + k];
      if (g >= 0 && owner[g] >= 0 && owner[g] != c) ++shared[owner[g]];
    }
  std::vector<int> out;
  for (const auto& [d, n] : shared) out.push_back(d);
  std::stable_sort(out.begin(), out.end(), [&](int a, int b) { return shared[a] > shared[b]; });
  return out;
}

}  // namespace

void merge_small_charts(const MeshData& input, const CleanMesh& clean, const AtlasOptions& options,
                        std::vector<FlatChart>& charts) {
  std::vector<int> owner(input.F.rows(), -1);
  for (size_t c = 0; c < charts.size(); ++c)
    for (int f : charts[c].mesh.faces) owner[f] = static_cast<int>(c);
  std::vector<int> order(charts.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return charts[a].mesh.faces.size() < charts[b].mesh.faces.size(); });
  std::vector<char> gone(charts.size(), 0);
  for (int c : order) {
    if (gone[c] || static_cast<int>(charts[c].mesh.faces.size()) >= options.min_chart_faces) continue;
    const std::vector<int> near = neighbours(clean, owner, charts[c], c);
    for (size_t i = 0; i < near.size() && i < 3; ++i) {
      const int d = near[i];
      std::vector<int> faces = charts[d].mesh.faces;
      faces.insert(faces.end(), charts[c].mesh.faces.begin(), charts[c].mesh.faces.end());
      std::sort(faces.begin(), faces.end());
      FlatChart merged;
      merged.mesh = chart_mesh(input, clean, faces);
      merged.summary.component = charts[d].summary.component;
      if (flatten_chart(merged, options.degenerate_ratio) != ChartStatus::Valid) continue;
      if (merged.summary.stretch_l2_mean > std::max(options.max_stretch, charts[d].summary.stretch_l2_mean)) continue;
      for (int f : charts[c].mesh.faces) owner[f] = d;
      charts[d] = std::move(merged);
      gone[c] = 1;
      break;
    }
  }
  std::vector<FlatChart> kept;
  for (size_t c = 0; c < charts.size(); ++c)
    if (!gone[c]) kept.push_back(std::move(charts[c]));
  charts = std::move(kept);
}

}  // namespace intrinsic::detail
