// intrinsic.Error and its subclasses, one per intrinsic::ErrorKind (the
// command line's exit codes 1-4), with the library's message unchanged: the
// text the command line prints after "intrinsic: error: ".
//
// They are also the built-in exceptions a Python user reaches for:
// UsageError is a ValueError (a bad keyword value is caught by
// `except ValueError`), and a file that could not be opened, read or written
// (the library's Error::os_error, an errno) raises a class that is both
// InputError/OutputError and FileNotFoundError, PermissionError,
// IsADirectoryError, NotADirectoryError or, for any other reason, OSError,
// with `errno` set. Their str() stays the command line's message (OSError's
// own "[Errno 2] ..." form appears only when strerror or filename is set,
// which is why only errno is).
#include <cerrno>
#include <cstring>

#include "common.h"
#include "intrinsic/error.h"

namespace intrinsic::python {
namespace {

PyObject* g_classes[5] = {nullptr, nullptr, nullptr, nullptr, nullptr};  // by exit code

// The file-system reasons with their own built-in class, in the order of
// g_file_classes' columns; the last column is plain OSError (any other errno).
struct FileReason {
  const char* suffix;  // the built-in's name
  PyObject* builtin;
};
constexpr int kReasons = 5;
PyObject* g_file_classes[2][kReasons] = {};  // [0]: InputError, [1]: OutputError

PyObject* new_class(py::module_& m, const char* name, const char* doc, PyObject* bases) {
  const std::string qualified = std::string("intrinsic.") + name;
  PyObject* cls = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases, nullptr);
  if (!cls) throw py::error_already_set();
  m.add_object(name, py::handle(cls));
  return cls;
}

PyObject* new_kind(py::module_& m, const char* name, const char* doc, py::tuple bases, int exit_code) {
  PyObject* cls = new_class(m, name, doc, bases.ptr());
  py::handle(cls).attr("exit_code") = exit_code;
  return cls;
}

int reason_column(int os_error) {
  switch (os_error) {
    case ENOENT: return 0;
    case EACCES:
    case EPERM: return 1;
    case EISDIR: return 2;
    case ENOTDIR: return 3;
    default: return 4;
  }
}

void register_file_classes(py::module_& m) {
  const FileReason reasons[kReasons] = {{"FileNotFoundError", PyExc_FileNotFoundError},
                                        {"PermissionError", PyExc_PermissionError},
                                        {"IsADirectoryError", PyExc_IsADirectoryError},
                                        {"NotADirectoryError", PyExc_NotADirectoryError},
                                        {"OSError", PyExc_OSError}};
  const char* kinds[2] = {"Input", "Output"};
  for (int k = 0; k < 2; ++k) {
    PyObject* kind_class = g_classes[k == 0 ? 2 : 4];
    for (int r = 0; r < kReasons; ++r) {
      const std::string name = std::string(kinds[k]) + reasons[r].suffix;
      const std::string doc = std::string("An ") + kinds[k] + "Error that is also a " + reasons[r].suffix +
                              ": the file could not be " + (k == 0 ? "opened or read" : "written") +
                              " (errno is set; str() is the command line's message).";
      py::tuple bases = py::make_tuple(py::handle(kind_class), py::handle(reasons[r].builtin));
      g_file_classes[k][r] = new_class(m, name.c_str(), doc.c_str(), bases.ptr());
    }
  }
}

// Raises `cls` with `message` (bytes that are not UTF-8, as in a path, are
// replaced rather than turned into a UnicodeDecodeError) and, when given,
// the errno.
void raise(PyObject* cls, const char* message, int os_error) {
  PyObject* text = PyUnicode_DecodeUTF8(message, static_cast<Py_ssize_t>(std::strlen(message)), "replace");
  if (!text) return;  // the decoding error stays set
  PyObject* exc = PyObject_CallOneArg(cls, text);
  Py_DECREF(text);
  if (!exc) return;
  if (os_error != 0) {
    PyObject* code = PyLong_FromLong(os_error);
    const int failed = !code || PyObject_SetAttrString(exc, "errno", code) != 0;
    Py_XDECREF(code);
    if (failed) {
      Py_DECREF(exc);
      return;
    }
  }
  PyErr_SetObject(cls, exc);
  Py_DECREF(exc);
}

PyObject* class_for(const Error& e) {
  const int code = e.exit_code();
  if (e.os_error() != 0 && (code == 2 || code == 4)) {
    return g_file_classes[code == 2 ? 0 : 1][reason_column(e.os_error())];
  }
  return g_classes[code >= 1 && code <= 4 ? code : 0];
}

}  // namespace

void register_errors(py::module_& m) {
  py::handle exception(PyExc_Exception);
  g_classes[0] = new_kind(m, "Error",
                          "Every failure of Intrinsic. `exit_code` is the command line's exit code for it and the "
                          "message is the one the command line prints after 'intrinsic: error: '.",
                          py::make_tuple(exception), 0);
  py::handle error(g_classes[0]);
  g_classes[1] = new_kind(m, "UsageError",
                          "Bad options or arguments (exit code 1). Also a ValueError: a keyword with a value it "
                          "does not take.",
                          py::make_tuple(error, py::handle(PyExc_ValueError)), 1);
  g_classes[2] = new_kind(m, "InputError",
                          "Unreadable or malformed input, or a mesh that is refused: closed, non-manifold, bad "
                          "index, bad constraints (exit code 2). A file that cannot be opened or read raises a "
                          "subclass that is also an OSError: InputFileNotFoundError, InputPermissionError, ...",
                          py::make_tuple(error), 2);
  g_classes[3] = new_kind(m, "NumericalError",
                          "Singular system, non-finite result, residual above max_residual (exit code 3).",
                          py::make_tuple(error), 3);
  g_classes[4] = new_kind(m, "OutputError",
                          "The result could not be written (exit code 4). A file system refusal raises a "
                          "subclass that is also an OSError: OutputFileNotFoundError, OutputPermissionError, ...",
                          py::make_tuple(error), 4);
  register_file_classes(m);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      raise(class_for(e), e.what(), e.os_error());
    }
  });
}

}  // namespace intrinsic::python
