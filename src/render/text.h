// Pixel text for labels and captions, built from the stb_easy_font stroke
// font; glyph strokes are scaled by an integer factor so they stay crisp.
#pragma once

#include <string>

#include "render/image.h"

namespace intrinsic::render {

// Top-left of the first line at (x, y). '\n' starts a new line; characters
// outside printable ASCII are drawn as '?'.
void draw_text(Image& img, int x, int y, const std::string& text, int scale, Rgb colour);
int text_width(const std::string& text, int scale);
int text_height(const std::string& text, int scale);  // all lines, including the last line's descent
int line_height(int scale);

}  // namespace intrinsic::render
