// metrics (the distortion report) and render (the pictures of
// `intrinsic render`), through the command line's own report and picture code.
#include "common.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "intrinsic/metrics.h"
#include "intrinsic/pictures.h"
#include "intrinsic/report.h"

namespace intrinsic::python {
namespace {

py::dict metrics(const py::object& V, const py::object& F, const py::object& uv) {
  MeshData data;
  data.V = to_V(V);
  data.F = to_F(F);
  const MatrixX2d UV = to_UV(uv);
  if (UV.rows() != data.V.rows()) throw_usage("uv must have one row per vertex (" + std::to_string(data.V.rows()) + ")");
  nlohmann::json report;
  {
    py::gil_scoped_release release;
    ValidateOptions vo;  // as `intrinsic metrics`: orientation kept, so flips are reported
    vo.allow_several_components = true;
    vo.allow_closed = true;
    const Mesh mesh = make_mesh(data, vo);
    report = nlohmann::json::parse(mesh_report(mesh));
    report.erase("input");
    report.update(nlohmann::json::parse(distortion_report(summarize_distortion(data.V, data.F, UV))));
    report["stretch"] = nlohmann::json::parse(stretch_report(summarize_stretch(data.V, data.F, UV)));
  }
  return to_python(report);
}

PictureSettings settings(const py::object& size, const py::object& view, bool on_surface, bool log_scale) {
  PictureSettings s;
  const auto wh = size.cast<std::pair<int, int>>();
  parse_size(std::to_string(wh.first) + "," + std::to_string(wh.second), "size", s.render.width,
                  s.render.height);
  const std::string v = py::isinstance<py::str>(view)
                            ? view.cast<std::string>()
                            : py::str(",").attr("join")(py::module_::import("builtins").attr("map")(
                                  py::module_::import("builtins").attr("repr"), view)).cast<std::string>();
  parse_view(v, s.render);
  s.render.fit_uv = true;
  s.on_surface = on_surface;
  s.log_scale = log_scale;
  return s;
}

py::object render(const py::object& V, const py::object& F, const py::object& uv, const std::string& mode,
                  const py::object& size, const py::object& view, const py::object& path, bool on_surface,
                  bool log_scale) {
  const PictureMode pm = parse_mode(mode, "mode");
  if ((on_surface || log_scale) && (pm == PictureMode::Checker || pm == PictureMode::Layout))
    throw_usage("on_surface and log apply to the angle, area and stretch modes only");
  const PictureSettings s = settings(size, view, on_surface, log_scale);
  const std::string out = path.is_none() ? "" : to_path(path);
  if (!out.empty()) check_png_path(out, "path");
  const MatrixX3d v = to_V(V);
  const MatrixX3i f = to_F(F);
  const MatrixX2d t = to_UV(uv);
  if (t.rows() != v.rows()) throw_usage("uv must have one row per vertex (" + std::to_string(v.rows()) + ")");
  Image image;
  {
    py::gil_scoped_release release;
    Distortion d;
    if (pm != PictureMode::Checker && pm != PictureMode::Layout) {
      d.faces = face_distortion(v, f, t);
      d.summary = summarize_distortion(v, f, t);
    }
    image = make_picture(pm, v, f, t, s, &d).image;
    if (!out.empty()) write_file_atomically(out, encode_png(image));
  }
  if (!out.empty()) return py::none();
  py::array_t<std::uint8_t> a({image.height, image.width, 3});
  std::copy(image.rgb.begin(), image.rgb.end(), a.mutable_data());
  return std::move(a);
}

}  // namespace

void register_render(py::module_& m) {
  m.def("metrics", &metrics, py::arg("V"), py::arg("F"), py::arg("uv"),
        "metrics(V, F, uv) -> dict\n\n"
        "The distortion report of `intrinsic metrics` for one UV per vertex: mesh facts (vertices, faces,\n"
        "boundary_loops, loops, components, ...), flipped_triangles, collapsed_triangles, min/mean/max of\n"
        "angle_distortion, area_distortion, stretch_l2, stretch_linf, edge_length_distortion, and\n"
        "edge_length_energy, area_energy, distortion_normalisation, stretch (Sander's L2 and per-face\n"
        "stretch percentiles, docs/maths.md 9.8; docs/formats.md 'Report'). Faces are taken as\n"
        "listed (not reoriented) so flipped triangles are counted.");
  m.def("render", &render, py::arg("V"), py::arg("F"), py::arg("uv"), py::arg("mode") = choice_name(PictureMode::Checker),
        py::arg("size") = py::make_tuple(1024, 1024), py::arg("view") = "auto", py::arg("path") = py::none(),
        py::arg("on_surface") = false, py::arg("log") = false,
        "render(V, F, uv, mode='checker', size=(1024, 1024), view='auto', path=None, on_surface=False, log=False)\n\n"
        "The pictures of `intrinsic render` (docs/pictures.md): mode 'checker' (the surface textured with a\n"
        "checkerboard through uv), 'layout' (the flattened mesh, flipped triangles red), or the per-triangle\n"
        "distortion 'angle', 'area', 'stretch' with a colour bar (on_surface: on the 3D surface; log: log scale).\n"
        "size is (width, height); view is 'auto', 'top', 'front' or (azimuth, elevation) in degrees.\n"
        "Returns an (height, width, 3) uint8 RGB array, or None after writing a PNG to path (atomically).");
}

}  // namespace intrinsic::python
