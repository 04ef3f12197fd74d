// `intrinsic render`: a picture of a mesh that already has UVs.
#include <iostream>
#include <nlohmann/json.hpp>

#include "command.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "intrinsic/metrics.h"
#include "intrinsic/render.h"
#include "choice_option.h"
#include "intrinsic/pictures.h"
#include "intrinsic/report.h"
#include "intrinsic/uv_mesh.h"

namespace intrinsic::app {

namespace {

struct RenderArgs {
  std::string input, output, report, texture;
  std::string mode = choice_name(PictureMode::Checker), size = "1024,1024", view = "auto";
  int squares = 16, supersample = 3;
  bool on_surface = false, log_scale = false, quiet = false;
};

// The picture settings the options ask for; `texture` is read here (it must
// outlive the settings, which point to it).
PictureSettings render_settings(const RenderArgs& a, PictureMode mode, Image& texture) {
  PictureSettings s;
  parse_size(a.size, "--size", s.render.width, s.render.height);
  parse_view(a.view, s.render);
  s.render.checker_squares = a.squares;
  s.render.supersample = a.supersample;
  s.on_surface = a.on_surface;
  s.log_scale = a.log_scale;
  // The checker density follows the UV bounding box, whatever the UV
  // scale; a texture image is mapped through the UVs as they are.
  s.render.fit_uv = a.texture.empty();
  if (!a.texture.empty()) {
    if (mode != PictureMode::Checker) throw_usage("--texture applies to --mode checker only");
    texture = read_picture_texture(a.texture);
    s.render.texture = &texture;
  }
  if ((a.on_surface || a.log_scale) && (mode == PictureMode::Checker || mode == PictureMode::Layout))
    throw_usage("--on-surface and --log apply to the angle, area and stretch modes only");
  return s;
}

nlohmann::json render_report(const RenderArgs& a, PictureMode mode, const UvMesh& m, const Picture& p,
                             const Distortion& d) {
  nlohmann::json r = {{"input", a.input},           {"output", a.output},
                      {"mode", a.mode},             {"width", p.image.width},
                      {"height", p.image.height},   {"vertices", m.input_vertices},
                      {"texture_coordinates", m.UV.rows()}, {"faces", m.F.rows()}};
  if (p.has_range) {
    r["measure"] = mode == PictureMode::Stretch ? "stretch_l2"
                   : mode == PictureMode::Angle ? "angle_distortion"
                                                : "area_distortion";
    r["colour_range"] = {{"lo", p.range.lo}, {"hi", p.range.hi}, {"log", p.range.log_scale}};
    r["values"] = nlohmann::json::parse(stat_report(mode_stat(mode, d.summary)));
    r["flipped_triangles"] = d.summary.flipped_triangles;
    r["collapsed_triangles"] = d.summary.collapsed_triangles;
  }
  return r;
}

int run_render(const RenderArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  check_png_path(a.output, "--output");
  const PictureMode mode = parse_mode(a.mode, "--mode");
  Image texture;
  const PictureSettings s = render_settings(a, mode, texture);
  const UvMesh m = split_by_texcoord(read_mesh(a.input));
  const double t_read = elapsed_ms(t0);
  const auto t1 = std::chrono::steady_clock::now();
  Distortion d;
  const bool needs_distortion = mode != PictureMode::Checker && mode != PictureMode::Layout;
  if (needs_distortion) {
    d.faces = face_distortion(m.V, m.F, m.UV);
    d.summary = summarize_distortion(m.V, m.F, m.UV);
  }
  Picture p;
  int charts = 0;
  if (mode == PictureMode::Layout) {
    // An atlas (several UV charts, e.g. `intrinsic atlas` or another tool's
    // output) gets a colour per chart, folded or overlapping faces in red.
    const UvAtlasMetrics atlas = uv_atlas_metrics(m.V, m.F, m.UV);
    charts = static_cast<int>(atlas.charts.size());
    if (charts > 1) {
      std::vector<char> red(m.F.rows());
      for (Eigen::Index f = 0; f < m.F.rows(); ++f) red[f] = atlas.face_folded[f] | atlas.face_overlapping[f];
      p.image = render_atlas_layout(m.F, m.UV, atlas.face_chart, red, s.render);
    }
  }
  if (p.image.width == 0) p = make_picture(mode, m.V, m.F, m.UV, s, needs_distortion ? &d : nullptr);
  const double t_render = elapsed_ms(t1);
  const auto t2 = std::chrono::steady_clock::now();
  std::vector<std::pair<std::string, std::string>> files{{a.output, encode_png(p.image)}};
  const double t_encode = elapsed_ms(t2);
  if (!a.report.empty()) {
    nlohmann::json r = render_report(a, mode, m, p, d);
    if (mode == PictureMode::Layout) r["charts"] = charts;
    r["timings_ms"] = {{"read", t_read}, {"render", t_render}, {"encode", t_encode}, {"total", elapsed_ms(t0)}};
    files.emplace_back(a.report, r.dump(2) + "\n");
  }
  write_all(files);
  if (!a.quiet) {
    std::cout << a.output << ": " << a.mode << ", " << p.image.width << "x" << p.image.height;
    if (p.has_range) std::cout << ", colour range " << p.range.lo << " .. " << p.range.hi;
    std::cout << ", render " << static_cast<long>(t_render) << " ms\n";
  }
  return 0;
}

}  // namespace

void register_render(CLI::App& app, Runner& run) {
  auto a = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Picture of a mesh with UVs: checkerboard, layout or distortion");
  cmd->add_option("input", a->input, "Mesh with texture coordinates (OBJ vt or PLY u,v; optionally .gz)")->required();
  cmd->add_option("-o,--output", a->output, "Output picture (.png)")->required();
  cmd->add_option("--mode", a->mode,
                  "checker: textured 3D surface | layout: the flattened mesh, flipped triangles red (an atlas: "
                  "one colour per chart, folded or overlapping triangles red) | "
                  "angle, area, stretch: distortion per triangle with a colour bar")
      ->check(choice_check<PictureMode>())
      ->capture_default_str();
  cmd->add_option("--size", a->size, "Picture size in pixels, W,H")->capture_default_str();
  cmd->add_option("--view", a->view, "3D view: auto (along the mean normal) | top | front | AZIMUTH,ELEVATION")
      ->capture_default_str();
  cmd->add_option("--texture", a->texture, "PNG image to map through the UVs instead of the checkerboard");
  cmd->add_option("--squares", a->squares, "Checker squares across the UV bounding box")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  cmd->add_option("--supersample", a->supersample, "Antialiasing samples per pixel along each axis")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  cmd->add_flag("--on-surface", a->on_surface, "Distortion modes: colour the 3D surface instead of the layout");
  cmd->add_flag("--log", a->log_scale, "Distortion modes: logarithmic colour scale");
  cmd->add_option("--report", a->report, "Write what was drawn (mode, colour range, figures) as JSON");
  cmd->add_flag("-q,--quiet", a->quiet, "Print nothing on success");
  cmd->callback([&run, a] { run = [a] { return run_render(*a); }; });
}

}  // namespace intrinsic::app
