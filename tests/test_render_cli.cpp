// Pictures from the command line (`render`, `param --render`, `compare`):
// expected pixels for known configurations, the colour bar's range against
// `metrics`, generated surfaces and every shared mesh in every mode, and
// refused runs.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "intrinsic/render.h"
#include "test_support.h"

namespace intrinsic {
namespace {

using test::run_cli;
using test::TempDir;

Image read_png(const std::string& path) { return decode_png(test::slurp(path)); }

std::array<int, 3> rgb_at(const Image& img, int x, int y) {
  const std::uint8_t* p = img.pixel(x, y);
  return {p[0], p[1], p[2]};
}

bool near(const std::array<int, 3>& a, const std::array<int, 3>& b, int tol = 3) {
  for (int c = 0; c < 3; ++c)
    if (std::abs(a[c] - b[c]) > tol) return false;
  return true;
}

// Bounding box of the pixels that are not pure white: [x0, x1] x [y0, y1].
struct Box {
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
};
Box drawn_box(const Image& img) {
  Box b;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (rgb_at(img, x, y) != std::array<int, 3>{255, 255, 255})
        b.x0 = std::min(b.x0, x), b.x1 = std::max(b.x1, x), b.y0 = std::min(b.y0, y), b.y1 = std::max(b.y1, y);
  return b;
}

double pixel_variance(const Image& img) {
  double sum = 0, sum2 = 0;
  for (std::uint8_t v : img.rgb) sum += v, sum2 += double(v) * v;
  const double n = static_cast<double>(img.rgb.size());
  return sum2 / n - (sum / n) * (sum / n);
}

// Unit square in z = 0 made of 4 x 4 cells, two triangles each, with vt = xy.
std::string unit_square_obj() {
  std::string s;
  const int n = 4;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) s += "v " + std::to_string(double(i) / n) + " " + std::to_string(double(j) / n) + " 0\n";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) s += "vt " + std::to_string(double(i) / n) + " " + std::to_string(double(j) / n) + "\n";
  auto id = [n](int i, int j) { return std::to_string(j * (n + 1) + i + 1); };
  auto corner = [&](int i, int j) { return id(i, j) + "/" + id(i, j); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      s += "f " + corner(i, j) + " " + corner(i + 1, j) + " " + corner(i + 1, j + 1) + "\n";
      s += "f " + corner(i, j) + " " + corner(i + 1, j + 1) + " " + corner(i, j + 1) + "\n";
    }
  return s;
}

TEST(RenderCli, CheckerSquaresWhereTheyShouldBe) {
  TempDir dir;
  test::write_text(dir / "square.obj", unit_square_obj());
  const auto r = run_cli("render " + (dir / "square.obj") + " -o " + (dir / "c.png") +
                             " --mode checker --view 0,90 --squares 4 --size 400,400 -q",
                         dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const Image img = read_png(dir / "c.png");
  ASSERT_EQ(img.width, 400);
  ASSERT_EQ(img.height, 400);
  // Top view: x to the right, y up, the square centred and framed.
  const Box b = drawn_box(img);
  EXPECT_NEAR(b.x0 + b.x1, 399, 3);
  EXPECT_NEAR(b.y0 + b.y1, 399, 3);
  EXPECT_NEAR(b.x1 - b.x0, b.y1 - b.y0, 2);
  EXPECT_GT(b.x1 - b.x0, 200);
  // The square at UV (0, 0) (bottom left) is light; neighbours alternate. The
  // surface faces the camera, so the colours are the unshaded ones.
  const std::array<int, 3> light = {240, 240, 240}, dark = {70, 100, 165};
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const int x = static_cast<int>(std::lround(b.x0 + (i + 0.5) / 4 * (b.x1 - b.x0)));
      const int y = static_cast<int>(std::lround(b.y1 - (j + 0.5) / 4 * (b.y1 - b.y0)));
      const auto expected = (i + j) % 2 == 0 ? light : dark;
      EXPECT_TRUE(near(rgb_at(img, x, y), expected)) << "square (" << i << ", " << j << ") at pixel " << x << ","
                                                     << y;
    }
  // Outside the square: background.
  EXPECT_TRUE(near(rgb_at(img, 5, 5), {255, 255, 255}, 0));
}

