// read_mesh and write_mesh: the library's readers and atomic writers.
#include "common.h"
#include "intrinsic/io.h"

namespace intrinsic::python {

void register_io(py::module_& m) {
  m.def(
      "read_mesh",
      [](const py::object& path, std::int64_t max_vertices) {
        ReadOptions ro;
        ro.max_vertices = max_vertices;
        ro.max_faces = faces_for_vertices(max_vertices);
        const std::string p = to_path(path);
        MeshData data;
        {
          py::gil_scoped_release release;
          data = read_mesh(p, ro);
        }
        return py::make_tuple(from_V(data.V), from_F(data.F));
      },
      py::arg("path"), py::arg("max_vertices") = ReadOptions().max_vertices,
      "read_mesh(path, max_vertices=50000000) -> (V, F)\n\n"
      "Reads an OBJ, OFF or PLY file (optionally gzip-compressed) as the command line does: polygons are\n"
      "fan-triangulated; no validation yet (parameterize validates). Returns V (n x 3 float64) and F (m x 3\n"
      "int32, zero-based), new C-contiguous arrays. Raises InputError naming file and line on malformed input.");
  m.def(
      "write_mesh",
      [](const py::object& path, const py::object& V, const py::object& F, const py::object& uv, bool binary) {
        const std::string p = to_path(path);
        const MatrixX3d v = to_V(V);
        const MatrixX3i f = to_F(F);
        const MatrixX2d t = uv.is_none() ? MatrixX2d() : to_UV(uv);
        WriteOptions wo;
        wo.binary = binary;
        py::gil_scoped_release release;
        write_mesh(p, v, f, t, wo);
      },
      py::arg("path"), py::arg("V"), py::arg("F"), py::arg("uv") = py::none(), py::arg("binary") = false,
      "write_mesh(path, V, F, uv=None, binary=False)\n\n"
      "Writes .obj or .ply (binary PLY with binary=True), with one UV per vertex when uv (n x 2) is given,\n"
      "exactly as `intrinsic param -o` writes (shortest round-trip numbers). The file is written to a\n"
      "temporary file and renamed into place. Raises OutputError when it cannot be written.");
  m.def(
      "_view_address",
      [](const py::object& a, int cols, bool integer) {
        const py::array v = integer ? c_array_int32(a, cols, "array") : c_array_double(a, cols, "array");
        return reinterpret_cast<std::uintptr_t>(v.data());
      },
      py::arg("array"), py::arg("cols"), py::arg("integer") = false,
      "Testing aid: the address of the data the binding reads for an input array (equal to\n"
      "array.ctypes.data when no conversion copy is made).");
}

}  // namespace intrinsic::python
