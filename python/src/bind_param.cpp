// parameterize(), Result, Parameterizer and BoundaryEditor over the
// library's pipeline (pipeline.h: the same job, checks and report as
// `intrinsic param`), with the GIL released while reading, validating,
// assembling, factoring and solving.
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>

#include "common.h"
#include "intrinsic/boundary_editor.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "intrinsic/metrics.h"
#include "intrinsic/param_option_table.h"
#include "intrinsic/parameterizer.h"

namespace intrinsic::python {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

struct Result {
  py::array uv;
  double residual = 0;
  int flipped_triangles = 0;
  py::dict timings, report;
  std::shared_ptr<const Mesh> mesh;  // the validated mesh the command line writes (V, F on demand)
};

// The mesh: a file read inside the job (as the command line reads it), or arrays.
struct Source {
  MeshData data;
  std::string path;
};

Source to_source(const py::object& V, const py::object& F) {
  Source s;
  if (F.is_none()) {
    if (!py::isinstance<py::str>(V) && !py::hasattr(V, "__fspath__"))
      throw_usage("give V and F arrays, or a mesh file path and no F");
    s.path = to_path(V);
  } else {
    s.data.V = to_V(V);
    s.data.F = to_F(F);
  }
  return s;
}

// What a solve hands back to Python, computed without the GIL.
struct Outcome {
  MatrixX2d UV;
  double residual = 0;
  int flipped = 0;
  nlohmann::json report;
  std::shared_ptr<const Mesh> mesh;
};

// The report of the pipeline (output null: nothing written), timings
// replaced by `timings` when given, plus the total.
Outcome outcome(const ParamRequest& request, ParamOutcome&& o, const nlohmann::json& timings,
                Clock::time_point t0) {
  Outcome out{o.map.UV, o.map.residual, o.distortion.flipped_triangles, nlohmann::json::parse(param_report(request, o, "")), nullptr};
  if (!timings.is_null()) {
    nlohmann::json t = timings;
    for (const char* k : {"assemble", "factor", "solve"}) t[k] = out.report["timings_ms"][k];
    out.report["timings_ms"] = t;
  }
  out.report["timings_ms"]["total"] = ms_since(t0);
  out.mesh = std::make_shared<const Mesh>(std::move(o.mesh));
  return out;
}

Result to_result(const Outcome& o) {
  Result r{from_UV(o.UV), o.residual, o.flipped, {}, to_python(o.report), o.mesh};
  r.timings = r.report["timings_ms"];
  return r;
}

Result parameterize(const py::object& V, const py::object& F, const py::kwargs& kwargs) {
  const ParamRequest request = to_request(kwargs, true);
  const Source src = to_source(V, F);
  Outcome o;
  {
    py::gil_scoped_release release;
    const auto t0 = Clock::now();
    ParamOutcome po = src.path.empty() ? parameterize_data(src.data, request) : parameterize_file(src.path, request);
    o = outcome(request, std::move(po), nullptr, t0);
  }
  return to_result(o);
}

Constraints to_constraints(const py::object& c) {
  if (py::isinstance<py::dict>(c))
    return parse_constraints_json(py::str(py::module_::import("json").attr("dumps")(c)).cast<std::string>(),
                                  "constraints");
  return read_constraints_file(to_path(c));
}

}  // namespace

// One mesh, factored once (intrinsic::Parameterizer). Methods release the GIL
// and are serialized by a mutex: one object is not used by two threads at once.
class PyParameterizer {
 public:
  PyParameterizer(const py::object& V, const py::object& F, const py::kwargs& kwargs)
      : request_(to_request(kwargs, false)), src_(to_source(V, F)) {
    py::gil_scoped_release release;
    const auto t0 = Clock::now();
    if (!src_.path.empty()) src_.data = read_mesh(src_.path, request_.read);
    mesh_ = std::make_shared<const Mesh>(validated_mesh(src_.data, request_));
    if (mesh_->topology.num_components > 1)
      throw_usage("Parameterizer takes a single component; use largest_component=True, or parameterize() for charts");
    p_ = std::make_unique<Parameterizer>(*mesh_, resolved_options(request_, *mesh_));
    if (request_.has_constraints()) p_->set_constraints(resolved_constraints(request_, src_.data.F, *mesh_));
    setup_ms_ = ms_since(t0);
  }

  Result solve(const std::optional<std::vector<FixedVertex>>& fixed) {
    Outcome o;
    {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(mutex_);
      const auto t0 = Clock::now();
      if (fixed) pending_ = fixed;
      ParamOutcome po;
      po.map = pending_ ? p_->solve_with_boundary(*pending_) : p_->solve();
      pending_.reset();
      po.mesh = *mesh_;
      po.distortion = summarize_distortion(mesh_->V, mesh_->F, po.map.UV);
      o = outcome(request_, std::move(po), {{"setup", setup_ms_}}, t0);
    }
    return to_result(o);
  }

