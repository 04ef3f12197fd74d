// Tests for the software renderer: pixel colours at known places for each
// mode, crack-free rasterization, PNG round trips and input errors.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "intrinsic/error.h"
#include "intrinsic/render.h"
#include "render/camera.h"
#include "render/colormap.h"
#include "render/colour_bar.h"
#include "render/layout.h"
#include "render/mesh_checks.h"
#include "render/rasterizer.h"
#include "render/surface.h"
#include "test_support.h"

using namespace intrinsic;
using render::Rgb;

namespace {

// n x n cells over [0,1]^2 in the z = 0 plane, counter-clockwise, UV = (x, y).
void grid(int n, MatrixX3d& V, MatrixX3i& F, MatrixX2d& UV) {
  V.resize((n + 1) * (n + 1), 3);
  UV.resize(V.rows(), 2);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const int k = j * (n + 1) + i;
      V.row(k) << double(i) / n, double(j) / n, 0;
      UV.row(k) << double(i) / n, double(j) / n;
    }
  F.resize(2 * n * n, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      F.row(2 * (j * n + i)) << a, b, d;
      F.row(2 * (j * n + i) + 1) << a, d, c;
    }
}

// A spherical cap over a grid: curved, so shading varies.
void cap(int n, MatrixX3d& V, MatrixX3i& F, MatrixX2d& UV) {
  grid(n, V, F, UV);
  for (Eigen::Index k = 0; k < V.rows(); ++k) {
    const double x = 1.4 * V(k, 0) - 0.7, y = 1.4 * V(k, 1) - 0.7;
    V.row(k) << x, y, std::sqrt(1 - x * x - y * y);
  }
}

double variance(const Image& img) {
  double s = 0, s2 = 0;
  for (std::uint8_t c : img.rgb) s += c, s2 += double(c) * c;
  const double n = double(img.rgb.size());
  return s2 / n - (s / n) * (s / n);
}

Rgb at(const Image& img, double x, double y) {
  return render::get_pixel(img, int(std::floor(x)), int(std::floor(y)));
}

RenderOptions small(int size = 256) {
  RenderOptions o;
  o.width = o.height = size;
  return o;
}

}  // namespace

TEST(Render, CheckerSquaresAlternateOnFrontView) {
  MatrixX3d V;
  MatrixX3i F;
  MatrixX2d UV;
  grid(6, V, F, UV);
  for (bool automatic : {false, true}) {
    RenderOptions o = small();
    o.checker_squares = 4;
    o.auto_view = automatic;
    o.elevation_deg = 90;
    const Image img = render_checker(V, F, UV, o);
    ASSERT_EQ(img.width, 256);
    // Same camera at pixel resolution tells where a point lands.
    const auto cam = render::make_camera(V, F, render::view_from_angles(0, 90), o.width, o.height);
    int checked = 0;
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const auto p = cam.project(Eigen::Vector3d((i + 0.5) / 4, (j + 0.5) / 4, 0));
        const Rgb expect = (i + j) % 2 == 0 ? render::kCheckerLight : render::kCheckerDark;
        EXPECT_EQ(at(img, p.x, p.y), expect) << "square " << i << "," << j << " auto=" << automatic;
        ++checked;
      }
    EXPECT_EQ(checked, 16);
    // u grows to the right and v upwards: square (0,0) is bottom-left.
    const auto bl = cam.project(Eigen::Vector3d(0.1, 0.1, 0)), tr = cam.project(Eigen::Vector3d(0.9, 0.9, 0));
    EXPECT_LT(bl.x, tr.x);
    EXPECT_GT(bl.y, tr.y);
  }
}

