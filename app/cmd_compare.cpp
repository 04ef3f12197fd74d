// `intrinsic compare`: one picture, a checker-rendered panel per method with
// its distortion figures under it, all from the same view (paper Figure 3).
#include <algorithm>
#include <climits>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <nlohmann/json.hpp>

#include "command.h"
#include "intrinsic/error.h"
#include "intrinsic/intrinsic.h"
#include "intrinsic/io.h"
#include "intrinsic/parameterize.h"
#include "intrinsic/pictures.h"
#include "intrinsic/report.h"

namespace intrinsic::app {
namespace {

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream s(text);
  for (std::string item; std::getline(s, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

// The methods compare can run without further parameters; "natural" is the
// conformal weights with the natural (free) boundary.
bool is_natural(const std::string& name) { return name == choice_name(BoundaryShape::Natural); }

Method compare_method(const std::string& name) {
  if (is_natural(name)) return Method::Conformal;
  if (!is_choice<Method>(name) || parse_method(name) == Method::Mixed) {
    std::string names;  // every method but mixed, then natural
    for (const std::string& n : choice_names<Method>())
      if (n != choice_name(Method::Mixed)) names += n + ", ";
    if (name == choice_name(Method::Mixed))
      throw_usage("--methods: 'mixed' needs --lambda and --mu; run it with `intrinsic param`");
    throw_usage("--methods: unknown method '" + name + "' (use " + names + choice_name(BoundaryShape::Natural) + ")");
  }
  return parse_method(name);
}

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

// Every panel shows the same view with the same framing, which fits the
// mesh's bounding sphere; a tall or wide mesh leaves empty bands. Crops the
// rows (or columns) that are empty in every panel, keeping a small margin, so
// the panels stay aligned with each other.
void crop_common_background(std::vector<Image>& panels) {
  int x0 = INT_MAX, y0 = INT_MAX, x1 = -1, y1 = -1;
  for (const Image& p : panels)
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) {
        const std::uint8_t* c = p.pixel(x, y);
        if (c[0] != 255 || c[1] != 255 || c[2] != 255)
          x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      }
  if (x1 < 0) return;  // nothing drawn
  const Image& first = panels.front();
  const int margin = std::max(2, std::min(first.width, first.height) / 25);
  x0 = std::max(0, x0 - margin), y0 = std::max(0, y0 - margin);
  x1 = std::min(first.width - 1, x1 + margin), y1 = std::min(first.height - 1, y1 + margin);
  for (Image& p : panels) {
    Image out(x1 - x0 + 1, y1 - y0 + 1);
    for (int y = y0; y <= y1; ++y) std::copy(p.pixel(x0, y), p.pixel(x1, y) + 3, out.pixel(0, y - y0));
    p = std::move(out);
  }
}

struct CompareArgs {
  std::string input, output, report;
  std::string methods = "tutte,floater,conformal,authalic,natural";
  std::string boundary = choice_name(BoundaryShape::Circle), size = "400,400", view = "auto";
  int columns = 0, squares = 16;
  bool quiet = false;
};

struct Panel {
  Image image;
  std::string caption;
  nlohmann::json figures;
};

// One method's map, its checker picture, caption and figures.
Panel compare_panel(const CompareArgs& a, const Mesh& mesh, const std::string& name, const RenderOptions& ro) {
  ParamOptions o;
  o.weights.method = compare_method(name);
  o.boundary = is_natural(name) ? BoundaryShape::Natural : parse_choice<BoundaryShape>(a.boundary, "--boundary");
  const auto t1 = std::chrono::steady_clock::now();
  const ParamResult r = parameterize(mesh, o);
  const double ms = elapsed_ms(t1);
  const DistortionSummary d = summarize_distortion(mesh.V, mesh.F, r.UV);
  Panel p;
  p.image = render_checker(mesh.V, mesh.F, r.UV, ro);
  // Short lines, so the text can be large in a narrow panel.
  p.caption = name + "\n" + std::to_string(d.flipped_triangles) + " flipped\nangle mean " +
              fixed(d.angle_distortion.mean, 3) + "\nangle max " + fixed(d.angle_distortion.max, 2) + "\narea mean " +
              fixed(d.area_distortion.mean, 3) + "\n" + fixed(ms, 0) + " ms";
  p.figures = {{"method", name}, {"solver", solvers_name(r.solvers)}, {"time_ms", ms}};
  p.figures.update(nlohmann::json::parse(distortion_report(d)));
  return p;
}

int run_compare(const CompareArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  check_png_path(a.output, "--output");
  const std::vector<std::string> names = split_list(a.methods);
  if (names.empty()) throw_usage("--methods: give at least one method");
  for (const std::string& n : names) compare_method(n);  // refuse an unknown name before reading
  RenderOptions ro;
  parse_size(a.size, "--size", ro.width, ro.height);
  parse_view(a.view, ro);
  ro.checker_squares = a.squares;
  ro.fit_uv = true;
  const Mesh mesh = make_mesh(read_mesh(a.input));
  std::vector<Image> panels;
  std::vector<std::string> captions;
  nlohmann::json results = nlohmann::json::array();
  for (const std::string& name : names) {
    Panel p = compare_panel(a, mesh, name, ro);
    panels.push_back(std::move(p.image));
    captions.push_back(p.caption);
    results.push_back(p.figures);
  }
  crop_common_background(panels);
  const int n = static_cast<int>(panels.size());
  const int columns = a.columns > 0 ? a.columns : n <= 5 ? n : (n + 1) / 2;
  std::vector<std::pair<std::string, std::string>> files = {
      {a.output, encode_png(compose_panels(panels, captions, columns))}};
  if (!a.report.empty()) {
    nlohmann::json report = nlohmann::json::parse(mesh_report(mesh));
    report["boundary"] = a.boundary;
    report["methods"] = results;
    report["timings_ms"] = {{"total", elapsed_ms(t0)}};
    files.emplace_back(a.report, report.dump(2) + "\n");
  }
  write_all(files);
  if (!a.quiet) std::cout << a.output << ": " << n << " methods, " << static_cast<long>(elapsed_ms(t0)) << " ms\n";
  return 0;
}

}  // namespace

void register_compare(CLI::App& app, Runner& run) {
  auto a = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand("compare", "One picture comparing methods: checker render and figures per method");
  cmd->add_option("input", a->input, "Input mesh (.obj, .off, .ply, .stl, optionally .gz)")->required();
  cmd->add_option("-o,--output", a->output, "Output picture (.png)")->required();
  cmd->add_option("--methods", a->methods, "Comma-separated: tutte, floater, conformal, authalic, natural")
      ->capture_default_str();
  cmd->add_option("--boundary", a->boundary, "Fixed boundary shape: circle | square")
      ->check(CLI::IsMember({choice_name(BoundaryShape::Circle), choice_name(BoundaryShape::Square)}))
      ->capture_default_str();
  cmd->add_option("--size", a->size, "Size of each panel in pixels, W,H")->capture_default_str();
  cmd->add_option("--columns", a->columns, "Panels per row (default: one row of up to 5, else two rows)")
      ->check(CLI::Range(1, 64));
  cmd->add_option("--view", a->view, "3D view: auto | top | front | AZIMUTH,ELEVATION")->capture_default_str();
  cmd->add_option("--squares", a->squares, "Checker squares across the UV square")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  cmd->add_option("--report", a->report, "Write the figures of every method as JSON");
  cmd->add_flag("-q,--quiet", a->quiet, "Print nothing on success");
  cmd->callback([&run, a] { run = [a] { return run_compare(*a); }; });
}

}  // namespace intrinsic::app
