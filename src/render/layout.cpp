// UV layout rendering. Flipped triangles are drawn after the others so they
// stay visible where they overlap their neighbours, which is exactly where
// a fold puts them.
#include "render/layout.h"

#include <cmath>

#include "render/mesh_checks.h"
#include "render/rasterizer.h"

namespace intrinsic::render {

namespace {
constexpr Rgb kBackground = {255, 255, 255};
constexpr Rgb kEdge = {95, 105, 125};
constexpr Rgb kBoundary = {20, 20, 20};

// Interior edges are only drawn when the mean edge is at least this many
// pixels long; below that they would merge into a solid dark fill.
constexpr double kMinEdgePixels = 5;
}  // namespace

Image draw_layout(const MatrixX3i& F, const MatrixX2d& UV, const std::vector<Rgb>* face_colours, int width,
                  int height, int ss) {
  const UvFrame fr = frame_uv(F, UV, width * ss, height * ss, kLayoutMargin);
  std::vector<ScreenVertex> screen(UV.rows());
  for (Eigen::Index i = 0; i < UV.rows(); ++i) screen[i] = {fr.x(UV(i, 0)), fr.y(UV(i, 1)), 0};

  // Orientation from the framed positions rather than raw UV: the product of
  // two tiny UV differences would underflow to zero and look flipped. The
  // screen's y axis points down, so positive UV area is negative here.
  std::vector<char> flipped(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const ScreenVertex &a = screen[F(f, 0)], &b = screen[F(f, 1)], &c = screen[F(f, 2)];
    const double area = -((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    flipped[f] = !(area > 0) && !std::isnan(area);
  }

  std::vector<std::array<int, 2>> interior, boundary;
  collect_edges(F, interior, boundary);
  double total = 0;
  std::size_t counted = 0;
  for (const auto* list : {&interior, &boundary})
    for (const auto& e : *list) {
      const double len = std::hypot(screen[e[0]].x - screen[e[1]].x, screen[e[0]].y - screen[e[1]].y);
      if (std::isfinite(len)) total += len, ++counted;
    }
  const bool show_edges = counted > 0 && total / counted / ss >= kMinEdgePixels;
  const double thin = 0.8 * ss, thick = 2.5 * ss;

  SampleBuffer buf(width * ss, height * ss, kBackground);
  for_each_band(buf.height, [&](int y0, int y1) {
    auto fill = [&](Eigen::Index f, Rgb c) {
      draw_triangle(buf, screen[F(f, 0)], screen[F(f, 1)], screen[F(f, 2)], y0, y1, false,
                    [c](double, double, double) { return c; });
    };
    if (face_colours) {
      for (Eigen::Index f = 0; f < F.rows(); ++f) fill(f, (*face_colours)[f]);
    } else {
      for (Eigen::Index f = 0; f < F.rows(); ++f)
        if (!flipped[f]) fill(f, kLayoutFill);
      for (Eigen::Index f = 0; f < F.rows(); ++f)
        if (flipped[f]) fill(f, kFlippedRed);
    }
    auto line = [&](const std::array<int, 2>& e, double w, Rgb c) {
      draw_line(buf, screen[e[0]].x, screen[e[0]].y, screen[e[1]].x, screen[e[1]].y, w, c, y0, y1);
    };
    if (show_edges)
      for (const auto& e : interior) line(e, thin, kEdge);
    for (const auto& e : boundary) line(e, thick, kBoundary);
  });
  return resolve(buf, ss);
}

}  // namespace intrinsic::render
