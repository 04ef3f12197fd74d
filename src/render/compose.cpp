// Grid of panels with captions, for side-by-side comparisons. Cells are
// sized to the largest panel so differently sized inputs still line up.
#include <algorithm>
#include <cmath>
#include <string>

#include "intrinsic/error.h"
#include "intrinsic/render.h"
#include "render/image.h"
#include "render/text.h"

namespace intrinsic {

using namespace render;

Image compose_panels(const std::vector<Image>& panels, const std::vector<std::string>& captions, int columns) {
  if (panels.empty()) throw_usage("compose_panels: no panels");
  if (columns < 1) throw_usage("compose_panels: columns must be at least 1");
  if (captions.size() > panels.size()) throw_usage("compose_panels: more captions than panels");
  int cell_w = 0, cell_h = 0;
  for (const Image& p : panels) {
    if (p.width < 1 || p.height < 1 || p.rgb.size() != static_cast<std::size_t>(p.width) * p.height * 3)
      throw_usage("compose_panels: a panel is empty or malformed");
    cell_w = std::max(cell_w, p.width);
    cell_h = std::max(cell_h, p.height);
  }
  // Text grows with the cell width, but never so much that a caption line
  // is wider than its cell.
  int widest = 0;  // at scale 1
  for (const std::string& c : captions)
    for (std::size_t start = 0; start <= c.size();) {
      const std::size_t end = std::min(c.find('\n', start), c.size());
      widest = std::max(widest, text_width(c.substr(start, end - start), 1));
      start = end + 1;
    }
  int s = std::max(1, static_cast<int>(std::lround(cell_w / 150.0)));
  while (s > 1 && widest * s > cell_w) --s;
  const int pad = 6 * s;
  int caption_h = 0;
  for (const std::string& c : captions) caption_h = std::max(caption_h, text_height(c, s));
  if (caption_h > 0) caption_h += 2 * pad;

  const int n = static_cast<int>(panels.size());
  const int cols = std::min(columns, n), rows = (n + cols - 1) / cols;
  const long long total_w = static_cast<long long>(cols) * (cell_w + pad) + pad;
  const long long total_h = static_cast<long long>(rows) * (cell_h + caption_h + pad) + pad;
  if (total_w > 32768 || total_h > 32768) throw_usage("compose_panels: the combined image would be too large");
  Image out(static_cast<int>(total_w), static_cast<int>(total_h));
  for (int i = 0; i < n; ++i) {
    const int cx = pad + (i % cols) * (cell_w + pad), cy = pad + (i / cols) * (cell_h + caption_h + pad);
    const Image& p = panels[i];
    blit(out, p, cx + (cell_w - p.width) / 2, cy + (cell_h - p.height) / 2);
    if (i < static_cast<int>(captions.size())) {
      // Centre each caption line on its own.
      std::size_t start = 0;
      int line = 0;
      const std::string& c = captions[i];
      while (start <= c.size()) {
        const std::size_t end = std::min(c.find('\n', start), c.size());
        const std::string text = c.substr(start, end - start);
        draw_text(out, cx + (cell_w - text_width(text, s)) / 2, cy + cell_h + pad + line * line_height(s), text, s,
                  {20, 20, 20});
        ++line;
        start = end + 1;
      }
    }
  }
  return out;
}

}  // namespace intrinsic