  void set_boundary(const py::object& fixed) { pending_ = to_fixed(fixed, "boundary"); }

  void set_constraints(const py::object& c) {
    Constraints constraints = to_constraints(c);
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    match_face_corners(constraints, src_.data.F, *mesh_);
    p_->set_constraints(constraints);
  }

  void set_constraint_targets(const py::object& targets) {
    std::vector<Eigen::Vector2d> t;
    for (const py::handle x : py::iter(targets)) {
      const auto uv = x.cast<std::pair<double, double>>();
      t.emplace_back(uv.first, uv.second);
    }
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    p_->set_constraint_targets(t);
  }

  void clear_constraints() {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    p_->clear_constraints();
  }
  Parameterizer& get() { return *p_; }
  std::mutex& mutex() { return mutex_; }

 private:
  ParamRequest request_;
  Source src_;
  std::shared_ptr<const Mesh> mesh_;
  std::unique_ptr<Parameterizer> p_;
  std::optional<std::vector<FixedVertex>> pending_;
  double setup_ms_ = 0;
  std::mutex mutex_;
};

// intrinsic::BoundaryEditor on a PyParameterizer (kept alive by pybind11).
class PyEditor {
 public:
  PyEditor(PyParameterizer& p, const py::object& basis, double memory_budget_gib, int resolve_above) : p_(p) {
    EditOptions o;
    o.basis = to_choice<BasisMode>(basis, "basis");
    o.memory_budget = static_cast<std::size_t>(memory_budget_gib * double(std::size_t(1) << 30));
    o.resolve_above = resolve_above;
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(p.mutex());
    editor_ = std::make_unique<BoundaryEditor>(p.get(), o);
  }
  py::array move(const py::object& positions) {
    const std::vector<FixedVertex> fixed = to_fixed(positions, "positions");
    {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(p_.mutex());
      editor_->move(fixed);
    }
    return from_UV(editor_->uv());
  }
  BoundaryEditor& get() { return *editor_; }

 private:
  PyParameterizer& p_;
  std::unique_ptr<BoundaryEditor> editor_;
};

void register_editor(py::module_& m) {
  py::class_<PyEditor>(m, "BoundaryEditor",
                       "BoundaryEditor(parameterizer, basis='lazy', memory_budget=2.0, resolve_above=64)\n\n"
                       "Realtime boundary moves by superposition of impulse responses (paper section 4.2),\n"
                       "as `intrinsic edit`: basis 'full' precomputes every response, 'lazy' computes one on a\n"
                       "vertex's first move; memory_budget in GiB; more than resolve_above moved vertices re-solve\n"
                       "with the kept factorization. Each move updates the Parameterizer's boundary.")
      .def(py::init<PyParameterizer&, const py::object&, double, int>(), py::arg("parameterizer"),
           py::arg("basis") = choice_name(BasisMode::Lazy), py::arg("memory_budget") = 2.0, py::arg("resolve_above") = 64,
           py::keep_alive<1, 2>())
      .def("move", &PyEditor::move, py::arg("positions"),
           "Moves fixed vertices [(vertex, u, v), ...] (others stay where they are) -> the new n x 2 UVs.")
      .def_property_readonly("uv", [](PyEditor& e) { return from_UV(e.get().uv()); })
      .def_property_readonly("boundary", [](PyEditor& e) { return from_fixed(e.get().boundary()); })
      .def_property_readonly("precompute_ms", [](PyEditor& e) { return e.get().precompute_ms(); })
      .def_property_readonly("basis_bytes", [](PyEditor& e) { return e.get().basis_bytes(); })
      .def_property_readonly("responses", [](PyEditor& e) { return e.get().responses(); })
      .def_property_readonly("last_update", [](PyEditor& e) {
        const EditStats& s = e.get().last_update();
        py::dict d;
        d["update_ms"] = s.ms;
        d["moved"] = s.moved;
        d["new_responses"] = s.new_responses;
        d["resolved"] = s.resolved;
        return d;
      }, "The last move: update_ms, moved, new_responses, resolved (as `intrinsic edit`'s report).");
}

void register_parameterizer(py::module_& m);

