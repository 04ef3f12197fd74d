// The texel transfer on arrays (include/intrinsic/texture.h): an image moved
// from one UV layout of a surface into another, for hosts that hold their
// own images and UVs (the Blender add-on bakes a material's textures into
// the atlas's layout with it). Files are the atlas's business
// (atlas(..., transfer_textures=True)); here everything is numpy.
#include <cstring>

#include "common.h"
#include "intrinsic/texture.h"

namespace intrinsic::python {
namespace {

// (h, w) or (h, w, c) floats in [0, 1], top row first -> Texture.
Texture to_texture(const py::handle& obj) {
  const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(obj);
  if (!a || (a.ndim() != 2 && a.ndim() != 3))
    throw_usage("image: an (h, w) or (h, w, channels) array of floats in [0, 1]");
  Texture t;
  t.height = static_cast<int>(a.shape(0));
  t.width = static_cast<int>(a.shape(1));
  t.channels = a.ndim() == 3 ? static_cast<int>(a.shape(2)) : 1;
  if (t.channels < 1 || t.channels > 4) throw_usage("image: 1 to 4 channels, got " + std::to_string(t.channels));
  t.texels.assign(a.data(), a.data() + a.size());
  return t;
}

py::array from_texture(const Texture& t) {
  py::array_t<float> out({t.height, t.width, t.channels});
  std::memcpy(out.mutable_data(), t.texels.data(), t.texels.size() * sizeof(float));
  return out;
}

MatrixX3d to_rows3(const py::handle& obj, const char* name) {
  const py::array a = c_array_double(obj, 3, name);
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
      static_cast<const double*>(a.data()), a.shape(0), 3);
}

Eigen::MatrixX4d to_tangents(const py::handle& obj, const char* name) {
  const py::array a = c_array_double(obj, 4, name);
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>>(
      static_cast<const double*>(a.data()), a.shape(0), 4);
}

py::array transfer(const py::handle& old_uv, const py::handle& new_uv, const py::handle& image, int width, int height,
                   const py::handle& role, int padding, const py::handle& wrap_u, const py::handle& wrap_v,
                   int supersample, const py::handle& normals, const py::handle& old_tangents,
                   const py::handle& new_tangents) {
  TransferMesh mesh;
  mesh.old_uv = to_UV(old_uv, "old_uv");
  mesh.new_uv = to_UV(new_uv, "new_uv");
  TransferOptions o;
  o.width = width;
  o.height = height;
  o.role = to_choice<TextureRole>(role, "role");
  o.padding = padding;
  o.supersample = supersample;
  if (o.role == TextureRole::TangentNormal) {
    if (normals.is_none() || old_tangents.is_none() || new_tangents.is_none())
      throw_usage("role='normal' needs normals, old_tangents and new_tangents (one row per corner)");
    mesh.normal = to_rows3(normals, "normals");
    mesh.old_tangent = to_tangents(old_tangents, "old_tangents");
    mesh.new_tangent = to_tangents(new_tangents, "new_tangents");
  }
  TextureSampler s;
  s.wrap_u = to_choice<TextureWrap>(wrap_u, "wrap_u");
  s.wrap_v = to_choice<TextureWrap>(wrap_v, "wrap_v");
  const Texture source = to_texture(image);
  TransferResult r;
  {
    py::gil_scoped_release release;
    r = transfer_texture(mesh, source, s, o);
  }
  return from_texture(r.texture);
}

py::array tangents(const py::handle& P, const py::handle& N, const py::handle& UV) {
  const Eigen::MatrixX4d T = compute_tangents(to_rows3(P, "position"), to_rows3(N, "normal"),
                                              to_UV(UV, "uv"));
  py::array_t<double> out({static_cast<py::ssize_t>(T.rows()), static_cast<py::ssize_t>(4)});
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>>(out.mutable_data(), T.rows(), 4) = T;
  return out;
}

}  // namespace

void register_texture(py::module_& m) {
  m.def("transfer_texture", &transfer, py::arg("old_uv"), py::arg("new_uv"), py::arg("image"), py::kw_only(),
        py::arg("width") = 2048, py::arg("height") = 2048, py::arg("role") = choice_name(TextureRole::Color),
        py::arg("padding") = 4, py::arg("wrap_u") = choice_name(TextureWrap::Repeat),
        py::arg("wrap_v") = choice_name(TextureWrap::Repeat), py::arg("supersample") = 1,
        py::arg("normals") = py::none(), py::arg("old_tangents") = py::none(), py::arg("new_tangents") = py::none(),
        "An image moved from one UV layout of a surface into another: row 3*f+k of old_uv and new_uv\n"
        "(3m x 2) is corner k of face f in each layout, in image convention (u right, v down, (0,0) the\n"
        "top-left corner of the image); image is (h, w) or (h, w, channels) floats in [0, 1], top row\n"
        "first. Every texel of the new width x height image maps back through its triangle to the old\n"
        "UVs and samples the image there (bilinear, wrap_u/wrap_v: 'repeat', 'clamp', 'mirror'); charts\n"
        "are dilated by `padding` texels (-1: the whole image). role: 'color' (sRGB, filtered in linear\n"
        "light), 'data' (as stored) or 'normal' (tangent-space normal map re-expressed in the new frame:\n"
        "needs normals (3m x 3) and old_tangents/new_tangents (3m x 4, glTF TANGENT convention)).\n"
        "Returns (height, width, channels) float32. Raises UsageError for bad arguments.");
  m.def("compute_tangents", &tangents, py::arg("position"), py::arg("normal"), py::arg("uv"),
        "Per-corner tangents (3m x 4: unit xyz, handedness w = +-1) of a triangle soup given per corner\n"
        "(3m rows each), MikkTSpace-style, for transfer_texture(role='normal').");
}

}  // namespace intrinsic::python
