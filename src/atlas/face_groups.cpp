// Face groups kept whole (ChartOptions::face_group, atlas.h). Hosts that
// store one UV per polygon corner, as Blender stores loops, cannot write a
// polygon whose triangles lie in different charts: the corners the
// triangles share take one chart's UVs and the other triangle is stretched
// across the atlas to reach them. Once the charts are valid, every group
// found in several charts goes whole to the chart that holds most of its
// area, and only the charts that changed are flattened again; a chart that
// then fails its checks is split where the flattening splits it, which can
// cut a group anew, hence a few rounds.
#include <algorithm>
#include <numeric>
#include <string>

#include "atlas/atlas_internal.h"
#include "intrinsic/error.h"

namespace intrinsic::detail {
namespace {

constexpr int kGroupRounds = 4;

// Per face: the index of its chart in `charts`, -1 for faces in none.
std::vector<int> chart_of_faces(int faces, const std::vector<FlatChart>& charts) {
  std::vector<int> chart(faces, -1);
  for (size_t k = 0; k < charts.size(); ++k)
    for (int f : charts[k].mesh.faces) chart[f] = static_cast<int>(k);
  return chart;
}

// Moves every split group into its largest chart (by 3D area; ties to the
// lower chart index); marks the charts that gained or lost faces. Returns
// the number of groups that were split.
int gather_groups(const std::vector<int>& group, const CleanMesh& clean, std::vector<int>& chart,
                  std::vector<char>& changed) {
  std::vector<int> order(group.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return group[a] < group[b]; });
  int split = 0;
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    while (j < order.size() && group[order[j]] == group[order[i]]) ++j;
    if (group[order[i]] >= 0) {
      int owner = -1;
      double best = -1;
      bool several = false;
      for (size_t k = i; k < j; ++k) {
        const int c = chart[order[k]];
        if (c < 0) continue;
        if (owner >= 0 && c != owner) several = true;
        double area = 0;
        for (size_t m = i; m < j; ++m)
          if (chart[order[m]] == c) area += clean.area[order[m]];
        if (area > best || (area == best && c < owner)) best = area, owner = c;
      }
      if (several) {
        ++split;
        for (size_t k = i; k < j; ++k) {
          int& c = chart[order[k]];
          if (c < 0 || c == owner) continue;
          changed[c] = changed[owner] = 1;
          c = owner;
        }
      }
    }
    i = j;
  }
  return split;
}

}  // namespace

void check_face_groups(const std::vector<int>& group, int faces) {
  if (group.empty()) return;
  if (group.size() != static_cast<size_t>(faces))
    throw_usage("the face groups number " + std::to_string(group.size()) + " for " + std::to_string(faces) +
                " faces (one per face, or none)");
  for (size_t f = 0; f < group.size(); ++f)
    if (group[f] < -1)
      throw_usage("face " + std::to_string(f) + ": group " + std::to_string(group[f]) +
                  " (groups are at least 0, or -1 for none)");
}

int keep_groups_whole(const std::vector<int>& group, const CleanMesh& clean, std::vector<FlatChart>& charts,
                      const FlattenCharts& flatten) {
  if (group.empty()) return 0;
  const int faces = static_cast<int>(group.size());
  for (int round = 0; round <= kGroupRounds; ++round) {
    std::vector<int> chart = chart_of_faces(faces, charts);
    std::vector<char> changed(charts.size(), 0);
    const int split = gather_groups(group, clean, chart, changed);
    if (split == 0 || round == kGroupRounds) return split;
    // The changed charts' faces, as ids for given_pieces, which cuts them
    // into connected pieces; the unchanged charts are kept as they are.
    std::vector<int> ids(faces, -1);
    for (int f = 0; f < faces; ++f)
      if (chart[f] >= 0 && changed[chart[f]]) ids[f] = chart[f];
      else if (clean.good[f]) ids[f] = static_cast<int>(charts.size());  // not regathered
    int pieces_split = 0;
    std::vector<std::vector<int>> pieces;
    for (std::vector<int>& p : given_pieces(clean, ids, pieces_split))
      if (ids[p.front()] < static_cast<int>(charts.size())) pieces.push_back(std::move(p));
    std::vector<FlatChart> kept;
    for (size_t k = 0; k < charts.size(); ++k)
      if (!changed[k]) kept.push_back(std::move(charts[k]));
    for (FlatChart& c : flatten(std::move(pieces))) kept.push_back(std::move(c));
    charts = std::move(kept);
  }
  return 0;
}

}  // namespace intrinsic::detail