TEST(Render, LayoutShowsFlippedTriangleInRed) {
  MatrixX3d V;
  MatrixX3i F;
  MatrixX2d UV;
  grid(4, V, F, UV);
  const int flipped = 9;
  std::swap(F(flipped, 1), F(flipped, 2));  // same UVs, opposite winding: signed area < 0
  const RenderOptions o = small();
  const Image img = render_layout(F, UV, o);
  const auto fr = render::frame_uv(F, UV, o.width, o.height, render::kLayoutMargin);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::RowVector2d c = (UV.row(F(f, 0)) + UV.row(F(f, 1)) + UV.row(F(f, 2))) / 3;
    const Rgb px = at(img, fr.x(c.x()), fr.y(c.y()));
    if (f == flipped)
      EXPECT_EQ(px, render::kFlippedRed);
    else
      EXPECT_EQ(px, render::kLayoutFill) << "face " << f;
  }
}

TEST(Render, LayoutAllFlippedWhenMirrored) {
  MatrixX3d V;
  MatrixX3i F;
  MatrixX2d UV;
  grid(2, V, F, UV);
  UV.col(0) *= -1;
  const Image img = render_layout(F, UV, small(64));
  int red = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) red += render::get_pixel(img, x, y) == render::kFlippedRed;
  EXPECT_GT(red, img.width * img.height / 2);
}

TEST(Render, ColourBarEndsMatchColormap) {
  MatrixX3d V;
  MatrixX3i F;
  MatrixX2d UV;
  grid(3, V, F, UV);
  Eigen::VectorXd values = Eigen::VectorXd::LinSpaced(F.rows(), 1.0, 3.0);
  FaceValueOptions fv;
  fv.title = "angle distortion";
  fv.lo = 1;
  fv.hi = 3;
  const RenderOptions o = small(400);
  const Image img = render_face_values(V, F, UV, values, fv, o);
  const auto L = render::face_values_layout(o.width, o.height, true);
  ASSERT_GT(L.bar.height(), 10);
  const int mid = (L.bar.x0 + L.bar.x1) / 2;
  EXPECT_EQ(render::get_pixel(img, mid, L.bar.y1 - 1), render::colormap(0));
  EXPECT_EQ(render::get_pixel(img, mid, L.bar.y0), render::colormap(1));
  EXPECT_NE(render::colormap(0), render::colormap(1));

  // Face 0 has value lo; find its centroid inside the plot area.
  const auto fr = render::frame_uv(F, UV, L.plot.width(), L.plot.height(), render::kLayoutMargin);
  const Eigen::RowVector2d c = (UV.row(F(0, 0)) + UV.row(F(0, 1)) + UV.row(F(0, 2))) / 3;
  EXPECT_EQ(at(img, L.plot.x0 + fr.x(c.x()), L.plot.y0 + fr.y(c.y())), render::colormap(0));
  const Eigen::Index last = F.rows() - 1;
  const Eigen::RowVector2d d = (UV.row(F(last, 0)) + UV.row(F(last, 1)) + UV.row(F(last, 2))) / 3;
  EXPECT_EQ(at(img, L.plot.x0 + fr.x(d.x()), L.plot.y0 + fr.y(d.y())), render::colormap(1));
}

TEST(Render, FaceValuesOnSurfaceFacingCameraAreUnshaded) {
  MatrixX3d V;
  MatrixX3i F;
  MatrixX2d UV;
  grid(2, V, F, UV);
  Eigen::VectorXd values = Eigen::VectorXd::Constant(F.rows(), 0.5);
  values[0] = std::nan("");
  FaceValueOptions fv;
  fv.on_surface = true;
  fv.lo = 0.5;
  fv.hi = 2;
  const RenderOptions o = small(300);
  const Image img = render_face_values(V, F, UV, values, fv, o);
  const auto L = render::face_values_layout(o.width, o.height, false);
  const auto cam = render::make_camera(V, F, render::auto_view(V, F), L.plot.width(), L.plot.height());
  auto pixel_of = [&](Eigen::Index f) {
    const Eigen::Vector3d c = (V.row(F(f, 0)) + V.row(F(f, 1)) + V.row(F(f, 2))).transpose() / 3;
    const auto p = cam.project(c);
    return at(img, L.plot.x0 + p.x, L.plot.y0 + p.y);
  };
  EXPECT_EQ(pixel_of(0), render::kNoDataGrey);
  EXPECT_EQ(pixel_of(3), render::colormap(0));
}

