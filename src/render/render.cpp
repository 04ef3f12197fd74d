// Public entry points: validate, pick the pass, and assemble the page.
#include "intrinsic/render.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "intrinsic/error.h"
#include "render/colormap.h"
#include "render/colour_bar.h"
#include "render/layout.h"
#include "render/mesh_checks.h"
#include "render/surface.h"
#include "render/text.h"

namespace intrinsic {

using namespace render;

Image render_checker(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV, const RenderOptions& o) {
  check_options(o);
  check_faces(F, V.rows(), "render");
  if (UV.rows() != V.rows())
    throw_input("render: " + std::to_string(UV.rows()) + " UV rows for " + std::to_string(V.rows()) + " vertices");
  check_some_finite(F, V, "render");
  SurfacePaint paint;
  paint.uv = &UV;
  return draw_surface(V, F, paint, o, o.width, o.height);
}

Image render_layout(const MatrixX3i& F, const MatrixX2d& UV, const RenderOptions& o) {
  check_options(o);
  check_faces(F, UV.rows(), "render layout");
  check_some_finite(F, UV, "render layout");
  return draw_layout(F, UV, nullptr, o.width, o.height, o.supersample);
}

namespace {

// A light colour per chart: HSV with the hue stepped by the golden ratio.
render::Rgb chart_colour(int k) {
  const double h = std::fmod(0.13 + 0.6180339887498949 * k, 1.0) * 6, s = 0.45, v = 0.95;
  const int i = static_cast<int>(h) % 6;
  const double f = h - std::floor(h), p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  const double rgb[6][3] = {{v, t, p}, {q, v, p}, {p, v, t}, {p, q, v}, {t, p, v}, {v, p, q}};
  auto byte = [](double x) { return static_cast<std::uint8_t>(std::lround(255 * x)); };
  return {byte(rgb[i][0]), byte(rgb[i][1]), byte(rgb[i][2])};
}

}  // namespace

Image render_atlas_layout(const MatrixX3i& F, const MatrixX2d& UV, const std::vector<int>& face_chart,
                          const std::vector<char>& red, const RenderOptions& o) {
  check_options(o);
  check_faces(F, UV.rows(), "render layout");
  check_some_finite(F, UV, "render layout");
  if (face_chart.size() != static_cast<size_t>(F.rows()) || (!red.empty() && red.size() != face_chart.size()))
    throw_usage("render layout: one chart (and one red flag, if any) per face");
  std::vector<render::Rgb> colours(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    colours[f] = !red.empty() && red[f] ? render::kFlippedRed : chart_colour(std::max(face_chart[f], 0));
  return draw_layout(F, UV, &colours, o.width, o.height, o.supersample);
}

Image render_face_values(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV, const Eigen::VectorXd& values,
                         const FaceValueOptions& fv, const RenderOptions& o) {
  check_options(o);
  if (!(std::isfinite(fv.lo) && std::isfinite(fv.hi)) || fv.lo > fv.hi)
    throw_usage("render: value range [" + format_tick(fv.lo) + ", " + format_tick(fv.hi) +
                "] must be finite with lo <= hi");
  if (fv.log_scale && !(fv.lo > 0))
    throw_usage("render: a log scale needs a positive range, got lo = " + format_tick(fv.lo));
  if (values.size() != F.rows())
    throw_usage("render: " + std::to_string(values.size()) + " values for " + std::to_string(F.rows()) + " faces");
  if (fv.on_surface) {
    check_faces(F, V.rows(), "render");
    check_some_finite(F, V, "render");
  } else {
    check_faces(F, UV.rows(), "render layout");
    check_some_finite(F, UV, "render layout");
  }

  std::vector<Rgb> colours(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    colours[f] = std::isfinite(values[f]) ? colormap(normalise_value(values[f], fv.lo, fv.hi, fv.log_scale))
                                          : kNoDataGrey;

  const FaceValuesLayout L = face_values_layout(o.width, o.height, !fv.title.empty());
  Image page(o.width, o.height);
  if (L.plot.width() > 0 && L.plot.height() > 0) {
    Image plot;
    if (fv.on_surface) {
      SurfacePaint paint;
      paint.face_colours = &colours;
      plot = draw_surface(V, F, paint, o, L.plot.width(), L.plot.height());
    } else {
      plot = draw_layout(F, UV, &colours, L.plot.width(), L.plot.height(), o.supersample);
    }
    blit(page, plot, L.plot.x0, L.plot.y0);
  }
  if (!fv.title.empty()) {
    const int s = L.text_scale;
    draw_text(page, (o.width - text_width(fv.title, s)) / 2, L.title.y0 + 6 * s, fv.title, s, {20, 20, 20});
  }
  draw_colour_bar(page, L.bar, fv.lo, fv.hi, fv.log_scale, L.text_scale);
  return page;
}

}  // namespace intrinsic
