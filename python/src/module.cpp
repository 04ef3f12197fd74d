// intrinsic._intrinsic: the Python binding of the Intrinsic library
// (pybind11). The package intrinsic/ re-exports it; see docs/python.md.
#include "common.h"

namespace intrinsic::python {
// bind_enums.cpp: Method, BoundaryShape, SolverKind, ... (declared here
// rather than in common.h, which holds the option conversions).
void register_enums(py::module_& m);
}  // namespace intrinsic::python

PYBIND11_MODULE(_intrinsic, m) {
  m.doc() =
      "Intrinsic parameterizations of surface meshes (Desbrun, Meyer, Alliez 2002): the compiled module.\n\n"
      "Use the package `intrinsic`, which re-exports everything here. Meshes are numpy arrays: V (n x 3\n"
      "float64 positions) and F (m x 3 int32 zero-based vertex indices); UVs are n x 2 float64.";
  intrinsic::python::register_errors(m);
  intrinsic::python::register_enums(m);
  intrinsic::python::register_io(m);
  intrinsic::python::register_param(m);
  intrinsic::python::register_render(m);
  intrinsic::python::register_atlas(m);
  intrinsic::python::register_texture(m);
  m.attr("__version__") = "0.1.0";
}
