// intrinsic.Error and its subclasses, one per intrinsic::ErrorKind (the
// command line's exit codes 1-4), with the library's message unchanged: the
// text the command line prints after "intrinsic: error: ".
#include "common.h"
#include "intrinsic/error.h"

namespace intrinsic::python {
namespace {

PyObject* g_classes[5] = {nullptr, nullptr, nullptr, nullptr, nullptr};  // by exit code

PyObject* new_class(py::module_& m, const char* name, const char* doc, PyObject* base, int exit_code) {
  const std::string qualified = std::string("intrinsic.") + name;
  PyObject* cls = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, base, nullptr);
  if (!cls) throw py::error_already_set();
  py::handle h(cls);
  h.attr("exit_code") = exit_code;
  m.add_object(name, h);
  return cls;
}

}  // namespace

void register_errors(py::module_& m) {
  g_classes[0] = new_class(m, "Error",
                           "Every failure of Intrinsic. `exit_code` is the command line's exit code for it and the "
                           "message is the one the command line prints after 'intrinsic: error: '.",
                           PyExc_Exception, 0);
  g_classes[1] = new_class(m, "UsageError", "Bad options or arguments (exit code 1).", g_classes[0], 1);
  g_classes[2] = new_class(m, "InputError",
                           "Unreadable or malformed input, or a mesh that is refused: closed, non-manifold, bad "
                           "index, bad constraints (exit code 2).",
                           g_classes[0], 2);
  g_classes[3] = new_class(m, "NumericalError",
                           "Singular system, non-finite result, residual above max_residual (exit code 3).",
                           g_classes[0], 3);
  g_classes[4] = new_class(m, "OutputError", "The result could not be written (exit code 4).", g_classes[0], 4);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      const int code = e.exit_code();
      PyErr_SetString(g_classes[code >= 1 && code <= 4 ? code : 0], e.what());
    }
  });
}

}  // namespace intrinsic::python
