// Colour bar with tick labels for scalar-field pictures, and the page layout
// (title strip, plot area, bar strip) of a face-values image.
#pragma once

#include <string>
#include <vector>

#include "render/image.h"

namespace intrinsic::render {

struct FaceValuesLayout {
  Rect title;  // strip across the top (empty height when there is no title)
  Rect plot;   // where the mesh goes
  Rect bar;    // the colour gradient itself; labels go to its right
  int text_scale = 1;
};

FaceValuesLayout face_values_layout(int width, int height, bool has_title);

// Maps a value to [0, 1] for the colour map: clamped, log-spaced if asked;
// NaN stays NaN (grey). lo == hi maps everything finite to the middle.
double normalise_value(double v, double lo, double hi, bool log_scale);

// Bottom row of `bar` is colormap(0) (lo), top row colormap(1) (hi); a frame
// is drawn just outside it and five tick labels to its right.
void draw_colour_bar(Image& img, Rect bar, double lo, double hi, bool log_scale, int text_scale);

// Label values: lo and hi first and last, "nice" round values (1, 2, 5 x
// 10^k steps, or powers of ten on a wide log scale) in between.
std::vector<double> tick_values(double lo, double hi, bool log_scale);

// Short, fixed-width-ish number for tick labels ("0.25", "1.5e+03").
std::string format_tick(double v);

}  // namespace intrinsic::render
