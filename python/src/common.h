// Shared declarations of the Python module intrinsic._intrinsic: array
// conversion (numpy <-> the library's Eigen matrices), the conversion of
// Python keyword options to the library's typed requests (pipeline.h), and
// one register function per binding file.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "intrinsic/boundary.h"
#include "intrinsic/mesh_data.h"
#include "intrinsic/boundary_editor.h"
#include "intrinsic/intrinsic.h"
#include "intrinsic/pictures.h"
#include "intrinsic/option_table.h"
#include "intrinsic/pipeline.h"

namespace intrinsic::python {

namespace py = pybind11;

// A C-contiguous float64 (or int32) array with `cols` columns: the object
// itself when it already is one (no copy), else a converted copy. Throws
// Error(Usage) naming `name` for a wrong shape or a non-numeric type.
py::array c_array_double(const py::handle& obj, int cols, const char* name);
py::array c_array_int32(const py::handle& obj, int cols, const char* name);

// The library stores column-major Eigen matrices: these copy once.
MatrixX3d to_V(const py::handle& obj);
MatrixX3i to_F(const py::handle& obj);
MatrixX2d to_UV(const py::handle& obj, const char* name = "uv");

// New C-contiguous numpy arrays (n x 3 float64, n x 3 int32, n x 2 float64).
py::array from_V(const MatrixX3d& V);
py::array from_F(const MatrixX3i& F);
py::array from_UV(const MatrixX2d& UV);

// A path from str or os.PathLike.
std::string to_path(const py::handle& obj);
// (vertex, u, v) triples -> fixed vertices.
std::vector<FixedVertex> to_fixed(const py::handle& obj, const char* name);
py::list from_fixed(const std::vector<FixedVertex>& fixed);
// A JSON document as Python objects (through the json module: exact numbers).
py::object to_python(const nlohmann::json& j);

// A keyword's value as the option `key` of `table` takes it (a Choice as
// its name or the bound enum value, a Path as str or os.PathLike);
// Error(Usage) for an unknown key or a value of another type.
OptionValue to_option_value(const std::vector<OptionSpec>& table, const std::string& key, const py::handle& value);
// A table as Python data: one dict per option (key, flag, flag_negates,
// aliases, type, group, help, min, max, choices, repeated, value_name,
// default), for the wrapper's
// signature, the batch runner's flags and the add-on's properties.
py::list table_to_python(const std::vector<OptionSpec>& table);

// A choice keyword: a name (the table's parse, `keyword` in the message) or
// the bound enum value (intrinsic.Method.CONFORMAL).
template <class E>
E to_choice(const py::handle& value, const char* keyword) {
  if (py::isinstance<py::str>(value)) return parse_choice<E>(value.cast<std::string>(), keyword);
  try {
    return value.cast<E>();
  } catch (const py::cast_error&) {
    throw_usage(std::string(keyword) + ": expected one of " + choice_list<E>() + ", got " +
                py::str(py::type::of(value).attr("__name__")).cast<std::string>());
  }
}

// The keyword options of parameterize() (the keys of param_option_table(),
// plus verbose) -> the library's request; Error(Usage) naming the keyword.
// `optimizers` false refuses the options of the table's group "Optimizers"
// (Parameterizer).
ParamRequest to_request(const py::dict& options, bool optimizers);

void register_errors(py::module_& m);
void register_texture(py::module_& m);
void register_io(py::module_& m);
void register_param(py::module_& m);
void register_render(py::module_& m);
void register_atlas(py::module_& m);

}  // namespace intrinsic::python