TEST(RenderCli, FlippedTriangleIsRedInLayout) {
  TempDir dir;
  // Square with a centre vertex; the centre's UV is pulled below the bottom
  // edge, which flips the bottom triangle only.
  test::write_text(dir / "flip.obj",
                   "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 0\n"
                   "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 -0.3\n"
                   "f 1/1 2/2 5/5\nf 2/2 3/3 5/5\nf 3/3 4/4 5/5\nf 4/4 1/1 5/5\n");
  const auto r = run_cli("render " + (dir / "flip.obj") + " -o " + (dir / "l.png") + " --mode layout --size 300,300 -q",
                         dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const Image img = read_png(dir / "l.png");
  const Box b = drawn_box(img);
  // The drawn box spans UV [0, 1] x [-0.3, 1].
  auto px = [&](double u, double v) {
    return std::array<int, 2>{static_cast<int>(std::lround(b.x0 + u * (b.x1 - b.x0))),
                              static_cast<int>(std::lround(b.y1 - (v + 0.3) / 1.3 * (b.y1 - b.y0)))};
  };
  const std::array<int, 3> red = {220, 30, 30};
  const auto flipped = px(0.5, -0.1);  // centroid of the flipped triangle
  EXPECT_TRUE(near(rgb_at(img, flipped[0], flipped[1]), red)) << flipped[0] << "," << flipped[1];
  // Centroids of the three other triangles are not red.
  for (const auto& uv : {std::array<double, 2>{0.83, 0.23}, {0.5, 0.57}, {0.17, 0.23}}) {
    const auto p = px(uv[0], uv[1]);
    EXPECT_FALSE(near(rgb_at(img, p[0], p[1]), red, 40)) << p[0] << "," << p[1];
  }
  // And there is no red far from the flipped triangle (above v = 0.1).
  for (int y = b.y0; y < px(0, 0.1)[1]; ++y)
    for (int x = b.x0; x <= b.x1; ++x) ASSERT_FALSE(near(rgb_at(img, x, y), red, 20)) << x << "," << y;
}

TEST(RenderCli, ColourBarRangeIsTheReportsMinAndMax) {
  TempDir dir;
  ASSERT_EQ(run_cli("generate wave --rings 10 -o " + (dir / "wave.obj"), dir).code, 0);
  ASSERT_EQ(run_cli("param " + (dir / "wave.obj") + " -o " + (dir / "uv.obj") + " --method authalic -q", dir).code, 0);
  const auto m = run_cli("metrics " + (dir / "uv.obj") + " --report " + (dir / "m.json"), dir);
  ASSERT_EQ(m.code, 0) << m.err;
  const nlohmann::json metrics = nlohmann::json::parse(test::slurp(dir / "m.json"));
  const struct {
    const char* mode;
    const char* measure;
  } cases[] = {{"angle", "angle_distortion"}, {"area", "area_distortion"}, {"stretch", "stretch_l2"}};
  for (const auto& c : cases)
    for (const char* extra : {"", " --log", " --on-surface"}) {
      SCOPED_TRACE(std::string(c.mode) + extra);
      const auto r = run_cli("render " + (dir / "uv.obj") + " -o " + (dir / "p.png") + " --mode " + c.mode +
                                 " --size 200,150 -q --report " + (dir / "r.json") + extra,
                             dir);
      ASSERT_EQ(r.code, 0) << r.err;
      const nlohmann::json rep = nlohmann::json::parse(test::slurp(dir / "r.json"));
      const nlohmann::json& stat = metrics.at(c.measure);
      EXPECT_EQ(rep.at("measure"), c.measure);
      EXPECT_EQ(rep.at("values"), stat);  // the same figures, bit for bit
      EXPECT_EQ(rep.at("colour_range").at("hi").get<double>(), stat.at("max").get<double>());
      EXPECT_EQ(rep.at("colour_range").at("lo").get<double>(), std::min(1.0, stat.at("min").get<double>()));
      EXPECT_EQ(rep.at("colour_range").at("log").get<bool>(), std::string(extra) == " --log");
      EXPECT_GT(stat.at("max").get<double>(), 1.0);
      const Image img = read_png(dir / "p.png");
      EXPECT_EQ(img.width, 200);
      EXPECT_EQ(img.height, 150);
    }
}

TEST(RenderCli, PerCornerUvsWithSeams) {
  TempDir dir;
  // Two triangles sharing an edge in 3D but not in UV: 4 vertices, 6 texture
  // coordinates, the islands side by side.
  test::write_text(dir / "seam.obj",
                   "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                   "vt 0 0\nvt 0.4 0\nvt 0.4 0.4\nvt 0.6 0\nvt 1 0.4\nvt 0.6 0.4\n"
                   "f 1/1 2/2 3/3\nf 1/4 3/5 4/6\n");
  for (const char* mode : {"checker", "layout", "angle", "area", "stretch"}) {
    const auto r = run_cli("render " + (dir / "seam.obj") + " -o " + (dir / "s.png") + " --mode " + mode +
                               " --size 120,100 -q",
                           dir);
    ASSERT_EQ(r.code, 0) << mode << ": " << r.err;
    EXPECT_GT(pixel_variance(read_png(dir / "s.png")), 0) << mode;
  }
}

// `intrinsic param MESH --render-all`, then `intrinsic render` of its output
// in every mode: pictures of the right size, not blank.
void expect_every_mode_after_param(const std::string& mesh, bool large, const TempDir& dir) {
  const auto p = run_cli("param " + mesh + " -o " + (dir / "uv.ply") + " --binary --render-all " + (dir / "p") +
                             " --render-size 200,200 -q",
                         dir);
  ASSERT_EQ(p.code, 0) << p.err;
  for (const char* mode : {"checker", "layout", "angle", "area", "stretch"}) {
    const Image img = read_png(dir / (std::string("p_") + mode + ".png"));
    EXPECT_EQ(img.width, 200);
    EXPECT_GT(pixel_variance(img), 0) << mode;
  }
  // The render command on param's output: every mode (the large mesh only
  // once, to keep the suite fast).
  std::vector<std::string> runs = {"checker", "layout", "angle", "area", "stretch", "area --on-surface --log"};
  if (large) runs = {"stretch --on-surface"};
  for (const std::string& mode : runs) {
    const auto r = run_cli("render " + (dir / "uv.ply") + " -o " + (dir / "r.png") + " --size 200,200 -q --mode " +
                               mode,
                           dir);
    ASSERT_EQ(r.code, 0) << mode << ": " << r.err;
    EXPECT_GT(pixel_variance(read_png(dir / "r.png")), 0) << mode;
  }
}

TEST(RenderCli, EveryModeAfterParamOnGeneratedSurfaces) {
  for (const char* surface : {"wave", "strip", "cap"}) {
    SCOPED_TRACE(surface);
    TempDir dir;
    ASSERT_EQ(run_cli(std::string("generate ") + surface + " --rings 10 -o " + (dir / "in.obj"), dir).code, 0);
    expect_every_mode_after_param(dir / "in.obj", false, dir);
  }
}

// Every shared mesh, explicitly listed: where ../shared/meshes is present, a
// missing one fails.
class RenderCliCorpus : public ::testing::TestWithParam<const char*> {};

TEST_P(RenderCliCorpus, EveryModeAfterParam) {
  REQUIRE_SHARED_MESHES();
  const std::string name = GetParam();
  const std::string mesh = test::shared_mesh(name);
  ASSERT_TRUE(std::filesystem::exists(mesh)) << "missing shared mesh " << mesh;
  TempDir dir;
  expect_every_mode_after_param(mesh, name == "max-planck-partial-loop2.obj.gz", dir);
}

INSTANTIATE_TEST_SUITE_P(RenderCli, RenderCliCorpus,
                         ::testing::Values("alligator.obj", "animal.obj", "beetle.off", "camel_b.obj",
                                           "camelhead.off", "cat_head.obj", "face-bff.obj", "fairing-cross.off",
                                           "inspired_mesh.obj", "inverted-triangles.obj", "max-planck-partial.obj",
                                           "maze.obj", "snail.obj", "stanford-bunny.obj",
                                           "max-planck-partial-loop2.obj.gz"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           std::string s = info.param;
                           for (char& c : s)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return s;
                         });

TEST(RenderCli, BadInputs) {
  TempDir dir;
  test::write_text(dir / "square.obj", unit_square_obj());
  test::write_text(dir / "nouv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  // No UVs: input error naming the problem.
  auto r = run_cli("render " + (dir / "nouv.obj") + " -o " + (dir / "x.png"), dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("no texture coordinates"), std::string::npos) << r.err;
  // Bad sizes: usage errors.
  for (const char* size : {"0,10", "10", "10,abc", "20000,10", "10.5,10", "-3,4", "10,10,10"}) {
    r = run_cli("render " + (dir / "square.obj") + " -o " + (dir / "x.png") + " --size " + size, dir);
    EXPECT_EQ(r.code, 1) << size;
    EXPECT_NE(r.err.find("--size"), std::string::npos) << r.err;
  }
  r = run_cli("render " + (dir / "square.obj") + " -o " + (dir / "x.png") + " --view 10,100", dir);
  EXPECT_EQ(r.code, 1);
  r = run_cli("render " + (dir / "square.obj") + " -o " + (dir / "x.jpg"), dir);
  EXPECT_EQ(r.code, 1);
  r = run_cli("render " + (dir / "square.obj") + " -o " + (dir / "x.png") + " --mode checker --log", dir);
  EXPECT_EQ(r.code, 1);
  r = run_cli("render " + (dir / "square.obj") + " -o " + (dir / "x.png") + " --texture " + (dir / "square.obj"), dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("texture"), std::string::npos) << r.err;
  // Unwritable output directory (missing, or read-only unless we are root):
  // output error, no file.
  r = run_cli("render " + (dir / "square.obj") + " -o " + (dir / "missing/x.png"), dir);
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("missing/x.png"), std::string::npos) << r.err;
  std::filesystem::create_directory(dir / "ro");
  std::filesystem::permissions(dir / "ro", std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  if (geteuid() != 0) {
    r = run_cli("render " + (dir / "square.obj") + " -o " + (dir / "ro/x.png"), dir);
    EXPECT_EQ(r.code, 4) << r.err;
    EXPECT_TRUE(std::filesystem::is_empty(dir / "ro"));
  }
  std::filesystem::permissions(dir / "ro", std::filesystem::perms::owner_all);
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"nouv.obj", "ro", "square.obj"}));
  // Report unwritable: the picture is not left behind either.
  r = run_cli("render " + (dir / "square.obj") + " -o " + (dir / "x.png") + " --report " + (dir / "missing/r.json"),
              dir);
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"nouv.obj", "ro", "square.obj"}));
}

