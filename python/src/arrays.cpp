// numpy <-> Eigen. Inputs: a C-contiguous float64/int32 array is read in
// place (no copy at the binding boundary); anything else is converted once by
// numpy. The library's matrices are column-major (MatrixX3d), so the data is
// then copied once into them. Outputs are new C-contiguous arrays.
#include <cstring>

#include "common.h"
#include "intrinsic/error.h"

namespace intrinsic::python {
namespace {

using RowX3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowX3i = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowX2d = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

void check_shape(const py::array& a, int cols, const char* name) {
  if (a.ndim() != 2 || a.shape(1) != cols)
    throw_usage(std::string(name) + " must be an n x " + std::to_string(cols) + " array (got shape " +
                shape_text(a) + ")");
}

py::array as_array(const py::handle& obj, const char* name) {
  try {
    return py::array::ensure(obj);
  } catch (const py::error_already_set&) {
  }
  throw_usage(std::string(name) + " must be a numeric array");
}

}  // namespace

py::array c_array_double(const py::handle& obj, int cols, const char* name) {
  using Target = py::array_t<double, py::array::c_style | py::array::forcecast>;
  if (Target::check_(obj)) {  // already float64 and C-contiguous: the same object
    py::array a = py::reinterpret_borrow<py::array>(obj);
    check_shape(a, cols, name);
    return a;
  }
  py::array a = as_array(obj, name);
  if (a.dtype().kind() != 'f' && a.dtype().kind() != 'i' && a.dtype().kind() != 'u')
    throw_usage(std::string(name) + " must be a numeric array");
  check_shape(a, cols, name);
  return Target::ensure(a);
}

py::array c_array_int32(const py::handle& obj, int cols, const char* name) {
  using Target = py::array_t<std::int32_t, py::array::c_style | py::array::forcecast>;
  if (Target::check_(obj)) {
    py::array a = py::reinterpret_borrow<py::array>(obj);
    check_shape(a, cols, name);
    return a;
  }
  py::array a = as_array(obj, name);
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u') throw_usage(std::string(name) + " must be an integer array");
  check_shape(a, cols, name);
  // Indices outside int32 would wrap in the cast: refuse them as the readers do.
  auto wide = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
  const std::int64_t* p = wide.data();
  for (py::ssize_t i = 0; i < wide.size(); ++i)
    if (p[i] < INT32_MIN || p[i] > INT32_MAX)
      throw_input(std::string(name) + ": face " + std::to_string(i / cols) + " has vertex index " +
                  std::to_string(p[i]) + " out of range");
  return Target::ensure(a);
}

MatrixX3d to_V(const py::handle& obj) {
  py::array a = c_array_double(obj, 3, "V");
  return Eigen::Map<const RowX3d>(static_cast<const double*>(a.data()), a.shape(0), 3);
}

MatrixX3i to_F(const py::handle& obj) {
  py::array a = c_array_int32(obj, 3, "F");
  return Eigen::Map<const RowX3i>(static_cast<const int*>(a.data()), a.shape(0), 3);
}

MatrixX2d to_UV(const py::handle& obj, const char* name) {
  py::array a = c_array_double(obj, 2, name);
  return Eigen::Map<const RowX2d>(static_cast<const double*>(a.data()), a.shape(0), 2);
}

py::array from_V(const MatrixX3d& V) {
  py::array_t<double> out({V.rows(), Eigen::Index(3)});
  Eigen::Map<RowX3d>(out.mutable_data(), V.rows(), 3) = V;
  return out;
}

py::array from_F(const MatrixX3i& F) {
  py::array_t<std::int32_t> out({F.rows(), Eigen::Index(3)});
  Eigen::Map<RowX3i>(out.mutable_data(), F.rows(), 3) = F;
  return out;
}

py::array from_UV(const MatrixX2d& UV) {
  py::array_t<double> out({UV.rows(), Eigen::Index(2)});
  Eigen::Map<RowX2d>(out.mutable_data(), UV.rows(), 2) = UV;
  return out;
}

std::string to_path(const py::handle& obj) {
  return py::str(py::module_::import("os").attr("fspath")(obj)).cast<std::string>();
}

std::vector<FixedVertex> to_fixed(const py::handle& obj, const char* name) {
  std::vector<FixedVertex> out;
  for (const py::handle item : py::iter(obj)) {
    const py::sequence t = py::reinterpret_borrow<py::sequence>(item);
    if (!py::isinstance<py::sequence>(item) || t.size() != 3)
      throw_usage(std::string(name) + ": expected (vertex, u, v) triples");
    out.push_back({t[0].cast<int>(), Eigen::Vector2d(t[1].cast<double>(), t[2].cast<double>())});
  }
  return out;
}

py::list from_fixed(const std::vector<FixedVertex>& fixed) {
  py::list out;
  for (const FixedVertex& f : fixed) out.append(py::make_tuple(f.vertex, f.uv.x(), f.uv.y()));
  return out;
}

py::object to_python(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

}  // namespace intrinsic::python