TEST(Render, ColormapIsMonotoneInLightness) {
  double prev = -1;
  for (int i = 0; i <= 64; ++i) {
    const Rgb c = render::colormap(i / 64.0);
    const double y = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    EXPECT_GT(y, prev - 0.5) << i;
    prev = y;
  }
  EXPECT_EQ(render::colormap(-5), render::colormap(0));
  EXPECT_EQ(render::colormap(7), render::colormap(1));
  EXPECT_EQ(render::colormap(std::nan("")), render::kNoDataGrey);
}

TEST(Render, LogScaleNormalisation) {
  EXPECT_DOUBLE_EQ(render::normalise_value(10, 1, 100, true), 0.5);
  EXPECT_DOUBLE_EQ(render::normalise_value(0, 1, 100, true), 0.0);
  EXPECT_DOUBLE_EQ(render::normalise_value(2, 1, 3, false), 0.5);
  EXPECT_DOUBLE_EQ(render::normalise_value(1e9, 1, 3, false), 1.0);
  EXPECT_DOUBLE_EQ(render::normalise_value(2, 2, 2, false), 0.5);
}

TEST(Render, SharedEdgesAreCoveredExactlyOnce) {
  // Square split along a diagonal that runs through sample centres, plus a
  // fan around a vertex sitting exactly on a sample centre.
  render::SampleBuffer buf(64, 64, {255, 255, 255});
  long calls = 0;
  auto count = [&](double, double, double) {
    ++calls;
    return Rgb{0, 0, 0};
  };
  using SV = render::ScreenVertex;
  const SV a{10.3, 10.3, 0}, b{50.7, 10.3, 0}, c{50.7, 50.7, 0}, d{10.3, 50.7, 0};
  render::draw_triangle(buf, a, b, c, 0, 64, false, count);
  render::draw_triangle(buf, a, c, d, 0, 64, false, count);
  EXPECT_EQ(calls, 41 * 41);

  // A fan of both windings around a vertex sitting exactly on a sample
  // centre. The shader recovers its sample from the barycentrics and counts.
  std::vector<int> hits(64 * 64, 0);
  const SV centre{30.5, 30.5, 0};
  const int n = 12;
  for (int k = 0; k < n; ++k) {
    const double t0 = 2 * M_PI * k / n, t1 = 2 * M_PI * (k + 1) / n;
    const SV p{30.5 + 20 * std::cos(t0), 30.5 + 20 * std::sin(t0), 0};
    const SV q{30.5 + 20 * std::cos(t1), 30.5 + 20 * std::sin(t1), 0};
    const SV v[3] = {centre, k % 2 ? p : q, k % 2 ? q : p};
    render::draw_triangle(buf, v[0], v[1], v[2], 0, 64, false, [&](double b0, double b1, double b2) {
      const double x = b0 * v[0].x + b1 * v[1].x + b2 * v[2].x, y = b0 * v[0].y + b1 * v[1].y + b2 * v[2].y;
      ++hits[int(std::floor(y)) * 64 + int(std::floor(x))];
      return Rgb{0, 0, 0};
    });
  }
  // Inside the polygon's inscribed circle (radius 20 cos 15 deg > 19.3)
  // every sample is drawn exactly once; nowhere is any drawn twice.
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      EXPECT_LE(hits[y * 64 + x], 1) << x << "," << y;
      if (std::hypot(x + 0.5 - 30.5, y + 0.5 - 30.5) < 19) EXPECT_EQ(hits[y * 64 + x], 1) << x << "," << y;
    }
}

