// Piecewise-linear colour map through 17 hand-picked control points that
// follow the viridis look (violet-blue-teal-green-yellow, increasing
// lightness). Interpolation is in sRGB bytes, which is close enough at this
// control-point density.
#include "render/colormap.h"

#include <algorithm>
#include <cmath>

namespace intrinsic::render {

namespace {
constexpr int kN = 17;
constexpr unsigned char kTable[kN][3] = {
    {68, 1, 84},    {72, 23, 105},  {71, 44, 122},  {65, 64, 134},  {59, 82, 139},  {52, 98, 141},
    {46, 114, 142}, {40, 129, 142}, {33, 145, 140}, {31, 160, 136}, {40, 174, 128}, {63, 188, 115},
    {94, 201, 98},  {132, 212, 75}, {173, 220, 48}, {215, 226, 25}, {253, 231, 37},
};
}  // namespace

Rgb colormap(double t) {
  if (std::isnan(t)) return kNoDataGrey;
  t = std::clamp(t, 0.0, 1.0) * (kN - 1);
  const int i = std::min(static_cast<int>(t), kN - 2);
  const double f = t - i;
  Rgb out;
  for (int c = 0; c < 3; ++c)
    out[c] = static_cast<std::uint8_t>(std::lround(kTable[i][c] + f * (kTable[i + 1][c] - kTable[i][c])));
  return out;
}

}  // namespace intrinsic::render
