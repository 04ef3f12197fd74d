// intrinsic.atlas and intrinsic.write_atlas: `intrinsic atlas` on arrays or a
// file through the library's atlas job (pipeline.h), with the same report and
// the same OBJ bytes.
#include "common.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/atlas_option_table.h"
#include "intrinsic/error.h"
#include "intrinsic/gltf.h"
#include "intrinsic/io.h"
#include "intrinsic/texture_transfer.h"
#include "intrinsic/report.h"

namespace intrinsic::python {
namespace {

struct AtlasOutput {
  MeshFile input;  // with a file's document, which write_atlas gives back
  AtlasResult result;
  py::object uv, uv_index, face_chart, report;
  // How write_atlas writes it: the glTF set (uv_set) and the texture transfer.
  GltfWriteOptions gltf;
  TextureTransferOptions textures;
};

// seams: a path to a seams file (read against the mesh, errors name its
// lines) or k x 2 vertex indices (checked by atlas() itself).
// The arrays' own UVs (pack_only): uv (k x 2) and uv_index (#F x 3 rows of
// uv), as an Atlas gives them; checked by the re-pack against F.
struct UvArgs {
  py::object uv = py::none(), uv_index = py::none();
};

struct SeamsArg {
  py::object value = py::none();
  bool is_path() const { return py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__"); }
};

std::vector<SeamEdge> to_seams(const py::handle& obj) {
  const py::array a = c_array_int32(obj, 2, "seams");
  const auto* p = static_cast<const std::int32_t*>(a.data());
  std::vector<SeamEdge> seams(static_cast<size_t>(a.shape(0)));
  for (size_t k = 0; k < seams.size(); ++k) seams[k] = {p[2 * k], p[2 * k + 1]};
  return seams;
}

// face_groups: one int per face (e.g. its polygon), -1 for none; the
// length and values are checked by atlas() itself.
std::vector<int> to_face_groups(const py::handle& obj) {
  const auto a = py::array_t<int, py::array::c_style | py::array::forcecast>::ensure(obj);
  if (!a || a.ndim() != 1) throw_usage("face_groups: a one-dimensional array of ints (one per face)");
  return std::vector<int>(a.data(), a.data() + a.shape(0));
}

// The keywords: the arrays (uv, uv_index, face_groups, seams as vertex
// pairs) are data; every other keyword is an option of the library's table
// (atlas_option_table.h), which checks it and makes the request. None
// leaves an option at its default.
AtlasRequest atlas_request_of(const py::kwargs& kwargs, SeamsArg& seams, UvArgs& uvs, py::object& face_groups) {
  GivenOptions given;
  for (const auto& [key, value] : kwargs) {
    const std::string k = py::str(key);
    if (k == "uv") uvs.uv = py::reinterpret_borrow<py::object>(value);
    else if (k == "uv_index") uvs.uv_index = py::reinterpret_borrow<py::object>(value);
    else if (k == "face_groups") face_groups = py::reinterpret_borrow<py::object>(value);
    else if (k == "seams") seams.value = py::reinterpret_borrow<py::object>(value);
    else if (!value.is_none()) given.emplace_back(k, to_option_value(atlas_option_table(), k, value));
  }
  if (seams.is_path()) given.emplace_back("seams", OptionValue(to_path(seams.value)));
  AtlasRequest request = atlas_request(given, OptionSpelling::Keyword);
  if (!seams.value.is_none() && !seams.is_path()) request.options.charts.seams = to_seams(seams.value);
  if (!face_groups.is_none()) request.options.charts.face_group = to_face_groups(face_groups);
  return request;
}

AtlasOutput run_atlas(const py::object& V, const py::object& F, const py::kwargs& kwargs) {
  SeamsArg seams;
  UvArgs uvs;
  py::object face_groups = py::none();
  AtlasOutput out;
  const AtlasRequest request = atlas_request_of(kwargs, seams, uvs, face_groups);
  out.gltf = request.gltf;
  out.textures = request.textures;
  const bool from_file = F.is_none();
  const std::string path = from_file ? to_path(V) : "";
  MeshData data;
  if (!from_file) {
    data.V = to_V(V);
    data.F = to_F(F);
    if (uvs.uv.is_none() != uvs.uv_index.is_none()) throw_usage("uv and uv_index go together (an Atlas's uv, uv_index)");
    if (!uvs.uv.is_none()) {
      data.TC = to_UV(uvs.uv, "uv");
      data.FTC = to_F(uvs.uv_index);
      if (data.FTC.rows() != data.F.rows()) throw_usage("uv_index needs one row per face of F");
      if (data.FTC.size() > 0 && (data.FTC.minCoeff() < 0 || data.FTC.maxCoeff() >= data.TC.rows()))
        throw_usage("uv_index refers to a row outside uv");
    }
  }
  AtlasOutcome o;
  {
    py::gil_scoped_release release;
    o = from_file ? atlas_file(path, request) : atlas_data(std::move(data), request);
  }
  nlohmann::json report = nlohmann::json::parse(atlas_report(o, ""));
  const AtlasTimings& t = o.result.timings;
  report["timings_ms"] = {{"clean", t.clean_ms},     {"segment", t.segment_ms}, {"flatten", t.flatten_ms},
                          {"merge", t.merge_ms},     {"pack", t.pack_ms},       {"total", t.total_ms}};
  out.input = std::move(o.input);
  out.result = std::move(o.result);
  out.uv = from_UV(out.result.UV);
  out.uv_index = from_F(out.result.FUV);
  py::array_t<std::int32_t> chart(static_cast<py::ssize_t>(out.result.face_chart.size()));
  std::copy(out.result.face_chart.begin(), out.result.face_chart.end(), chart.mutable_data());
  out.face_chart = chart;
  out.report = to_python(report);
  return out;
}

}  // namespace

void register_atlas(py::module_& m) {
  py::class_<AtlasOutput>(m, "Atlas",
                          "An atlas: uv (k x 2 float64 in [0,1]^2), uv_index (#F x 3 int32: per face corner, a row\n"
                          "of uv), face_chart (#F int32, -1 for degenerate faces), V (the input's vertices), F (the\n"
                          "input's faces; with reorient=True the reoriented ones reversed) and report (the dict\n"
                          "`intrinsic atlas --report` writes; 'input' is the path or None, 'output' None).")
      .def_readonly("uv", &AtlasOutput::uv)
      .def_readonly("uv_index", &AtlasOutput::uv_index)
      .def_readonly("face_chart", &AtlasOutput::face_chart)
      .def_readonly("report", &AtlasOutput::report)
      .def_property_readonly("V", [](const AtlasOutput& a) { return from_V(a.input.mesh.V); })
      .def_property_readonly("F", [](const AtlasOutput& a) { return from_F(a.result.F); })
      .def("__repr__", [](const AtlasOutput& a) {
        return "<intrinsic.Atlas " + std::to_string(a.result.charts.size()) + " charts, utilization " +
               std::to_string(static_cast<int>(100 * a.result.utilization + 0.5)) + "%>";
      });
  m.def("atlas", &run_atlas, py::arg("V"), py::arg("F") = py::none(),
        "atlas(V, F=None, **options) -> Atlas\n\n"
        "`intrinsic atlas` on arrays (V n x 3 float64, F m x 3 int32) or on a mesh file (atlas(path)).\n"
        "options: the keywords of atlas_option_table() (intrinsic.atlas lists them with their\n"
        "defaults), and the arrays seams (k x 2 vertex indices, or a seams file's path), face_groups,\n"
        "uv and uv_index. The GIL is released while it runs. Raises UsageError / InputError as the\n"
        "command line exits 1 / 2.");
  m.def("atlas_option_table", [] { return table_to_python(atlas_option_table()); },
        "atlas_option_table() -> list of dict\n\n"
        "The atlas job's options as the library declares them, in --help's order: per option its\n"
        "key (the keyword), flag (the command line's), flag_negates, aliases, type (bool, int,\n"
        "float, choice, path, str, choice or path, pair), group, help, min and max (None: no bound),\n"
        "choices, repeated (given once per value), value_name and default (None: unset unless given).");
  m.def(
      "write_atlas",
      [](const py::object& path, const AtlasOutput& a) -> py::object {
        const std::string p = to_path(path);
        check_atlas_output(p);
        TextureTransferReport baked;
        {
          py::gil_scoped_release release;
          baked = write_atlas_with_textures(p, a.input, a.result, a.gltf, a.textures);
        }
        if (!a.textures.enabled) return py::none();
        return to_python(nlohmann::json::parse(texture_transfer_report(baked)));
      },
      py::arg("path"), py::arg("atlas"),
      "write_atlas(path, atlas)\n\nWrites the file `intrinsic atlas -o path` writes (same bytes): .obj (the\n"
      "input's vertices in input order, one vt per atlas UV, faces f v/vt) or .glb (glTF 2.0 binary,\n"
      "vertices split at seams; a glTF input: its own document with the atlas as TEXCOORD_<uv_set>); atomically.\n"
      "With atlas(..., transfer_textures=True): the textures reading the replaced set are baked into the new\n"
      "layout (docs/textures.md) and the report's 'textures' dict ({'baked': [...], 'notes': [...]}) is\n"
      "returned (else None). Raises UsageError for another extension, InputError for an image it cannot\n"
      "read, OutputError.");
}

}  // namespace intrinsic::python
