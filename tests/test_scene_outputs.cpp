// What travels from a scene into the written atlas (docs/formats.md "Images
// travel with the output", "Instances", "Other formats (assimp)"): checked on
// scenes the tests build (a torus drawn by two nodes, its material's image
// in a sub-folder; the same scene exported by assimp as Collada), each output
// read back independently (the bytes of the image, tinygltf's loader,
// assimp's own reading of the source) and by the Khronos validator.
#include <gtest/gtest.h>

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_support.h"
#include "gltf_support.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/generate.h"
#include "intrinsic/gltf.h"
#include "intrinsic/io.h"
#include "intrinsic/pipeline.h"
#include "intrinsic/render.h"
#include "intrinsic/texture_transfer.h"

namespace intrinsic {
namespace {

namespace fs = std::filesystem;
using gltf_test::Doc;
using nlohmann::json;
using test::TempDir;

MeshData torus() {
  GenerateOptions g;
  g.rings = 10;
  return generate_torus(g);
}

std::string checker_png() {
  Image im(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) im.pixel(x, y)[0] = (x + y) % 2 ? 200 : 30;
  return encode_png(im);
}

// in/scene.gltf: the torus drawn by two nodes (one moved by 5 along x), its
// material's base colour texture "tex/checker%20one.png" (a URI with an
// escape, in a sub-folder), the buffer embedded.
std::string write_scene(const TempDir& dir) {
  fs::create_directories(dir.path() / "in" / "tex");
  test::write_text(dir / "in/tex/checker one.png", checker_png());
  const MeshData t = torus();
  Doc d = gltf_test::simple_doc(t);
  d.j["meshes"][0]["primitives"][0]["material"] = 0;
  // A planar TEXCOORD_0 (x, y scaled into [0, 1]) the texture reads.
  std::vector<float> uv;
  const Eigen::RowVector3d lo = t.V.colwise().minCoeff(), hi = t.V.colwise().maxCoeff();
  for (int v = 0; v < t.V.rows(); ++v)
    for (int k = 0; k < 2; ++k) uv.push_back(static_cast<float>((t.V(v, k) - lo[k]) / (hi[k] - lo[k])));
  d.j["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = d.add(uv, 5126, "VEC2", static_cast<int>(t.V.rows()));
  d.j["materials"] = json::array({{{"name", "Checker"},
                                    {"pbrMetallicRoughness",
                                     {{"baseColorFactor", {0.5, 0.25, 1.0, 1.0}}, {"baseColorTexture", {{"index", 0}}}}}}});
  d.j["textures"] = json::array({{{"source", 0}}});
  d.j["images"] = json::array({{{"uri", "tex/checker%20one.png"}}});
  d.j["nodes"] = json::array({{{"mesh", 0}}, {{"mesh", 0}, {"translation", {5.0, 0.0, 0.0}}}});
  d.j["scenes"] = json::array({{{"nodes", {0, 1}}}});
  const std::string path = dir / "in/scene.gltf";
  test::write_text(path, d.gltf());
  return path;
}

json glb_json(const std::string& path) {
  const std::string b = test::slurp(path);
  std::uint32_t len = 0;
  std::memcpy(&len, b.data() + 12, 4);
  return json::parse(b.substr(20, len));
}

AtlasOutcome atlas_of(const std::string& path, InstanceMode instances = InstanceMode::Shared) {
  AtlasRequest req;
  req.read.instances = instances;
  return atlas_file(path, req);
}

TEST(SceneOutputs, GlbWrittenElsewhereCarriesTheImageBytes) {
  TempDir dir;
  const AtlasOutcome o = atlas_of(write_scene(dir));
  fs::create_directories(dir.path() / "out");
  write_atlas_file(dir / "out/scene.glb", o.input, o.result, GltfWriteOptions{});
  const tinygltf::Model m = gltf_test::load(dir / "out/scene.glb");
  ASSERT_EQ(m.images.size(), 1u);
  EXPECT_TRUE(m.images[0].uri.empty());
  EXPECT_EQ(m.images[0].mimeType, "image/png");
  const tinygltf::BufferView& v = m.bufferViews[static_cast<std::size_t>(m.images[0].bufferView)];
  const std::string bytes(reinterpret_cast<const char*>(m.buffers[0].data.data()) + v.byteOffset, v.byteLength);
  EXPECT_EQ(bytes, test::slurp(dir / "in/tex/checker one.png"));
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"in", "out"}));
  gltf_test::expect_valid(dir / "out/scene.glb");
}

