// The user's charts (charts_from_ids, atlas.h): chart ids per face taken as
// the segmentation. A given chart is cut only where the computation cannot
// span it: into its pieces connected across glued edges (cleaning.cpp: not
// across a non-manifold or inconsistently oriented edge, a seam or a hard
// edge), so that every piece is one connected chart for the flattening,
// which then splits it further only where it is not a disk or its map is
// invalid.
#include <algorithm>
#include <map>
#include <string>

#include "atlas/atlas_internal.h"
#include "intrinsic/error.h"

namespace intrinsic::detail {
namespace {

void check_ids(const CleanMesh& clean, const std::vector<int>& face_chart) {
  for (size_t f = 0; f < face_chart.size(); ++f) {
    const int id = face_chart[f];
    if (id < -1)
      throw_usage("face " + std::to_string(f) + ": chart id " + std::to_string(id) +
                  " (ids are at least 0, or -1 for a degenerate face)");
    if (id == -1 && clean.good[f])
      throw_usage("face " + std::to_string(f) + ": chart id -1, but the face is not degenerate (every other face needs a chart)");
  }
}

}  // namespace

std::vector<std::vector<int>> given_pieces(const CleanMesh& clean, const std::vector<int>& face_chart, int& splits) {
  check_ids(clean, face_chart);
  const int nf = static_cast<int>(face_chart.size());
  std::vector<char> taken(nf, 0);
  std::map<int, int> pieces_of;  // given id -> its pieces
  std::vector<std::vector<int>> pieces;
  std::vector<int> stack;
  for (int seed = 0; seed < nf; ++seed) {
    if (!clean.good[seed] || taken[seed]) continue;
    const int id = face_chart[seed];
    std::vector<int> piece;
    taken[seed] = 1;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      piece.push_back(f);
      for (int c = 0; c < 3; ++c) {
        const int g = clean.glued[3 * f + c];
        if (g >= 0 && !taken[g] && face_chart[g] == id) taken[g] = 1, stack.push_back(g);
      }
    }
    std::sort(piece.begin(), piece.end());
    pieces.push_back(std::move(piece));
    ++pieces_of[id];
  }
  splits = 0;
  for (const auto& [id, n] : pieces_of) splits += n - 1;
  return pieces;
}

}  // namespace intrinsic::detail