TEST(RenderCli, ParamWritesPicturesOnlyWhenEverythingSucceeded) {
  TempDir dir;
  ASSERT_EQ(run_cli("generate wave --rings 8 -o " + (dir / "wave.obj"), dir).code, 0);
  // A picture that cannot be written takes the mesh and report with it.
  auto r = run_cli("param " + (dir / "wave.obj") + " -o " + (dir / "uv.obj") + " --report " + (dir / "r.json") +
                       " --render " + (dir / "c.png") + " --render-all " + (dir / "missing/p") +
                       " --render-size 100,100",
                   dir);
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{"wave.obj"});
  r = run_cli("param " + (dir / "wave.obj") + " -o " + (dir / "uv.obj") + " --render " + (dir / "c.jpg"), dir);
  EXPECT_EQ(r.code, 1);
  r = run_cli("param " + (dir / "wave.obj") + " -o " + (dir / "uv.obj") + " --render-size 0,0 --render " + (dir / "c.png"), dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(dir.files(), std::vector<std::string>{"wave.obj"});
  // Success: the checker picture and all five modes.
  r = run_cli("param " + (dir / "wave.obj") + " -o " + (dir / "uv.obj") + " --render " + (dir / "c.png") +
                  " --render-all " + (dir / "p") + " --render-size 120,90 -q",
              dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"c.png", "p_angle.png", "p_area.png", "p_checker.png",
                                                   "p_layout.png", "p_stretch.png", "uv.obj", "wave.obj"}));
  const Image c = read_png(dir / "c.png");
  EXPECT_EQ(c.width, 120);
  EXPECT_EQ(c.height, 90);
  // --render and --render-all's checker are the same picture.
  EXPECT_EQ(test::slurp(dir / "c.png"), test::slurp(dir / "p_checker.png"));
}