TEST(Render, BandsMatchSingleThreadedOutput) {
  render::SampleBuffer one(100, 100, {255, 255, 255}), two(100, 100, {255, 255, 255});
  const render::ScreenVertex a{3.2, 5.1, 0}, b{97.3, 40.2, 0}, c{20.6, 96.6, 0};
  auto col = [](double b0, double b1, double) {
    return Rgb{std::uint8_t(b0 * 255), std::uint8_t(b1 * 255), 0};
  };
  render::draw_triangle(one, a, b, c, 0, 100, false, col);
  render::draw_triangle(two, a, b, c, 0, 37, false, col);
  render::draw_triangle(two, a, b, c, 37, 100, false, col);
  EXPECT_EQ(one.rgb, two.rgb);
}

TEST(Render, EveryModeHasContrastOnCurvedMesh) {
  MatrixX3d V;
  MatrixX3i F;
  MatrixX2d UV;
  cap(20, V, F, UV);
  const RenderOptions o = small(200);
  EXPECT_GT(variance(render_checker(V, F, UV, o)), 0);
  EXPECT_GT(variance(render_layout(F, UV, o)), 0);
  Eigen::VectorXd values(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) values[f] = V(F(f, 0), 2);
  FaceValueOptions fv;
  fv.lo = values.minCoeff();
  fv.hi = values.maxCoeff();
  EXPECT_GT(variance(render_face_values(V, F, UV, values, fv, o)), 0);
  fv.on_surface = true;
  fv.log_scale = true;
  EXPECT_GT(variance(render_face_values(V, F, UV, values, fv, o)), 0);
  RenderOptions side = o;
  side.auto_view = false;
  side.azimuth_deg = 30;
  side.elevation_deg = 10;
  EXPECT_GT(variance(render_checker(V, F, UV, side)), 0);
}

TEST(Render, TextureReplacesChecker) {
  MatrixX3d V;
  MatrixX3i F;
  MatrixX2d UV;
  grid(2, V, F, UV);
  Image tex(4, 4);
  for (std::size_t i = 0; i < tex.rgb.size(); i += 3) tex.rgb[i] = 200, tex.rgb[i + 1] = 10, tex.rgb[i + 2] = 30;
  RenderOptions o = small(64);
  o.texture = &tex;
  const Image img = render_checker(V, F, UV, o);
  EXPECT_EQ(at(img, 32, 32), (Rgb{200, 10, 30}));
}

TEST(Render, PngRoundTripIsExact) {
  Image img(37, 23);
  std::mt19937 rng(7);
  for (auto& c : img.rgb) c = std::uint8_t(rng());
  const std::string bytes = encode_png(img);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  const Image back = decode_png(bytes);
  EXPECT_EQ(back.width, 37);
  EXPECT_EQ(back.height, 23);
  EXPECT_EQ(back.rgb, img.rgb);
}

TEST(Render, BadTextureBytesAreInputErrors) {
  auto kind_of = [](const std::string& bytes) {
    try {
      decode_png(bytes);
    } catch (const Error& e) {
      return e.kind();
    }
    return ErrorKind::Usage;  // "did not throw" marker
  };
  EXPECT_EQ(kind_of(""), ErrorKind::Input);
  EXPECT_EQ(kind_of("definitely not a png file"), ErrorKind::Input);
  const std::string good = encode_png(Image(16, 16, 128));
  EXPECT_EQ(kind_of(good.substr(0, good.size() / 2)), ErrorKind::Input);
  std::string corrupt = good;
  for (std::size_t i = 40; i < corrupt.size() - 12; ++i) corrupt[i] = char(0x5a);
  EXPECT_EQ(kind_of(corrupt), ErrorKind::Input);
}