void register_param(py::module_& m) {
  py::class_<Result>(m, "Result",
                     "What a solve produced: uv (n x 2 float64, one row per input vertex, unused vertices at 0),\n"
                     "residual (max relative residual over u and v), flipped_triangles, timings (milliseconds)\n"
                     "and report (the dict `intrinsic param --report` writes, built by the same code; 'input' is\n"
                     "the file path or None for arrays, 'output' is None).")
      .def_readonly("uv", &Result::uv, "n x 2 float64 UVs (a new C-contiguous array)")
      .def_readonly("residual", &Result::residual, "max over u and v of |Ax-b|/|b|")
      .def_readonly("flipped_triangles", &Result::flipped_triangles, "triangles with non-positive UV area")
      .def_readonly("timings", &Result::timings, "stage timings in ms (report['timings_ms'])")
      .def_readonly("report", &Result::report, "the command line's report as a dict (docs/formats.md 'Report')")
      .def_property_readonly(
          "V", [](const Result& r) { return from_V(r.mesh->V); },
          "the validated mesh's positions (n x 3 float64, a new array): what `intrinsic param -o` writes\n"
          "(with largest_component only the kept component's vertices)")
      .def_property_readonly(
          "F", [](const Result& r) { return from_F(r.mesh->F); },
          "the validated mesh's faces (m x 3 int32, a new array), consistently oriented (reoriented faces\n"
          "flipped, as `intrinsic param -o` writes them); write_mesh(path, r.V, r.F, uv=r.uv) writes the\n"
          "command line's output file")
      .def("__repr__", [](const Result& r) {
        return "<intrinsic.Result " + std::to_string(r.uv.shape(0)) + " vertices, residual " +
               short_number(r.residual) + ", " + std::to_string(r.flipped_triangles) + " flipped>";
      });
  m.def("parameterize", &parameterize, py::arg("V"), py::arg("F") = py::none(),
        "parameterize(V, F=None, **options) -> Result\n\n"
        "`intrinsic param` on arrays (or on a file: parameterize(path)). The package's parameterize()\n"
        "documents every option; they are the keys of param_option_table(), plus verbose.");
  m.def("param_option_table", [] { return table_to_python(param_option_table()); },
        "param_option_table() -> list of dict\n\n"
        "The param job's options as the library declares them, in --help's order (the dicts of\n"
        "atlas_option_table()); the group Optimizers holds those a Parameterizer does not take.");
  register_parameterizer(m);
  register_editor(m);
}

void register_parameterizer(py::module_& m) {
  py::class_<PyParameterizer>(m, "Parameterizer",
                              "Parameterizer(V, F=None, **options): assembles and factors once (intrinsic::"
                              "Parameterizer);\nsolve() answers new boundaries and constraints without "
                              "refactoring when the set of fixed\nvertices stays the same. Options as "
                              "parameterize() except the optimize_* ones. One component only.")
      .def(py::init<const py::object&, const py::object&, const py::kwargs&>(), py::arg("V"),
           py::arg("F") = py::none(),
           "V, F arrays (or a mesh file path and no F) and the options of parameterize(): method, lam/lambda_,\n"
           "mu, boundary, spacing, scale, holes, largest_component, solver, pins, max_residual, constraints.\n"
           "Validates, assembles and factors (GIL released). Raises as parameterize().")
      .def("solve", [](PyParameterizer& p) { return p.solve(std::nullopt); },
           "The map for the current boundary (or the one set by set_boundary) and constraints -> Result.")
      .def("solve_with_boundary",
           [](PyParameterizer& p, const py::object& fixed) { return p.solve(to_fixed(fixed, "boundary")); },
           py::arg("fixed"),
           "New positions [(vertex, u, v), ...] (output coordinates) for every fixed vertex, then solve.\n"
           "The same set of fixed vertices needs no refactorization.")
      .def("set_boundary", &PyParameterizer::set_boundary, py::arg("fixed"),
           "Positions [(vertex, u, v), ...] used by the next solve() (see solve_with_boundary).")
      .def("set_constraints", &PyParameterizer::set_constraints, py::arg("constraints"),
           "Point and line constraints: a dict shaped like the JSON constraint file ({'points': [...],\n"
           "'lines': [...]}) or the path of such a file. Replaces earlier constraints; no sparse refactorization.")
      .def("set_constraint_targets", &PyParameterizer::set_constraint_targets, py::arg("targets"),
           "New (u, v) targets for the same constraint rows, in the order of the report's 'constraints'.")
      .def("clear_constraints", &PyParameterizer::clear_constraints, "Removes every constraint.")
      .def_property_readonly("boundary", [](PyParameterizer& p) { return from_fixed(p.get().boundary()); },
                             "Current fixed vertices [(vertex, u, v), ...] in output coordinates.")
      .def_property_readonly("free_vertices", [](PyParameterizer& p) { return p.get().free_vertices(); },
                             "Unknowns per coordinate of the factored system.")
      .def_property_readonly("factorizations", [](PyParameterizer& p) { return p.get().factorizations(); },
                             "Sparse numeric factorizations so far.")
      .def_property_readonly("constraint_setups", [](PyParameterizer& p) { return p.get().constraint_setups(); },
                             "Dense constraint factorizations so far (one per set_constraints).");
}

}  // namespace intrinsic::python
