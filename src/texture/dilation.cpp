// Dilation of the transferred charts ("edge padding"): texels around each
// chart take the colour of its border, ring by ring, so bilinear filtering
// and mipmaps near seams average chart colour, not background. A ring is the
// empty texels 8-adjacent to what is filled; each takes the mean of its
// filled 4-neighbours, or of its filled diagonal ones when it has none (the
// corners of a ring). Values of a ring depend only on earlier rings, so the
// result does not depend on the visiting order.
#include <cstdint>

#include "texture/texture_internal.h"

namespace intrinsic::detail {

long dilate(std::vector<float>& value, std::vector<char>& filled, int width, int height, int channels, int rings) {
  auto at = [width](int x, int y) { return static_cast<std::size_t>(y) * width + x; };
  // The first frontier: empty texels next to a filled one.
  std::vector<std::int64_t> frontier;
  std::vector<char> queued(filled.size(), 0);
  auto push_neighbours = [&](int x, int y, std::vector<std::int64_t>& list) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
        const std::size_t j = at(nx, ny);
        if (!filled[j] && !queued[j]) queued[j] = 1, list.push_back(static_cast<std::int64_t>(j));
      }
  };
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (filled[at(x, y)]) {
        // Only border texels can have empty neighbours; the check is cheap.
        push_neighbours(x, y, frontier);
      }
  long added = 0;
  std::vector<float> ring_values;
  for (int ring = 0; (rings < 0 || ring < rings) && !frontier.empty(); ++ring) {
    ring_values.assign(frontier.size() * channels, 0.0f);
    for (std::size_t k = 0; k < frontier.size(); ++k) {
      const int x = static_cast<int>(frontier[k] % width), y = static_cast<int>(frontier[k] / width);
      int count = 0;
      for (int pass = 0; pass < 2 && count == 0; ++pass)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const bool straight = (dx == 0) != (dy == 0);
            if ((pass == 0) != straight || (dx == 0 && dy == 0)) continue;
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= width || ny >= height || !filled[at(nx, ny)]) continue;
            for (int c = 0; c < channels; ++c) ring_values[k * channels + c] += value[at(nx, ny) * channels + c];
            ++count;
          }
      for (int c = 0; c < channels; ++c) ring_values[k * channels + c] /= static_cast<float>(count);
    }
    std::vector<std::int64_t> next;
    for (std::size_t k = 0; k < frontier.size(); ++k) {
      const std::size_t j = static_cast<std::size_t>(frontier[k]);
      for (int c = 0; c < channels; ++c) value[j * channels + c] = ring_values[k * channels + c];
      filled[j] = 1;
    }
    added += static_cast<long>(frontier.size());
    for (std::int64_t j : frontier) push_neighbours(static_cast<int>(j % width), static_cast<int>(j / width), next);
    frontier.swap(next);
  }
  return added;
}

}  // namespace intrinsic::detail
