// The 3D surface pass: orthographic view, z-buffer, two-sided headlight
// Lambert shading, and per-sample colour from UV (checker or texture) or a
// flat per-face colour.
#pragma once

#include <vector>

#include "intrinsic/render.h"
#include "render/image.h"

namespace intrinsic::render {

struct SurfacePaint {
  const MatrixX2d* uv = nullptr;                 // for checker / texture
  const std::vector<Rgb>* face_colours = nullptr;  // overrides uv when set
};

// Ambient share of the lighting; a surface facing the camera gets exactly
// full brightness, so its colour is the unshaded base colour.
inline constexpr double kAmbient = 0.25;
inline constexpr Rgb kCheckerLight = {240, 240, 240};
inline constexpr Rgb kCheckerDark = {70, 100, 165};

// Checker colour at (u, v): the square containing (0, 0)+ is light, and
// neighbours alternate. NaN gives grey.
Rgb checker_colour(double u, double v, int squares);

Image draw_surface(const MatrixX3d& V, const MatrixX3i& F, const SurfacePaint& paint, const RenderOptions& o,
                   int width, int height);

}  // namespace intrinsic::render
