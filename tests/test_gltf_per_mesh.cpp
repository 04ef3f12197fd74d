// AtlasScope::PerMesh (src/atlas/atlas_per_mesh.cpp): each glTF mesh (or OBJ
// object) gets its own atlas filling the unit square; the whole-input atlas
// keeps every chart apart from every other. Overlaps are found here by a
// separating-axis test on every pair of UV triangles of different charts,
// not by the packer's own texel masks.
#include <gtest/gtest.h>

#include <array>
#include <functional>

#include "cli_support.h"
#include "gltf_support.h"
#include "intrinsic/atlas.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/gltf.h"
#include "intrinsic/io.h"
#include "intrinsic/intrinsic.h"

namespace intrinsic {
namespace {

using nlohmann::json;
using namespace gltf_test;

// Two meshes, a disk and a torus, each drawn by its own node.
Doc two_meshes() {
  GenerateOptions g;
  g.rings = 8;
  const MeshData parts[2] = {generate_flat_disk(g), generate_torus(g)};
  Doc d;
  for (const MeshData& m : parts) {
    const std::vector<float> p = positions(m);
    const int pa = d.add(p, 5126, "VEC3", static_cast<int>(m.V.rows()), 34962, min_max(p, json::object()));
    const int ia = d.add(indices(m), 5125, "SCALAR", static_cast<int>(3 * m.F.rows()), 34963);
    d.j["meshes"].push_back({{"primitives", json::array({{{"attributes", {{"POSITION", pa}}}, {"indices", ia}}})}});
  }
  d.j["nodes"] = json::array({{{"mesh", 0}}, {{"mesh", 1}, {"translation", {5, 0, 0}}}});
  d.j["scenes"] = json::array({{{"nodes", {0, 1}}}});
  d.j["scene"] = 0;
  return d;
}

using Tri = std::array<Eigen::Vector2d, 3>;

Tri uv_triangle(const AtlasResult& r, int f) {
  return {r.UV.row(r.FUV(f, 0)).transpose(), r.UV.row(r.FUV(f, 1)).transpose(), r.UV.row(r.FUV(f, 2)).transpose()};
}

// True when the interiors of a and b overlap by more than `eps` along every
// edge normal of both (triangles that only touch are apart).
bool overlap(const Tri& a, const Tri& b, double eps = 1e-9) {
  for (const Tri* t : {&a, &b})
    for (int e = 0; e < 3; ++e) {
      const Eigen::Vector2d d = (*t)[(e + 1) % 3] - (*t)[e];
      const Eigen::Vector2d n(-d.y(), d.x());
      double alo = 1e300, ahi = -1e300, blo = 1e300, bhi = -1e300;
      for (int k = 0; k < 3; ++k) {
        alo = std::min(alo, n.dot(a[k])), ahi = std::max(ahi, n.dot(a[k]));
        blo = std::min(blo, n.dot(b[k])), bhi = std::max(bhi, n.dot(b[k]));
      }
      if (ahi <= blo + eps * n.norm() || bhi <= alo + eps * n.norm()) return false;
    }
  return true;
}

// Pairs of faces of different charts whose UV triangles overlap, among the
// faces `in` says to compare (same(f, g): whether f and g must stay apart).
int overlaps(const AtlasResult& r, const std::function<bool(int, int)>& compared) {
  int n = 0;
  for (int f = 0; f < r.F.rows(); ++f)
    for (int g = f + 1; g < r.F.rows(); ++g)
      if (r.face_chart[f] >= 0 && r.face_chart[g] >= 0 && r.face_chart[f] != r.face_chart[g] && compared(f, g) &&
          overlap(uv_triangle(r, f), uv_triangle(r, g)))
        ++n;
  return n;
}

// The box of the UVs of the faces of mesh `mesh`.
Eigen::AlignedBox2d mesh_box(const AtlasResult& r, const std::vector<int>& face_mesh, int mesh) {
  Eigen::AlignedBox2d box;
  for (int f = 0; f < r.F.rows(); ++f)
    if (face_mesh[static_cast<std::size_t>(f)] == mesh)
      for (int k = 0; k < 3; ++k) box.extend(r.UV.row(r.FUV(f, k)).transpose());
  return box;
}

TEST(GltfPerMesh, EachMeshFillsItsOwnSquare) {
  test::TempDir dir;
  test::write_text(dir / "two.glb", two_meshes().glb());
  const MeshFile file = read_mesh_file(dir / "two.glb");
  const MeshData& data = file.mesh;
  const std::vector<int> face_mesh = gltf_provenance(file).face_mesh;
  AtlasOptions o;
  o.scope = AtlasScope::PerMesh;
  const AtlasResult r = atlas(file, o);
  ASSERT_EQ(r.F.rows(), data.F.rows());
  for (int f = 0; f < r.F.rows(); ++f)  // the input's faces, each in the input's place
    for (int k = 0; k < 3; ++k) EXPECT_NE((data.F.row(f).array() == r.F(f, k)).count(), 0) << f;
  for (int mesh = 0; mesh < 2; ++mesh) {
    const Eigen::AlignedBox2d box = mesh_box(r, face_mesh, mesh);
    EXPECT_GE(box.min().minCoeff(), 0.0) << mesh;
    EXPECT_LE(box.max().maxCoeff(), 1.0) << mesh;
    EXPECT_GT(box.sizes().maxCoeff(), 0.9) << mesh;  // alone in the square, it fills it
  }
  const auto same_mesh = [&](int f, int g) { return face_mesh[f] == face_mesh[g]; };
  EXPECT_EQ(overlaps(r, same_mesh), 0);
  EXPECT_EQ(r.overlapping, 0);
  // The meshes do share the square: each mesh's own atlas, not one.
  EXPECT_GT(overlaps(r, [&](int f, int g) { return !same_mesh(f, g); }), 0);
  const GltfWriteResult w = write_gltf_atlas(dir / "out.glb", file, r);
  EXPECT_TRUE(w.pruned);
  expect_valid(dir / "out.glb", true);
  // The whole-file atlas (the default): no chart overlaps any other, across
  // meshes too.
  const AtlasResult whole = atlas(data);
  EXPECT_EQ(overlaps(whole, [](int, int) { return true; }), 0);
}

// OBJ objects are meshes too; an input with no meshes to tell apart is refused.
TEST(GltfPerMesh, ObjObjectsAndRefusal) {
  GenerateOptions g;
  g.rings = 6;
  const MeshData disk = generate_flat_disk(g);
  std::string obj;
  for (int copy = 0; copy < 2; ++copy)
    for (int v = 0; v < disk.V.rows(); ++v)
      obj += "v " + std::to_string(disk.V(v, 0) + 3 * copy) + " " + std::to_string(disk.V(v, 1)) + " 0\n";
  for (int copy = 0; copy < 2; ++copy) {
    obj += copy ? "o second\n" : "o first\n";
    for (int f = 0; f < disk.F.rows(); ++f)
      obj += "f " + std::to_string(disk.F(f, 0) + 1 + copy * disk.V.rows()) + " " +
             std::to_string(disk.F(f, 1) + 1 + copy * disk.V.rows()) + " " +
             std::to_string(disk.F(f, 2) + 1 + copy * disk.V.rows()) + "\n";
  }
  test::TempDir dir;
  test::write_text(dir / "two.obj", obj);
  const MeshFile file = read_mesh_file(dir / "two.obj");
  const MeshData& data = file.mesh;
  AtlasOptions o;
  o.scope = AtlasScope::PerMesh;
  const AtlasResult r = atlas(file, o);
  std::vector<int> face_mesh(static_cast<std::size_t>(data.F.rows()));
  for (int f = 0; f < data.F.rows(); ++f) face_mesh[static_cast<std::size_t>(f)] = f < disk.F.rows() ? 0 : 1;
  for (int mesh = 0; mesh < 2; ++mesh) EXPECT_GT(mesh_box(r, face_mesh, mesh).sizes().maxCoeff(), 0.9) << mesh;
  EXPECT_EQ(overlaps(r, [&](int f, int h) { return face_mesh[f] == face_mesh[h]; }), 0);
  // An OFF file has no meshes to tell apart.
  std::string off = "OFF\n" + std::to_string(disk.V.rows()) + " " + std::to_string(disk.F.rows()) + " 0\n";
  for (int v = 0; v < disk.V.rows(); ++v) off += std::to_string(disk.V(v, 0)) + " " + std::to_string(disk.V(v, 1)) + " 0\n";
  for (int f = 0; f < disk.F.rows(); ++f)
    off += "3 " + std::to_string(disk.F(f, 0)) + " " + std::to_string(disk.F(f, 1)) + " " + std::to_string(disk.F(f, 2)) + "\n";
  test::write_text(dir / "disk.off", off);
  try {
    atlas(read_mesh_file(dir / "disk.off"), o);
    ADD_FAILURE() << "not refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("no meshes to tell apart"), std::string::npos) << e.what();
  }
  // Nor has the geometry alone: the objects are the file's document.
  try {
    atlas(data, o);
    ADD_FAILURE() << "not refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("no meshes to tell apart"), std::string::npos) << e.what();
  }
  // The command line's --atlas.
  const test::CliResult c = test::run_cli("atlas " + (dir / "two.obj") + " -o " + (dir / "out.obj") + " -q --atlas per-mesh", dir);
  EXPECT_EQ(c.code, 0) << c.err;
  const test::CliResult bad = test::run_cli("atlas " + (dir / "two.obj") + " -o " + (dir / "bad.obj") + " -q --atlas each", dir);
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.err.find("per-mesh"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace intrinsic
