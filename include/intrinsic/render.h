// Software renderer for the figures the paper shows: a checkerboard-textured
// 3D surface, the flattened UV layout (flipped triangles in red) and
// per-triangle scalar fields with a colour bar. Everything is drawn on the
// CPU into an RGB8 image so the tool needs no display or GPU; PNG encoding
// and decoding are in memory so the caller decides where bytes go.
//
// Conventions: z is "up" for azimuth/elevation views (azimuth 0, elevation 0
// looks along +y; elevation 90 looks down -z with x to the right and y up).
// Projection is orthographic so pictures of different parameterizations of
// the same mesh line up exactly. UV (0,0) is the bottom-left of a texture.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "intrinsic/image.h"
#include "intrinsic/mesh.h"

namespace intrinsic {

struct RenderOptions {
  int width = 1024, height = 1024;  // output size in pixels, 1..16384
  int supersample = 3;              // samples per pixel along each axis, 1..8
  bool auto_view = true;            // camera along the area-weighted mean normal
  double azimuth_deg = 0, elevation_deg = 0;  // used when auto_view is false
  int checker_squares = 16;  // squares across the unit UV square
  // Map the UV bounding box onto the unit square (aspect kept) before
  // texturing, so the checker density does not depend on the UV scale.
  bool fit_uv = false;
  const Image* texture = nullptr;  // replaces the checkerboard when set; UV wraps
};

// 3D surface, Lambert-shaded (two-sided headlight + ambient), textured
// through UV (one row per vertex of V).
Image render_checker(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV,
                     const RenderOptions& options);

// The flattened mesh: light fill, thin interior edges (omitted when triangles
// are too small for them to be seen), thick boundary edges, flipped triangles
// (signed UV area <= 0) filled red. UV is framed with a margin, aspect kept.
Image render_layout(const MatrixX3i& F, const MatrixX2d& UV, const RenderOptions& options);

// An atlas: each chart (face_chart, #F entries, values >= 0) filled in its own
// colour (hues spread by the golden angle, so neighbours in index differ),
// faces marked in `red` (may be empty: e.g. folded or overlapping ones) in
// red, boundary edges of charts thick.
Image render_atlas_layout(const MatrixX3i& F, const MatrixX2d& UV, const std::vector<int>& face_chart,
                          const std::vector<char>& red, const RenderOptions& options);

struct FaceValueOptions {
  std::string title;
  double lo = 0, hi = 1;   // values mapped to the ends of the colour map
  bool log_scale = false;  // needs 0 < lo <= hi
  bool on_surface = false; // draw on the 3D surface instead of the UV layout
};

// Per-face scalar field coloured with a perceptual (viridis-like) map, with a
// colour bar (min, max, ticks) on the right and the title on top. Values
// outside [lo, hi] are clamped; non-finite values are grey. V may be empty
// unless on_surface is set.
Image render_face_values(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV,
                         const Eigen::VectorXd& values, const FaceValueOptions& fv,
                         const RenderOptions& options);

// Panels in a grid, `columns` wide, each with a (possibly multi-line) caption
// under it; for side-by-side comparisons. captions may be shorter than panels.
Image compose_panels(const std::vector<Image>& panels, const std::vector<std::string>& captions,
                     int columns);


}  // namespace intrinsic