TEST(SceneOutputs, GltfWrittenElsewhereHasItsImageBeside) {
  TempDir dir;
  const AtlasOutcome o = atlas_of(write_scene(dir));
  fs::create_directories(dir.path() / "out");
  const GltfWriteResult w = write_atlas_file(dir / "out/scene.gltf", o.input, o.result, GltfWriteOptions{});
  const json j = json::parse(test::slurp(dir / "out/scene.gltf"));
  const std::string uri = j["images"][0]["uri"];
  EXPECT_EQ(uri, "checker%20one.png");
  EXPECT_EQ(test::slurp(dir / "out/checker one.png"), test::slurp(dir / "in/tex/checker one.png"));
  EXPECT_EQ(w.files, (std::vector<std::string>{dir / "out/checker one.png"}));
  gltf_test::expect_valid(dir / "out/scene.gltf");
  // Beside its input, the URI already resolves: kept, nothing copied.
  const GltfWriteResult same = write_atlas_file(dir / "in/again.gltf", o.input, o.result, GltfWriteOptions{});
  EXPECT_TRUE(same.files.empty());
  EXPECT_EQ(json::parse(test::slurp(dir / "in/again.gltf"))["images"][0]["uri"], "tex/checker%20one.png");
}

TEST(SceneOutputs, MissingImageRefusedUnlessAllowed) {
  TempDir dir;
  const std::string in = write_scene(dir);
  fs::remove(dir.path() / "in/tex/checker one.png");
  fs::create_directories(dir.path() / "out");
  const test::CliResult r = test::run_cli("atlas '" + in + "' -o '" + (dir / "out/scene.glb") + "'", dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("/images/0"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("tex/checker%20one.png"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir.path() / "out"));
  const test::CliResult ok = test::run_cli("atlas '" + in + "' -o '" + (dir / "out/scene.glb") +
                                               "' --allow-missing-images --report '" + (dir / "out/r.json") + "'",
                                           dir);
  ASSERT_EQ(ok.code, 0) << ok.err;
  EXPECT_NE(ok.err.find("warning"), std::string::npos);
  EXPECT_EQ(json::parse(test::slurp(dir / "out/r.json"))["missing_images"], json::array({"tex/checker%20one.png"}));
}

// Triangles drawn by the scene: each node's mesh's triangles.
std::size_t drawn_triangles(const tinygltf::Model& m) {
  std::size_t n = 0;
  for (const tinygltf::Node& node : m.nodes)
    if (node.mesh >= 0)
      for (const tinygltf::Primitive& p : m.meshes[static_cast<std::size_t>(node.mesh)].primitives)
        n += m.accessors[static_cast<std::size_t>(p.indices)].count / 3;
  return n;
}

TEST(SceneOutputs, SharedInstancesKeepOneLayoutUniqueOnesGetTheirOwn) {
  TempDir dir;
  const std::string in = write_scene(dir);
  const auto faces = static_cast<std::size_t>(torus().F.rows());
  const AtlasOutcome shared = atlas_of(in);
  EXPECT_EQ(static_cast<std::size_t>(shared.input.mesh.F.rows()), faces);
  EXPECT_EQ(scene_summary(shared.input.document).instances, 2);
  write_atlas_file(dir / "shared.glb", shared.input, shared.result, GltfWriteOptions{});
  const tinygltf::Model s = gltf_test::load(dir / "shared.glb");
  EXPECT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(drawn_triangles(s), 2 * faces);

  const AtlasOutcome unique = atlas_of(in, InstanceMode::Unique);
  ASSERT_EQ(static_cast<std::size_t>(unique.input.mesh.F.rows()), 2 * faces);
  // The copy sits where its node puts it: 5 along x.
  EXPECT_NEAR(unique.input.mesh.V.bottomRows(unique.input.mesh.V.rows() / 2).col(0).mean() -
                  unique.input.mesh.V.topRows(unique.input.mesh.V.rows() / 2).col(0).mean(),
              5.0, 1e-6);
  EXPECT_EQ(unique.result.overlapping, 0);
  for (std::size_t f = 0; f < faces; ++f)  // no chart spans both instances
    EXPECT_NE(unique.result.face_chart[f], unique.result.face_chart[f + faces]);
  write_atlas_file(dir / "unique.glb", unique.input, unique.result, GltfWriteOptions{});
  const tinygltf::Model u = gltf_test::load(dir / "unique.glb");
  ASSERT_EQ(u.meshes.size(), 2u);
  EXPECT_NE(u.nodes[0].mesh, u.nodes[1].mesh);
  EXPECT_EQ(drawn_triangles(u), 2 * faces);
  gltf_test::expect_valid(dir / "unique.glb");
}

// The scene as assimp builds it: the torus mesh drawn by two nodes, a
// material with a diffuse colour and a texture file beside the document.
std::unique_ptr<aiScene> assimp_scene(const MeshData& t) {
  auto scene = std::make_unique<aiScene>();
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial*[1]{new aiMaterial()};
  const aiString name("Painted");
  scene->mMaterials[0]->AddProperty(&name, AI_MATKEY_NAME);
  const aiColor4D colour(0.25f, 0.5f, 0.75f, 1.0f);
  scene->mMaterials[0]->AddProperty(&colour, 1, AI_MATKEY_COLOR_DIFFUSE);
  const aiString tex("checker.png");
  scene->mMaterials[0]->AddProperty(&tex, AI_MATKEY_TEXTURE_DIFFUSE(0));
  scene->mNumMeshes = 1;
  scene->mMeshes = new aiMesh*[1]{new aiMesh()};
  aiMesh& m = *scene->mMeshes[0];
  m.mName = aiString("Ring");
  m.mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  m.mNumVertices = static_cast<unsigned>(t.V.rows());
  m.mVertices = new aiVector3D[m.mNumVertices];
  m.mNormals = new aiVector3D[m.mNumVertices];
  for (unsigned v = 0; v < m.mNumVertices; ++v) {
    m.mVertices[v] = aiVector3D(static_cast<float>(t.V(v, 0)), static_cast<float>(t.V(v, 1)), static_cast<float>(t.V(v, 2)));
    const Eigen::Vector3d n = Eigen::Vector3d(t.V(v, 0), t.V(v, 1), 0.3 * t.V(v, 2)).normalized();
    m.mNormals[v] = aiVector3D(static_cast<float>(n.x()), static_cast<float>(n.y()), static_cast<float>(n.z()));
  }
  m.mNumFaces = static_cast<unsigned>(t.F.rows());
  m.mFaces = new aiFace[m.mNumFaces];
  for (unsigned f = 0; f < m.mNumFaces; ++f) {
    m.mFaces[f].mNumIndices = 3;
    m.mFaces[f].mIndices = new unsigned[3];
    for (int c = 0; c < 3; ++c) m.mFaces[f].mIndices[c] = static_cast<unsigned>(t.F(f, c));
  }
  scene->mRootNode = new aiNode("Root");
  aiNode* kids[2] = {new aiNode("Left"), new aiNode("Right")};
  aiMatrix4x4::Translation(aiVector3D(4, 0, 0), kids[1]->mTransformation);
  for (aiNode* k : kids) {
    k->mNumMeshes = 1;
    k->mMeshes = new unsigned[1]{0};
  }
  scene->mRootNode->addChildren(2, kids);
  return scene;
}

TEST(SceneOutputs, ColladaSceneKeepsInstancesMaterialAndNormals) {
  TempDir dir;
  fs::create_directories(dir.path() / "in");
  test::write_text(dir / "in/checker.png", checker_png());
  const std::unique_ptr<aiScene> scene = assimp_scene(torus());
  Assimp::Exporter exporter;
  const std::string dae = dir / "in/rings.dae";
  ASSERT_EQ(exporter.Export(scene.get(), "collada", dae), aiReturn_SUCCESS) << exporter.GetErrorString();
  // What assimp itself reads from the file: the reference.
  Assimp::Importer importer;
  const aiScene* ref = importer.ReadFile(dae, aiProcess_Triangulate);
  ASSERT_NE(ref, nullptr);
  ASSERT_EQ(ref->mNumMeshes, 1u);
  aiColor4D diffuse;
  ASSERT_EQ(ref->mMaterials[ref->mMeshes[0]->mMaterialIndex]->Get(AI_MATKEY_COLOR_DIFFUSE, diffuse), aiReturn_SUCCESS);

  const AtlasOutcome o = atlas_of(dae);
  EXPECT_EQ(o.result.flipped, 0);
  EXPECT_EQ(o.result.overlapping, 0);
  fs::create_directories(dir.path() / "out");
  write_atlas_file(dir / "out/rings.glb", o.input, o.result, GltfWriteOptions{});
  gltf_test::expect_valid(dir / "out/rings.glb");
  const tinygltf::Model m = gltf_test::load(dir / "out/rings.glb");
  ASSERT_EQ(m.meshes.size(), 1u);
  EXPECT_EQ(drawn_triangles(m), 2 * static_cast<std::size_t>(ref->mMeshes[0]->mNumFaces));
  ASSERT_EQ(m.materials.size(), 1u);
  const std::vector<double>& c = m.materials[0].pbrMetallicRoughness.baseColorFactor;
  EXPECT_NEAR(c[0], diffuse.r, 1e-6);
  EXPECT_NEAR(c[1], diffuse.g, 1e-6);
  EXPECT_NEAR(c[2], diffuse.b, 1e-6);
  ASSERT_EQ(m.images.size(), 1u);
  EXPECT_GE(m.images[0].bufferView, 0);  // embedded
  // Every written vertex: a vertex of assimp's mesh at that position with
  // that normal (to 1e-5).
  const tinygltf::Primitive& p = m.meshes[0].primitives[0];
  const aiMesh& am = *ref->mMeshes[0];
  const int pa = p.attributes.at("POSITION"), na = p.attributes.at("NORMAL");
  const std::size_t n = m.accessors[static_cast<std::size_t>(pa)].count;
  for (std::size_t i = 0; i < n; ++i) {
    float pos[3], nor[3];
    std::memcpy(pos, gltf_test::element(m, pa, i).data(), 12);
    std::memcpy(nor, gltf_test::element(m, na, i).data(), 12);
    bool found = false;
    for (unsigned v = 0; v < am.mNumVertices && !found; ++v)
      found = (am.mVertices[v] - aiVector3D(pos[0], pos[1], pos[2])).Length() < 1e-6f &&
              (am.mNormals[v] - aiVector3D(nor[0], nor[1], nor[2])).Length() < 1e-5f;
    ASSERT_TRUE(found) << "written vertex " << i;
  }
}

TEST(SceneOutputs, ColladaToObjWritesMaterialsNormalsAndTheMap) {
  TempDir dir;
  fs::create_directories(dir.path() / "in");
  fs::create_directories(dir.path() / "out");
  test::write_text(dir / "in/checker.png", checker_png());
  const std::unique_ptr<aiScene> scene = assimp_scene(torus());
  Assimp::Exporter exporter;
  ASSERT_EQ(exporter.Export(scene.get(), "collada", dir / "in/rings.dae"), aiReturn_SUCCESS);
  // The diffuse colour as assimp itself reads the file back: the reference
  // (Collada keeps either a colour or a texture in <diffuse>).
  Assimp::Importer importer;
  const aiScene* ref = importer.ReadFile(dir / "in/rings.dae", aiProcess_Triangulate);
  ASSERT_NE(ref, nullptr);
  aiColor4D d;
  ASSERT_EQ(ref->mMaterials[ref->mMeshes[0]->mMaterialIndex]->Get(AI_MATKEY_COLOR_DIFFUSE, d), aiReturn_SUCCESS);
  const AtlasOutcome o = atlas_of(dir / "in/rings.dae");
  const GltfWriteResult w = write_atlas_file(dir / "out/rings.obj", o.input, o.result, GltfWriteOptions{});
  const MeshFile back = read_mesh_file(dir / "out/rings.obj");
  const ObjExtras& x = back.document.obj;
  ASSERT_EQ(back.mesh.F.rows(), o.input.mesh.F.rows());
  ASSERT_EQ(x.material_libraries, std::vector<std::string>{"rings.mtl"});
  for (int f = 0; f < back.mesh.F.rows(); ++f) ASSERT_EQ(*x.materials.of(f), "Painted");
  EXPECT_TRUE(x.has_normals(back.mesh.F));
  const std::string mtl = test::slurp(dir / "out/rings.mtl");
  std::istringstream kd(mtl.substr(mtl.find("newmtl Painted\nKd ") + 18));
  double r = -1, g = -1, b = -1;
  kd >> r >> g >> b;
  EXPECT_NEAR(r, d.r, 1e-6) << mtl;
  EXPECT_NEAR(g, d.g, 1e-6) << mtl;
  EXPECT_NEAR(b, d.b, 1e-6) << mtl;
  EXPECT_NE(mtl.find("map_Kd checker.png"), std::string::npos) << mtl;
  EXPECT_EQ(test::slurp(dir / "out/checker.png"), test::slurp(dir / "in/checker.png"));
  EXPECT_EQ(w.files.size(), 2u);
}

TEST(SceneOutputs, ObjMaterialLibraryAndMapsFollowTheOutput) {
  TempDir dir;
  fs::create_directories(dir.path() / "in/maps");
  fs::create_directories(dir.path() / "out");
  test::write_text(dir / "in/maps/wood.png", checker_png());
  test::write_text(dir / "in/m.mtl", "newmtl Wood\nKd 1 1 1\nmap_Kd -bm 1 maps/wood.png\n");
  std::string obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl Wood\nf 1 2 3\n";
  test::write_text(dir / "in/tri.obj", obj);
  const AtlasOutcome o = atlas_of(dir / "in/tri.obj");
  write_atlas_file(dir / "out/tri.obj", o.input, o.result, GltfWriteOptions{});
  EXPECT_EQ(test::slurp(dir / "out/m.mtl"), "newmtl Wood\nKd 1 1 1\nmap_Kd -bm 1 maps/wood.png\n");
  EXPECT_EQ(test::slurp(dir / "out/maps/wood.png"), test::slurp(dir / "in/maps/wood.png"));
  fs::remove(dir.path() / "in/maps/wood.png");
  fs::create_directories(dir.path() / "out2");
  const test::CliResult r = test::run_cli("atlas '" + (dir / "in/tri.obj") + "' -o '" + (dir / "out2/tri.obj") + "'", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("maps/wood.png"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir.path() / "out2"));
}

TEST(SceneOutputs, SceneWithoutMeshesSaysWhatItHolds) {
  TempDir dir;
  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode("Root");
  scene->mNumCameras = 1;
  scene->mCameras = new aiCamera*[1]{new aiCamera()};
  scene->mCameras[0]->mName = aiString("Root");
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial*[1]{new aiMaterial()};
  Assimp::Exporter exporter;
  ASSERT_EQ(exporter.Export(scene.get(), "collada", dir / "cam.dae"), aiReturn_SUCCESS);
  const test::CliResult r = test::run_cli("atlas '" + (dir / "cam.dae") + "' -o '" + (dir / "o.glb") + "'", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("no mesh in the scene (1 cameras"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "o.glb"));
}

// After a texture transfer the image it replaced is gone from the output:
// one image (the baked one, embedded), one texture, nothing dangling.
TEST(SceneOutputs, TextureTransferDropsTheReplacedImage) {
  TempDir dir;
  const AtlasOutcome o = atlas_of(write_scene(dir));
  GltfWriteOptions w;
  w.texcoord_set = 0;
  TextureTransferOptions t;
  t.enabled = true;
  t.size = 64;
  fs::create_directories(dir.path() / "out");
  const TextureTransferReport r = write_atlas_with_textures(dir / "out/baked.gltf", o.input, o.result, w, t);
  ASSERT_EQ(r.baked.size(), 1u);
  const json j = json::parse(test::slurp(dir / "out/baked.gltf"));
  ASSERT_EQ(j["images"].size(), 1u);
  EXPECT_TRUE(j["images"][0].contains("bufferView"));
  ASSERT_EQ(j["textures"].size(), 1u);
  EXPECT_EQ(j["textures"][0]["source"], 0);
  EXPECT_EQ(j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"], 0);
  EXPECT_TRUE(r.files.empty());  // nothing copied beside: the old image is not needed
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"in", "out"}));
  gltf_test::expect_valid(dir / "out/baked.gltf", true);
}

