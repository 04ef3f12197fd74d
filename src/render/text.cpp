// Wraps stb_easy_font: it emits axis-aligned quads in a vertex buffer, which
// we fill as scaled rectangles directly into the image.
#include "render/text.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

namespace intrinsic::render {

namespace {

constexpr int kLine = 12;  // stb_easy_font's line advance
constexpr int kGlyphHeight = 9;  // tallest glyph extent below the line top

std::vector<char> sanitize(const std::string& text) {
  std::vector<char> s;
  s.reserve(text.size() + 1);
  for (char ch : text) s.push_back(ch == '\n' || (ch >= 32 && ch < 127) ? ch : '?');
  s.push_back('\0');
  return s;
}

}  // namespace

int line_height(int scale) { return kLine * scale; }

int text_width(const std::string& text, int scale) {
  std::vector<char> s = sanitize(text);
  return stb_easy_font_width(s.data()) * scale;
}

int text_height(const std::string& text, int scale) {
  if (text.empty()) return 0;
  return (static_cast<int>(std::count(text.begin(), text.end(), '\n')) * kLine + kGlyphHeight) * scale;
}

void draw_text(Image& img, int x, int y, const std::string& text, int scale, Rgb colour) {
  // One line at a time keeps the vertex buffer small: about 270 bytes per
  // character is what stb_easy_font documents.
  std::istringstream lines(text);
  std::string line;
  int row = 0;
  while (std::getline(lines, line)) {
    std::vector<char> s = sanitize(line);
    std::vector<char> vbuf(s.size() * 400 + 64);
    const int quads = stb_easy_font_print(0, 0, s.data(), nullptr, vbuf.data(), static_cast<int>(vbuf.size()));
    for (int q = 0; q < quads; ++q) {
      // Corners 0 and 2 of each 16-byte-per-vertex quad are opposite.
      float v0[2], v2[2];
      std::memcpy(v0, vbuf.data() + q * 64, sizeof v0);
      std::memcpy(v2, vbuf.data() + q * 64 + 32, sizeof v2);
      const int x0 = x + static_cast<int>(std::lround(v0[0] * scale));
      const int y0 = y + row * kLine * scale + static_cast<int>(std::lround(v0[1] * scale));
      const int x1 = x + static_cast<int>(std::lround(v2[0] * scale));
      const int y1 = y + row * kLine * scale + static_cast<int>(std::lround(v2[1] * scale));
      fill_rect(img, {std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1)}, colour);
    }
    ++row;
  }
}

}  // namespace intrinsic::render
