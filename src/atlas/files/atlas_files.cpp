// Writing an atlas (atlas_files.h "Atlases"): the OBJ with one texture
// coordinate per corner and what the input's document carried besides
// (normals, materials, groups, objects, smoothing groups; docs/formats.md
// "OBJ"), its material files beside it (obj_materials.cpp), or the
// .glb/.gltf through write_glb, chosen by the output's extension; a mesh
// read from glTF goes back into its document (gltf.h).
#include <charconv>
#include <filesystem>

#include "intrinsic/atlas.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/error.h"
#include "intrinsic/gltf.h"
#include "intrinsic/io.h"
#include "io/obj_materials.h"

namespace intrinsic {
namespace {

void put(std::string& s, double x) {
  char b[32];
  s.append(b, std::to_chars(b, b + sizeof b, x).ptr);
}

void put(std::string& s, long x) {
  char b[24];
  s.append(b, std::to_chars(b, b + sizeof b, x).ptr);
}

// What the input OBJ carried that the atlas OBJ gives back, checked against
// the result before anything is written (extras built by hand may be
// inconsistent; those read from a file never are).
void check_obj_extras(const std::string& path, const MeshData& m, const ObjExtras& x, const AtlasResult& r) {
  auto fail = [&](const std::string& what) { throw_output("cannot write " + path + ": " + what); };
  const Eigen::Index nf = r.F.rows();
  if (x.FN.rows() > 0) {
    if (x.FN.rows() != nf || m.F.rows() != nf) fail("the normal indices do not cover the faces");
    if (x.FN.minCoeff() < -1 || x.FN.maxCoeff() >= x.N.rows()) fail("a normal index is out of range");
    if (!x.N.allFinite()) fail("the normals are not all finite");
  }
  auto check_names = [&](const std::vector<std::string>& names, const char* what) {
    for (const std::string& n : names)
      if (n.find_first_of("\r\n") != std::string::npos) fail(std::string(what) + " '" + n + "' holds a line break");
  };
  check_names(x.material_libraries, "the material library");
  for (const FaceLabels* l : {&x.materials, &x.groups, &x.objects, &x.smoothing}) {
    if (l->empty()) continue;
    if (static_cast<Eigen::Index>(l->of_face.size()) != nf) fail("a per-face label list does not cover the faces");
    for (int i : l->of_face)
      if (i < -1 || i >= static_cast<int>(l->names.size())) fail("a per-face label is out of range");
    check_names(l->names, "the label");
  }
}

// Emits the state statements whose label changes at face f, in the order
// o, g, usemtl, s. A face without a label after one with a label gets no
// statement: OBJ has no way to say "none" again.
void put_statements(std::string& s, const ObjExtras& x, int f) {
  static constexpr const char* kKeyword[] = {"o", "g", "usemtl", "s"};
  const FaceLabels* labels[] = {&x.objects, &x.groups, &x.materials, &x.smoothing};
  for (int k = 0; k < 4; ++k) {
    const FaceLabels& l = *labels[k];
    if (l.empty()) continue;
    const int cur = l.of_face[static_cast<std::size_t>(f)];
    const int prev = f > 0 ? l.of_face[static_cast<std::size_t>(f) - 1] : -1;
    if (cur < 0 || cur == prev) continue;
    s += kKeyword[k];
    const std::string& name = l.names[static_cast<std::size_t>(cur)];
    if (!name.empty()) s += ' ', s += name;
    s += '\n';
  }
}

// The input's corner of face f that the result's corner c is: the result
// lists reversed faces 0, 2, 1 (ChartOptions::reorient).
int input_corner(const MeshData& m, const AtlasResult& r, int f, int c) {
  if (c == 0 || r.F(f, c) == m.F(f, c)) return c;
  return 3 - c;
}

// The OBJ, streamed in blocks of lines: mtllib lines, v, vt (the atlas), vn
// (the input's), then the faces in input order with the input's state
// statements where they change and `f v/vt/vn` where the corner had a normal.
void write_obj_lines(const std::string& path, const MeshFile& input, const AtlasResult& r,
                     const std::vector<std::string>& mtllib) {
  const MeshData& m = input.mesh;
  const ObjExtras& x = input.document.obj;
  check_obj_extras(path, m, x, r);
  const bool normals = x.FN.rows() > 0;
  write_file_atomically(path, [&](const ByteSink& sink) {
    std::string s = "# intrinsic atlas: " + std::to_string(r.charts.size()) + " charts\n";
    auto flush = [&](bool force) {
      if (force || s.size() > (1 << 20)) sink(s.data(), s.size()), s.clear();
    };
    for (const std::string& lib : mtllib) s += "mtllib " + lib + '\n';
    auto put_rows = [&](const char* keyword, const auto& X) {
      for (Eigen::Index i = 0; i < X.rows(); ++i) {
        s += keyword;
        for (Eigen::Index c = 0; c < X.cols(); ++c) s += ' ', put(s, X(i, c));
        s += '\n';
        flush(false);
      }
    };
    put_rows("v", m.V);
    put_rows("vt", r.UV);
    if (normals) put_rows("vn", x.N);
    for (int f = 0; f < r.F.rows(); ++f) {
      put_statements(s, x, f);
      s += "f";
      for (int c = 0; c < 3; ++c) {
        s += ' ';
        put(s, static_cast<long>(r.F(f, c)) + 1);
        s += '/';
        put(s, static_cast<long>(r.FUV(f, c)) + 1);
        const int n = normals ? x.FN(f, input_corner(m, r, f, c)) : -1;
        if (n >= 0) s += '/', put(s, static_cast<long>(n) + 1);
      }
      s += '\n';
      flush(false);
    }
    flush(true);
  });
}

// The OBJ and the material files it names, all or none.
GltfWriteResult write_obj_with_materials(const std::string& path, const MeshFile& input, const AtlasResult& r,
                                         bool allow_missing) {
  io::ObjSideFiles side = io::obj_side_files(input, path, allow_missing);
  GltfWriteResult out;
  out.missing_images = side.missing;
  for (const auto& [file, bytes] : side.files) out.files.push_back(file);
  for (const std::string& folder : side.folders) {
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec) throw_output_file("cannot create " + folder + ": " + ec.message(), ec.value());
  }
  write_all(side.files);
  try {
    write_obj_lines(path, input, r, side.mtllib);
  } catch (...) {
    std::error_code ec;
    for (const std::string& f : out.files) std::filesystem::remove(f, ec);
    throw;
  }
  return out;
}

}  // namespace

