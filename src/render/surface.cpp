// 3D surface rendering. Shading uses the signed headlight term interpolated
// from area-weighted vertex normals (Gouraud on n.l, which is linear in n),
// taken in absolute value so back faces of open surfaces are lit too.
#include "render/surface.h"

#include <algorithm>
#include <cmath>

#include "render/camera.h"
#include "render/colormap.h"
#include "render/rasterizer.h"

namespace intrinsic::render {

namespace {

constexpr Rgb kSurfaceBackground = {255, 255, 255};

// Bilinear, repeating in both directions; v = 0 is the bottom image row.
Rgb sample_texture(const Image& tex, double u, double v) {
  if (!(std::isfinite(u) && std::isfinite(v))) return kNoDataGrey;
  const double fx = (u - std::floor(u)) * tex.width - 0.5;
  const double fy = (1.0 - (v - std::floor(v))) * tex.height - 0.5;
  const double x0f = std::floor(fx), y0f = std::floor(fy);
  const double ax = fx - x0f, ay = fy - y0f;
  auto wrap = [](long i, int n) { return static_cast<int>(((i % n) + n) % n); };
  const int x0 = wrap(static_cast<long>(x0f), tex.width), x1 = wrap(static_cast<long>(x0f) + 1, tex.width);
  const int y0 = wrap(static_cast<long>(y0f), tex.height), y1 = wrap(static_cast<long>(y0f) + 1, tex.height);
  Rgb out;
  for (int c = 0; c < 3; ++c) {
    const double top = tex.pixel(x0, y0)[c] * (1 - ax) + tex.pixel(x1, y0)[c] * ax;
    const double bot = tex.pixel(x0, y1)[c] * (1 - ax) + tex.pixel(x1, y1)[c] * ax;
    out[c] = static_cast<std::uint8_t>(std::lround(top * (1 - ay) + bot * ay));
  }
  return out;
}

Rgb shade(Rgb base, double light) {
  const double k = kAmbient + (1 - kAmbient) * std::min(std::abs(light), 1.0);
  return {static_cast<std::uint8_t>(std::lround(base[0] * k)), static_cast<std::uint8_t>(std::lround(base[1] * k)),
          static_cast<std::uint8_t>(std::lround(base[2] * k))};
}

}  // namespace

Rgb checker_colour(double u, double v, int squares) {
  if (!(std::isfinite(u) && std::isfinite(v))) return kNoDataGrey;
  const double i = std::floor(u * squares), j = std::floor(v * squares);
  // fmod keeps parity right for huge or negative indices.
  return std::fmod(std::abs(i + j), 2.0) == 0 ? kCheckerLight : kCheckerDark;
}

Image draw_surface(const MatrixX3d& V, const MatrixX3i& F, const SurfacePaint& paint, const RenderOptions& o,
                   int width, int height) {
  const int ss = o.supersample;
  const ViewDirection dir = o.auto_view ? auto_view(V, F) : view_from_angles(o.azimuth_deg, o.elevation_deg);
  const Camera cam = make_camera(V, F, dir, width * ss, height * ss);

  const Eigen::Index nv = V.rows();
  std::vector<ScreenVertex> screen(nv);
  for (Eigen::Index i = 0; i < nv; ++i) screen[i] = cam.project(V.row(i).transpose());

  // Vertex normals in radius units (no overflow), then only n.forward is kept.
  Eigen::MatrixX3d N = Eigen::MatrixX3d::Zero(nv, 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)) / cam.radius, b = V.row(F(f, 1)) / cam.radius,
                          c = V.row(F(f, 2)) / cam.radius;
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (!n.allFinite()) continue;
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n.transpose();
  }
  std::vector<double> light(nv);
  for (Eigen::Index i = 0; i < nv; ++i) {
    const double len = N.row(i).norm();
    light[i] = len > 0 ? N.row(i).dot(cam.forward) / len : 0.0;
  }

  // Optional remap of UV so its bounding box becomes the unit square.
  double uv_scale = 1, uv_u0 = 0, uv_v0 = 0;
  if (paint.uv && o.fit_uv) {
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (Eigen::Index i = 0; i < paint.uv->rows(); ++i)
      for (int d = 0; d < 2; ++d)
        if (std::isfinite((*paint.uv)(i, d)))
          lo[d] = std::min(lo[d], (*paint.uv)(i, d)), hi[d] = std::max(hi[d], (*paint.uv)(i, d));
    const double ext = std::max(hi[0] - lo[0], hi[1] - lo[1]);
    if (std::isfinite(ext) && ext > 0) uv_scale = 1 / ext, uv_u0 = lo[0], uv_v0 = lo[1];
  }

  SampleBuffer buf(width * ss, height * ss, kSurfaceBackground);
  for_each_band(buf.height, [&](int y0, int y1) {
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      const int i0 = F(f, 0), i1 = F(f, 1), i2 = F(f, 2);
      const double l0 = light[i0], l1 = light[i1], l2 = light[i2];
      if (paint.face_colours) {
        const Rgb base = (*paint.face_colours)[f];
        draw_triangle(buf, screen[i0], screen[i1], screen[i2], y0, y1, true, [&](double b0, double b1, double b2) {
          return shade(base, b0 * l0 + b1 * l1 + b2 * l2);
        });
      } else {
        const MatrixX2d& UV = *paint.uv;
        const double u0 = (UV(i0, 0) - uv_u0) * uv_scale, v0 = (UV(i0, 1) - uv_v0) * uv_scale;
        const double u1 = (UV(i1, 0) - uv_u0) * uv_scale, v1 = (UV(i1, 1) - uv_v0) * uv_scale;
        const double u2 = (UV(i2, 0) - uv_u0) * uv_scale, v2 = (UV(i2, 1) - uv_v0) * uv_scale;
        draw_triangle(buf, screen[i0], screen[i1], screen[i2], y0, y1, true, [&](double b0, double b1, double b2) {
          const double u = b0 * u0 + b1 * u1 + b2 * u2, v = b0 * v0 + b1 * v1 + b2 * v2;
          const Rgb base = o.texture ? sample_texture(*o.texture, u, v) : checker_colour(u, v, o.checker_squares);
          return shade(base, b0 * l0 + b1 * l1 + b2 * l2);
        });
      }
    }
  });
  return resolve(buf, ss);
}

}  // namespace intrinsic::render