// A file whose name says nothing is read by what its bytes show: each format
// written under its own name, then copied under a name without an extension,
// reads back the same.
TEST(SceneOutputs, FormatFromBytesWhenTheNameSaysNothing) {
  TempDir dir;
  const MeshData t = torus();
  for (const char* ext : {".obj", ".off", ".ply", ".stl", ".glb"}) {
    SCOPED_TRACE(ext);
    const std::string named = dir / (std::string("t") + ext);
    if (std::string(ext) == ".glb") {
      write_glb(named, t.V, t.F, MatrixX2d::Zero(t.V.rows(), 2), t.F);
    } else if (std::string(ext) == ".off") {
      std::ostringstream o;
      o << "OFF\n" << t.V.rows() << ' ' << t.F.rows() << " 0\n" << t.V << '\n';
      for (int f = 0; f < t.F.rows(); ++f) o << "3 " << t.F.row(f) << '\n';
      test::write_text(named, o.str());
    } else if (std::string(ext) == ".stl") {
      // Binary STL by hand: 80-byte header, count, 50 bytes per facet.
      std::string b(80, ' ');
      const auto n = static_cast<std::uint32_t>(t.F.rows());
      b.append(reinterpret_cast<const char*>(&n), 4);
      for (int f = 0; f < t.F.rows(); ++f) {
        float v[12] = {0, 0, 0};
        for (int c = 0; c < 3; ++c)
          for (int k = 0; k < 3; ++k) v[3 + 3 * c + k] = static_cast<float>(t.V(t.F(f, c), k));
        b.append(reinterpret_cast<const char*>(v), 48);
        b.append(2, '\0');
      }
      test::write_text(named, b);
    } else {
      write_mesh(named, t.V, t.F, MatrixX2d());
    }
    const MeshData a = read_mesh(named);
    fs::copy_file(named, dir / "unnamed", fs::copy_options::overwrite_existing);
    const MeshData b = read_mesh(dir / "unnamed");
    EXPECT_EQ(a.V, b.V);
    EXPECT_EQ(a.F, b.F);
  }
  test::write_text(dir / "junk", "hello\n");
  try {
    read_mesh(dir / "junk");
    ADD_FAILURE() << "junk was read";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("cannot tell the format of " + (dir / "junk")), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace intrinsic