TEST(RenderCli, ComparePanelsAndFigures) {
  TempDir dir;
  ASSERT_EQ(run_cli("generate wave --rings 8 -o " + (dir / "wave.obj"), dir).code, 0);
  auto r = run_cli("compare " + (dir / "wave.obj") + " -o " + (dir / "cmp.png") +
                       " --methods tutte,floater,conformal,authalic --size 120,120 -q --report " + (dir / "r.json"),
                   dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const Image img = read_png(dir / "cmp.png");
  // One row of four panels; empty bands around the disk are cropped.
  EXPECT_GT(img.width, 4 * 80);
  EXPECT_GT(img.height, 80);
  EXPECT_LT(img.height, 2 * 120);
  EXPECT_GT(pixel_variance(img), 0);
  const nlohmann::json rep = nlohmann::json::parse(test::slurp(dir / "r.json"));
  ASSERT_EQ(rep.at("methods").size(), 4u);
  EXPECT_EQ(rep["methods"][0]["method"], "tutte");
  EXPECT_EQ(rep["methods"][3]["method"], "authalic");
  for (const auto& m : rep["methods"]) {
    EXPECT_EQ(m.at("flipped_triangles"), 0);
    EXPECT_GE(m.at("time_ms").get<double>(), 0.0);
  }
  // Conformal has the smallest mean angle distortion of the four.
  for (int i : {0, 1, 3})
    EXPECT_LE(rep["methods"][2]["angle_distortion"]["mean"].get<double>(),
              rep["methods"][i]["angle_distortion"]["mean"].get<double>() + 1e-12);
  // The natural map panel: free boundary, conformal weights, lower angle
  // distortion than the circle-bound conformal map.
  r = run_cli("compare " + (dir / "wave.obj") + " -o " + (dir / "nat.png") +
                  " --methods conformal,natural --size 120,120 -q --report " + (dir / "n.json"),
              dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json nat = nlohmann::json::parse(test::slurp(dir / "n.json"));
  EXPECT_EQ(nat["methods"][1]["method"], "natural");
  EXPECT_EQ(nat["methods"][1]["flipped_triangles"], 0);
  EXPECT_LT(nat["methods"][1]["angle_distortion"]["mean"].get<double>(),
            nat["methods"][0]["angle_distortion"]["mean"].get<double>());
  // Unknown methods: a usage error, no file.
  for (const char* m : {"foo", "mixed", ""}) {
    TempDir d2;
    r = run_cli("compare " + (dir / "wave.obj") + " -o " + (d2 / "x.png") + " --methods '" + m + "'", d2);
    EXPECT_EQ(r.code, 1) << m;
    EXPECT_NE(r.err.find("--methods"), std::string::npos) << r.err;
    EXPECT_TRUE(d2.files().empty());
  }
}

}  // namespace
}  // namespace intrinsic