void write_atlas_obj(const std::string& path, const MeshFile& input, const AtlasResult& r) {
  write_obj_with_materials(path, input, r, false);
}

void write_atlas_obj_naming(const std::string& path, const MeshFile& input, const AtlasResult& r,
                            const std::vector<std::string>& mtllib) {
  write_obj_lines(path, input, r, mtllib);
}

void check_atlas_output(const std::string& path) {
  const std::string ext = mesh_extension(path);
  if (ext != ".obj" && ext != ".glb" && ext != ".gltf")
    throw_usage("output '" + path + "': the atlas is written as .obj (one texture coordinate per corner), .glb or .gltf");
  if (ext != ".obj" && path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0)
    throw_usage("output '" + path + "': " + ext + " is written uncompressed (drop the .gz)");
}

void write_atlas_file(const std::string& path, const MeshFile& input, const AtlasResult& r) {
  write_atlas_file(path, input, r, GltfWriteOptions{});
}

GltfWriteResult write_atlas_file(const std::string& path, const MeshFile& input, const AtlasResult& r,
                                 const GltfWriteOptions& gltf_options) {
  check_atlas_output(path);
  const std::string ext = mesh_extension(path);
  // A glTF input is written back as the same document with the atlas added.
  if (ext != ".obj" && input.document.gltf) return write_gltf_atlas(path, input, r, gltf_options);
  if (ext == ".obj") return write_obj_with_materials(path, input, r, gltf_options.allow_missing_images);
  write_glb(path, input.mesh.V, r.F, r.UV, r.FUV);  // the faces as written (reorient)
  return {};
}

}  // namespace intrinsic