TEST(Render, DegenerateInputs) {
  MatrixX3d V;
  MatrixX3i F;
  MatrixX2d UV;
  grid(2, V, F, UV);
  const RenderOptions o = small(64);
  auto kind_of = [](auto&& fn) {
    try {
      fn();
    } catch (const Error& e) {
      return static_cast<int>(e.kind());
    }
    return 0;
  };
  const MatrixX3i none(0, 3);
  EXPECT_EQ(kind_of([&] { render_layout(none, UV, o); }), int(ErrorKind::Input));
  EXPECT_EQ(kind_of([&] { render_checker(V, none, UV, o); }), int(ErrorKind::Input));
  MatrixX2d nan_uv = MatrixX2d::Constant(UV.rows(), 2, std::nan(""));
  EXPECT_EQ(kind_of([&] { render_layout(F, nan_uv, o); }), int(ErrorKind::Input));
  MatrixX3i bad = F;
  bad(0, 0) = 999;
  EXPECT_EQ(kind_of([&] { render_layout(bad, UV, o); }), int(ErrorKind::Input));
  RenderOptions zero = o;
  zero.width = 0;
  EXPECT_EQ(kind_of([&] { render_layout(F, UV, zero); }), int(ErrorKind::Usage));
  RenderOptions ss = o;
  ss.supersample = 0;
  EXPECT_EQ(kind_of([&] { render_layout(F, UV, ss); }), int(ErrorKind::Usage));
  FaceValueOptions fv;
  fv.lo = 0;
  fv.log_scale = true;
  EXPECT_EQ(kind_of([&] { render_face_values(V, F, UV, Eigen::VectorXd::Ones(F.rows()), fv, o); }),
            int(ErrorKind::Usage));

  // Collapsed UV (a point), some NaN UVs, and extreme coordinates all render.
  EXPECT_EQ(kind_of([&] { render_layout(F, MatrixX2d::Zero(UV.rows(), 2), o); }), 0);
  MatrixX2d some_nan = UV;
  some_nan(0, 0) = std::nan("");
  EXPECT_EQ(kind_of([&] { render_layout(F, some_nan, o); }), 0);
  EXPECT_EQ(kind_of([&] { render_checker(V, F, some_nan, o); }), 0);
  for (double s : {1e-200, 1e200, 1e300}) {
    // Same picture up to last-bit rounding of sample positions.
    const Image a = render_layout(F, UV * s, o), b = render_layout(F, UV, o);
    int differ = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) differ += std::abs(int(a.rgb[i]) - int(b.rgb[i])) > 8;
    EXPECT_LT(differ, int(a.rgb.size() / 100)) << s;
    MatrixX3d Vc;
    cap(4, Vc, F, UV);
    EXPECT_GT(variance(render_checker(Vc * s, F, UV, o)), 0) << s;
    grid(2, V, F, UV);
  }
}

TEST(Render, ComposePanelsLaysOutGrid) {
  std::vector<Image> panels = {Image(50, 40, 0), Image(30, 40, 0), Image(50, 20, 0)};
  const Image out = compose_panels(panels, {"one", "two\nlines"}, 2);
  EXPECT_GT(out.width, 100);
  EXPECT_GT(out.height, 2 * 40);
  EXPECT_GT(variance(out), 0);
  intrinsic::test::expect_error([] { compose_panels({}, {}, 1); }, ErrorKind::Usage, "compose_panels: no panels");
}

TEST(Render, TickValuesAreRoundAndIncludeEnds) {
  const auto t = render::tick_values(1, 2.5, false);
  ASSERT_GE(t.size(), 3u);
  EXPECT_EQ(t.front(), 1);
  EXPECT_EQ(t.back(), 2.5);
  for (std::size_t i = 1; i + 1 < t.size(); ++i) EXPECT_NEAR(std::fmod(t[i], 0.5), 0, 1e-12) << t[i];
  // A range narrow next to its magnitude ends (this once looped forever).
  const auto narrow = render::tick_values(1, std::nextafter(1.0, 2.0), false);
  EXPECT_EQ(narrow.front(), 1);
  EXPECT_EQ(narrow.back(), std::nextafter(1.0, 2.0));
  EXPECT_LE(narrow.size(), 12u);
  const auto g = render::tick_values(0.01, 1000, true);
  EXPECT_EQ(g.front(), 0.01);
  EXPECT_EQ(g.back(), 1000);
  EXPECT_GE(g.size(), 4u);
  EXPECT_EQ(render::tick_values(2, 2, false).size(), 1u);
}
