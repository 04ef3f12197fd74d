// Colour bar drawing and the face-values page layout.
#include "render/colour_bar.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "render/colormap.h"
#include "render/text.h"

namespace intrinsic::render {

namespace {
constexpr Rgb kInk = {20, 20, 20};
}

FaceValuesLayout face_values_layout(int width, int height, bool has_title) {
  FaceValuesLayout L;
  const int s = std::max(1, static_cast<int>(std::lround(std::min(width, height) / 300.0)));
  L.text_scale = s;
  const int pad = 6 * s;
  const int title_h = has_title ? line_height(s) + 2 * pad : pad;
  L.title = {0, 0, width, std::min(title_h, height)};
  // Room for a bar, tick marks and labels like "-1.23e+03".
  const int strip = std::min(width / 2, 90 * s);
  L.plot = {0, L.title.y1, width - strip, height};
  const int bx0 = width - strip + 8 * s;
  L.bar = {bx0, L.title.y1 + 2 * pad, std::min(bx0 + 16 * s, width), std::max(L.title.y1 + 2 * pad, height - 2 * pad)};
  return L;
}

double normalise_value(double v, double lo, double hi, bool log_scale) {
  if (std::isnan(v)) return v;
  if (log_scale) {
    // Non-positive values are below any positive range: clamp to the bottom.
    if (!(v > 0)) return 0;
    v = std::log(v), lo = std::log(lo), hi = std::log(hi);
  }
  if (!(hi > lo)) return v < lo ? 0 : v > hi ? 1 : 0.5;
  return std::clamp((v - lo) / (hi - lo), 0.0, 1.0);
}

std::string format_tick(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

std::vector<double> tick_values(double lo, double hi, bool log_scale) {
  std::vector<double> ticks = {lo};
  if (!(hi > lo)) return ticks;
  auto nice_step = [](double raw) {
    const double mag = std::pow(10.0, std::floor(std::log10(raw))), n = raw / mag;
    return (n < 1.5 ? 1 : n < 3 ? 2 : n < 7 ? 5 : 10) * mag;
  };
  if (log_scale && hi / lo >= 10) {
    // Powers of ten, thinned to at most about five.
    const double e0 = std::ceil(std::log10(lo)), e1 = std::floor(std::log10(hi));
    const double every = std::max(1.0, std::ceil((e1 - e0 + 1) / 5));
    for (double e = e0; e <= e1; e += every) ticks.push_back(std::pow(10.0, e));
  } else {
    const double step = nice_step((hi - lo) / 4);
    // A range narrow next to its magnitude (1 .. 1 + 2e-16) makes k larger
    // than the integers a double holds, so ++k would not advance: no interior
    // ticks then, and never more than a handful.
    const double k0 = std::ceil(lo / step);
    if (std::abs(k0) < 1e12 && std::abs(hi / step) < 1e12)
      for (double k = k0; k * step <= hi && ticks.size() < 12; ++k) ticks.push_back(k * step);
  }
  ticks.push_back(hi);
  return ticks;
}

void draw_colour_bar(Image& img, Rect bar, double lo, double hi, bool log_scale, int s) {
  const int h = bar.height();
  if (h <= 0 || bar.width() <= 0) return;
  fill_rect(img, {bar.x0 - 1, bar.y0 - 1, bar.x1 + 1, bar.y1 + 1}, kInk);
  for (int y = bar.y0; y < bar.y1; ++y) {
    const double t = h > 1 ? static_cast<double>(bar.y1 - 1 - y) / (h - 1) : 0.0;
    fill_rect(img, {bar.x0, y, bar.x1, y + 1}, colormap(t));
  }
  const std::vector<double> ticks = tick_values(lo, hi, log_scale);
  auto row_of = [&](double v) {
    return bar.y1 - 1 - static_cast<int>(std::lround(normalise_value(v, lo, hi, log_scale) * (h - 1)));
  };
  // The end labels (exact lo and hi) always show; an interior tick is
  // dropped when its label would touch either of them.
  const int y_lo = row_of(lo), y_hi = row_of(hi), gap = line_height(s);
  for (std::size_t k = 0; k < ticks.size(); ++k) {
    const bool end = k == 0 || k + 1 == ticks.size();
    const int y = row_of(ticks[k]);
    if (!end && (std::abs(y - y_lo) < gap || std::abs(y - y_hi) < gap)) continue;
    if (k + 1 == ticks.size() && ticks.size() > 1 && y == y_lo) continue;  // lo == hi
    fill_rect(img, {bar.x1 + 1, y - s / 2, bar.x1 + 1 + 4 * s, y - s / 2 + s}, kInk);
    // Digits are about 7 font units tall; centre them on the tick.
    draw_text(img, bar.x1 + 7 * s, y - (7 * s) / 2, format_tick(ticks[k]), s, kInk);
  }
}

}  // namespace intrinsic::render
