// Picture modes and their option parsing.
#include "intrinsic/pictures.h"
#include "intrinsic/image.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "render/image.h"

namespace intrinsic {

namespace {

// Two comma-separated numbers, nothing else; false if malformed.
bool parse_pair(const std::string& text, double& a, double& b) {
  const size_t comma = text.find(',');
  if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos) return false;
  auto number = [](const std::string& s, double& out) {
    if (s.empty() || std::isspace(static_cast<unsigned char>(s[0]))) return false;
    char* end = nullptr;
    errno = 0;
    out = std::strtod(s.c_str(), &end);
    return errno == 0 && end == s.c_str() + s.size() && std::isfinite(out);
  };
  return number(text.substr(0, comma), a) && number(text.substr(comma + 1), b);
}

}  // namespace

std::string mode_name(PictureMode m) { return choice_name(m); }

PictureMode parse_mode(const std::string& name, std::string_view label) { return parse_choice<PictureMode>(name, label); }

void parse_size(const std::string& text, const std::string& option, int& width, int& height) {
  double w = 0, h = 0;
  if (!parse_pair(text, w, h) || w != std::floor(w) || h != std::floor(h) || w < 1 || h < 1 || w > 16384 ||
      h > 16384)
    throw_usage(option + " '" + text + "': expected W,H with whole numbers of pixels in 1..16384, e.g. 800,600");
  width = static_cast<int>(w);
  height = static_cast<int>(h);
}

void parse_view(const std::string& text, RenderOptions& o) {
  double az = 0, el = 0;
  if (text == "auto") {
    o.auto_view = true;
    return;
  }
  if (text == "top") az = 0, el = 90;
  else if (text == "front") az = 0, el = 0;
  else if (!parse_pair(text, az, el) || el < -90 || el > 90)
    throw_usage("--view '" + text + "': expected auto, top, front or AZIMUTH,ELEVATION in degrees (elevation in -90..90)");
  o.auto_view = false;
  o.azimuth_deg = az;
  o.elevation_deg = el;
}

void check_png_path(const std::string& path, const std::string& option) {
  std::string p = path;
  std::transform(p.begin(), p.end(), p.begin(), [](unsigned char c) { return std::tolower(c); });
  if (p.size() < 5 || p.compare(p.size() - 4, 4, ".png") != 0)
    throw_usage(option + " '" + path + "': pictures are written as PNG; use a name ending in .png");
}

Image read_picture_texture(const std::string& path) { return picture_from_texture(read_texture_file(path)); }

const Eigen::VectorXd& mode_values(PictureMode m, const FaceDistortion& fd) {
  switch (m) {
    case PictureMode::Angle: return fd.angle;
    case PictureMode::Area: return fd.area;
    case PictureMode::Stretch: return fd.stretch_l2;
    default: throw_usage(std::string("mode ") + mode_name(m) + " shows no distortion measure");
  }
}

const Stat& mode_stat(PictureMode m, const DistortionSummary& d) {
  switch (m) {
    case PictureMode::Angle: return d.angle_distortion;
    case PictureMode::Area: return d.area_distortion;
    case PictureMode::Stretch: return d.stretch_l2;
    default: throw_usage(std::string("mode ") + mode_name(m) + " shows no distortion measure");
  }
}

ColourRange mode_range(PictureMode m, const DistortionSummary& d, bool log_scale) {
  const Stat& s = mode_stat(m, d);
  ColourRange r;
  r.log_scale = log_scale;
  // Angle and area distortion are >= 1 by definition; L2 stretch of a face
  // that grew in the plane is below 1, so the range reaches down to it.
  r.lo = std::min(1.0, s.min);
  r.hi = std::max(r.lo, s.max);
  // No finite value at all (every face collapsed): a neutral range.
  if (!(std::isfinite(r.lo) && std::isfinite(r.hi)) || !(r.lo > 0)) r.lo = r.hi = 1;
  return r;
}

Picture make_picture(PictureMode mode, const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV,
                     const PictureSettings& s, const Distortion* distortion) {
  Picture p;
  if (mode == PictureMode::Checker) {
    p.image = render_checker(V, F, UV, s.render);
    return p;
  }
  if (mode == PictureMode::Layout) {
    p.image = render_layout(F, UV, s.render);
    return p;
  }
  if (!distortion) throw_usage(std::string("mode ") + mode_name(mode) + " needs the distortion figures");
  p.has_range = true;
  p.range = mode_range(mode, distortion->summary, s.log_scale);
  FaceValueOptions fv;
  fv.lo = p.range.lo;
  fv.hi = p.range.hi;
  fv.log_scale = p.range.log_scale;
  fv.on_surface = s.on_surface;
  const char* title = mode == PictureMode::Angle ? "angle distortion s1/s2"
                      : mode == PictureMode::Area ? "area distortion max(r, 1/r)"
                                                  : "L2 stretch (Sander et al. 2001)";
  fv.title = std::string(title) + (s.log_scale ? ", log scale" : "");
  p.image = render_face_values(V, F, UV, mode_values(mode, distortion->faces), fv, s.render);
  return p;
}

// How the command line, Python and the reports spell these (intrinsic/choice.h).
template <>
ChoiceTable<PictureMode> choice_table<PictureMode>() {
  static const Choice<PictureMode> rows[] = {{PictureMode::Checker, "checker"},
                                             {PictureMode::Layout, "layout"},
                                             {PictureMode::Angle, "angle"},
                                             {PictureMode::Area, "area"},
                                             {PictureMode::Stretch, "stretch"}};
  return make_choice_table(rows);
}

}  // namespace intrinsic
