// What `render`, `param --render`, `compare` and the Python module share: option parsing for
// pictures, the five picture modes, and writing a set of outputs so that
// either all of them appear or none does.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "intrinsic/metrics.h"
#include "intrinsic/choice.h"
#include "intrinsic/render.h"

namespace intrinsic {

// The five pictures of `intrinsic render`.
enum class PictureMode { Checker, Layout, Angle, Area, Stretch };
template <>
ChoiceTable<PictureMode> choice_table<PictureMode>();

inline constexpr std::array<PictureMode, 5> kAllPictureModes = {PictureMode::Checker, PictureMode::Layout,
                                                                PictureMode::Angle, PictureMode::Area,
                                                                PictureMode::Stretch};

// PictureMode's names (its choice table): "checker", "layout", "angle", "area", "stretch".
std::string mode_name(PictureMode m);
PictureMode parse_mode(const std::string& name, std::string_view label = "mode");  // throws Error(Usage)

// "W,H", each 1..16384; throws Error(Usage) naming the option.
void parse_size(const std::string& text, const std::string& option, int& width, int& height);
// "auto", "top" (0,90), "front" (0,0) or "AZ,EL" in degrees; throws Error(Usage).
void parse_view(const std::string& text, RenderOptions& o);
// Throws Error(Usage) unless the path ends in .png (any case).
void check_png_path(const std::string& path, const std::string& option);
// A texture for the checker picture (RenderOptions::texture): PNG or JPEG
// read by read_texture_file (texture.h), as RGB8 with alpha composited on white.
// Error(Input) naming the file on failure.
Image read_picture_texture(const std::string& path);

struct PictureSettings {
  RenderOptions render;
  bool on_surface = false;  // distortion modes: colour the 3D surface instead of the layout
  bool log_scale = false;   // distortion modes: logarithmic colour scale
};

// The colour bar of a distortion picture.
struct ColourRange {
  double lo = 1, hi = 1;
  bool log_scale = false;
};

// The per-face measure a distortion mode shows, and its summary statistic
// (the same numbers the JSON report prints).
const Eigen::VectorXd& mode_values(PictureMode m, const FaceDistortion& fd);
const Stat& mode_stat(PictureMode m, const DistortionSummary& d);

// Colour range for a distortion mode: [min(1, stat.min), stat.max], so 1
// (no distortion) is always the dark end and the top is the report's max.
ColourRange mode_range(PictureMode m, const DistortionSummary& d, bool log_scale);

struct Distortion {
  FaceDistortion faces;
  DistortionSummary summary;
};

struct Picture {
  Image image;
  bool has_range = false;  // distortion modes only
  ColourRange range;
};

// V, F, UV as for render_checker (one UV per row of V). `distortion` is
// needed for the angle, area and stretch modes (computed from the same V, F, UV).
Picture make_picture(PictureMode mode, const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV,
                     const PictureSettings& settings, const Distortion* distortion);


}  // namespace intrinsic
