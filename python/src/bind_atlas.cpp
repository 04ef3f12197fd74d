// intrinsic.atlas and intrinsic.write_atlas: `intrinsic atlas` on arrays or a
// file through the library's atlas job (pipeline.h), with the same report and
// the same OBJ bytes.
#include "common.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/error.h"
#include "intrinsic/gltf.h"
#include "intrinsic/io.h"
#include "intrinsic/texture_transfer.h"
#include "intrinsic/report.h"

namespace intrinsic::python {
namespace {

struct AtlasOutput {
  MeshData data;
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

// The chart map as parameterize() spells it: boundary natural|circle|square,
// method/lambda/mu (fixed boundaries only), optimize_lambda or optimize_boundary.
void set_chart_map(ChartMapOptions& m, py::dict& o) {
  const auto given = [&](const char* key) { return o.contains(key) && !o[key].is_none(); };
  const py::object boundary = o.attr("pop")("boundary", py::none());
  if (!boundary.is_none()) m.boundary = to_choice<BoundaryShape>(boundary, "boundary");
  if (m.boundary == BoundaryShape::Natural &&
      ((given("method") && to_choice<Method>(o["method"], "method") != Method::Conformal) || given("lambda") ||
       given("lambda_") || given("lam") || given("mu")))
    throw_usage("method applies to fixed chart boundaries: add boundary='circle' or 'square'");
  m.weights = pop_weights(o);
  const py::object lambda = o.attr("pop")("optimize_lambda", py::none());
  const py::object energy = o.attr("pop")("optimize_boundary", py::none());
  if (!lambda.is_none() && !energy.is_none()) throw_usage("optimize_lambda and optimize_boundary: choose one");
  if (!lambda.is_none()) {
    m.optimizer = ChartOptimizer::OptimalLambda;
    m.lambda_energy = to_choice<LambdaEnergy>(lambda, "optimize_lambda");
  } else if (!energy.is_none()) {
    m.optimizer = ChartOptimizer::OptimizeBoundary;
    m.boundary_energy = to_choice<BoundaryEnergy>(energy, "optimize_boundary");
  }
}

// face_groups: one int per face (e.g. its polygon), -1 for none; the
// length and values are checked by atlas() itself.
std::vector<int> to_face_groups(const py::handle& obj) {
  const auto a = py::array_t<int, py::array::c_style | py::array::forcecast>::ensure(obj);
  if (!a || a.ndim() != 1) throw_usage("face_groups: a one-dimensional array of ints (one per face)");
  return std::vector<int>(a.data(), a.data() + a.shape(0));
}

// Range checks are atlas()'s own (Error(Usage)), as for the command line.
AtlasOptions atlas_options(const py::kwargs& kwargs, ReadOptions& read, SeamsArg& seams, UvArgs& uvs,
                           AtlasOutput& out) {
  AtlasOptions o;
  // The chart map first, spelled as parameterize()'s options.
  py::dict rest = py::dict(kwargs).attr("copy")();
  set_chart_map(o.charts.chart_map, rest);
  for (const auto& [key, value] : rest) {
    const std::string k = py::str(key);
    if (k == "padding") o.pack.padding = value.cast<double>();
    else if (k == "resolution") o.pack.resolution = value.cast<int>();
    else if (k == "texels_per_unit") o.pack.texels_per_unit = value.cast<double>();
    else if (k == "max_pages") o.pack.max_pages = value.cast<int>();
    else if (k == "pack_only") o.pack_only = value.cast<bool>();
    else if (k == "keep_overlaps") o.keep_overlaps = value.cast<bool>();
    else if (k == "uv") uvs.uv = py::reinterpret_borrow<py::object>(value);
    else if (k == "uv_index") uvs.uv_index = py::reinterpret_borrow<py::object>(value);
    else if (k == "max_normal_deviation") o.charts.max_normal_deviation_deg = value.cast<double>();
    else if (k == "min_chart_faces") o.charts.min_chart_faces = value.cast<int>();
    else if (k == "max_stretch") o.charts.max_stretch = value.cast<double>();
    else if (k == "max_charts") o.charts.max_charts = value.cast<int>();
    else if (k == "hard_angle") o.charts.hard_angle_deg = value.cast<double>();
    else if (k == "max_face_stretch") o.charts.max_face_stretch = value.cast<double>();
    else if (k == "isometric_iterations") o.charts.chart_map.isometric_iterations = value.cast<int>();
    else if (k == "weld") o.charts.weld = value.cast<double>();
    else if (k == "reorient") o.charts.reorient = value.cast<bool>();
    else if (k == "atlas_stretch_budget") o.charts.atlas_stretch_budget = value.cast<bool>();
    else if (k == "seams") seams.value = py::reinterpret_borrow<py::object>(value);
    else if (k == "face_groups") o.charts.face_group = to_face_groups(value);
    else if (k == "scope") o.scope = to_choice<AtlasScope>(value, "scope");
    else if (k == "max_vertices") read.max_vertices = value.cast<std::int64_t>();
    else if (k == "instances") read.instances = to_choice<InstanceMode>(value, "instances");
    else if (k == "allow_missing_images") out.gltf.allow_missing_images = value.cast<bool>();
    else if (k == "uv_set") out.gltf.texcoord_set = value.is_none() ? -1 : value.cast<int>();
    else if (k == "replace_used_set") out.gltf.replace_used_set = value.cast<bool>();
    else if (k == "transfer_textures") out.textures.enabled = value.cast<bool>();
    else if (k == "texture_size") out.textures.size = value.cast<int>();
    else if (k == "texture_padding") out.textures.padding = value.cast<int>();
    else throw_usage("unknown option '" + k + "'");
  }
  if (!seams.value.is_none() && !seams.is_path()) o.charts.seams = to_seams(seams.value);
  return o;
}

AtlasOutput run_atlas(const py::object& V, const py::object& F, const py::kwargs& kwargs) {
  AtlasRequest request;
  SeamsArg seams;
  UvArgs uvs;
  AtlasOutput out;
  request.options = atlas_options(kwargs, request.read, seams, uvs, out);
  request.textures = out.textures;
  request.texcoord_set = out.gltf.texcoord_set;
  request.read.max_faces = faces_for_vertices(request.read.max_vertices);
  if (seams.is_path()) request.seams_file = to_path(seams.value);
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
  nlohmann::json report = atlas_report_json(o, "");
  const AtlasTimings& t = o.result.timings;
  report["timings_ms"] = {{"clean", t.clean_ms},     {"segment", t.segment_ms}, {"flatten", t.flatten_ms},
                          {"merge", t.merge_ms},     {"pack", t.pack_ms},       {"total", t.total_ms}};
  out.data = std::move(o.data);
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
      .def_property_readonly("V", [](const AtlasOutput& a) { return from_V(a.data.V); })
      .def_property_readonly("F", [](const AtlasOutput& a) { return from_F(a.result.F); })
      .def("__repr__", [](const AtlasOutput& a) {
        return "<intrinsic.Atlas " + std::to_string(a.result.charts.size()) + " charts, utilization " +
               std::to_string(static_cast<int>(100 * a.result.utilization + 0.5)) + "%>";
      });
  m.def("atlas", &run_atlas, py::arg("V"), py::arg("F") = py::none(),
        "atlas(V, F=None, *, padding=2, resolution=1024, max_normal_deviation=60, min_chart_faces=20,\n"
        "      max_stretch=1.08, max_face_stretch=2, hard_angle=0, isometric_iterations=10, max_charts=0, weld=1e-7, reorient=True, atlas_stretch_budget=True, seams=None, face_groups=None, scope=\"whole\",\n"
        "      boundary='natural', method='conformal', lambda_=None, mu=None, optimize_lambda=None,\n"
        "      optimize_boundary=None, max_vertices=50000000, uv_set=None, replace_used_set=False,\n"
        "      transfer_textures=False, texture_size=2048, texture_padding=4, instances='shared',\n"
        "      allow_missing_images=False) -> Atlas\n\n"
        "`intrinsic atlas` on arrays (V n x 3 float64, F m x 3 int32) or on a mesh file (atlas(path)):\n"
        "any triangle mesh (closed, higher genus, several components, non-manifold bits) cut into disk\n"
        "charts, each flattened by the natural conformal map, packed into [0,1]^2 without flips or\n"
        "overlaps. Options as the command line's; seams is a seams file's path or k x 2 vertex\n"
        "indices (edges to cut). The GIL is released while it runs. Raises\n"
        "UsageError / InputError as the command line exits 1 / 2.");
  m.def(
      "write_atlas",
      [](const py::object& path, const AtlasOutput& a) -> py::object {
        const std::string p = to_path(path);
        check_atlas_output(p);
        TextureTransferReport baked;
        {
          py::gil_scoped_release release;
          baked = write_atlas_with_textures(p, a.data, a.result, a.gltf, a.textures);
        }
        if (!a.textures.enabled) return py::none();
        return to_python(texture_transfer_json(baked));
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
