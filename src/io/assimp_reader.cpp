// Reading every other asset format through assimp (docs/formats.md "Other
// formats (assimp)"): assimp imports the file and splits its polygons into
// triangles, then its own glTF 2.0 exporter turns the scene into a glTF
// document in memory, which is read like any glTF file. The asset thereby
// keeps, for a .glb or .gltf output, everything glTF can say of it: one
// mesh per source mesh and material, the node tree and its names, every
// instance of a mesh, materials (base colour, metallic/roughness, textures,
// normal maps), normals as authored (split normals stay split), cameras and
// lights; an OBJ output gets the materials, groups, objects and normals
// (gltf_reader.cpp). Image files the source names resolve from its folder
// (gltf_images.cpp). Points and lines stay in the document and are not
// charted. assimp's log stays off: library code never prints, and assimp
// only logs when a program creates its DefaultLogger.
#include "io/assimp_reader.h"

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>


#include <algorithm>
#include <cmath>
#include <vector>

#include "io/gltf_document.h"
#include "io/mesh_builder.h"

namespace intrinsic::io {

namespace {

// Triangulate: polygons become fans of triangles. ValidateDataStructure:
// indices out of range and other inconsistencies a damaged file may give
// are refused by assimp before we read them (it only checks in debug builds
// otherwise).
// LimitBoneWeights: at most four bones per vertex, renormalized, as glTF's
// one JOINTS_0/WEIGHTS_0 pair holds.
constexpr unsigned kSteps = aiProcess_Triangulate | aiProcess_ValidateDataStructure | aiProcess_LimitBoneWeights;

const aiScene* import(Assimp::Importer& importer, const std::string& bytes, const std::string& name,
                      const std::string& ext, bool from_file) {
  if (bytes.empty()) throw_input(name + ": empty file");
  // Skeletons without skin would come back as made-up bone meshes.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  const aiScene* scene = nullptr;
  try {
    scene = from_file ? importer.ReadFile(name, kSteps)
                      : importer.ReadFileFromMemory(bytes.data(), bytes.size(), kSteps, ext.substr(1).c_str());
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw_input(name + ": assimp cannot read it: " + e.what());
  }
  if (!scene) {
    std::string why = importer.GetErrorString();
    if (why.empty()) why = "no scene";
    throw_input(name + ": assimp cannot read it: " + why);
  }
  if (scene->mNumMeshes == 0 || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    throw_input(name + ": no mesh in the scene (" + std::to_string(scene->mNumCameras) + " cameras, " +
                std::to_string(scene->mNumLights) + " lights, " + std::to_string(scene->mNumAnimations) +
                " animations: nothing to chart)");
  return scene;
}

// What glTF does not allow but importers give (and assimp's glTF exporter
// passes on, so the written file would not be valid glTF): three texture
// coordinate components (glTF has two; the third is dropped), vertex colours
// outside [0, 1] or not finite (clamped), bone weights that do not sum to 1
// per vertex (normalized), animation keys that are not finite (a 3DS
// camera's roll: set to zero, or the identity rotation), key times in ticks
// at a rate of 0 (taken as 25 per second).
void make_exportable(aiScene& scene) {
  auto finite = [](float x) { return std::isfinite(x); };
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    aiMesh& mesh = *scene.mMeshes[m];
    for (unsigned k = 0; k < AI_MAX_NUMBER_OF_TEXTURECOORDS; ++k)
      if (mesh.mTextureCoords[k] && mesh.mNumUVComponents[k] > 2) mesh.mNumUVComponents[k] = 2;
    for (unsigned k = 0; k < AI_MAX_NUMBER_OF_COLOR_SETS; ++k)
      for (unsigned v = 0; mesh.mColors[k] && v < mesh.mNumVertices; ++v)
        for (float* c : {&mesh.mColors[k][v].r, &mesh.mColors[k][v].g, &mesh.mColors[k][v].b, &mesh.mColors[k][v].a})
          *c = finite(*c) ? std::clamp(*c, 0.0f, 1.0f) : 0.0f;
    std::vector<float> sum(mesh.mNumVertices, 0.0f);
    for (unsigned b = 0; b < mesh.mNumBones; ++b)
      for (unsigned w = 0; w < mesh.mBones[b]->mNumWeights; ++w) {
        const aiVertexWeight& vw = mesh.mBones[b]->mWeights[w];
        if (vw.mVertexId < sum.size()) sum[vw.mVertexId] += vw.mWeight;
      }
    for (unsigned b = 0; b < mesh.mNumBones; ++b)
      for (unsigned w = 0; w < mesh.mBones[b]->mNumWeights; ++w) {
        aiVertexWeight& vw = mesh.mBones[b]->mWeights[w];
        if (vw.mVertexId < sum.size() && sum[vw.mVertexId] > 0) vw.mWeight /= sum[vw.mVertexId];
      }
  }
  for (unsigned a = 0; a < scene.mNumAnimations; ++a) {
    // Key times are in ticks; the exporter divides by the rate, which some
    // importers leave at 0 (assimp's own convention then is 25 per second).
    aiAnimation& anim = *scene.mAnimations[a];
    if (!(anim.mTicksPerSecond > 0) || !std::isfinite(anim.mTicksPerSecond)) anim.mTicksPerSecond = 25;
    for (unsigned c = 0; c < scene.mAnimations[a]->mNumChannels; ++c) {
      aiNodeAnim& ch = *scene.mAnimations[a]->mChannels[c];
      for (aiVectorKey* keys : {ch.mPositionKeys, ch.mScalingKeys})
        for (unsigned k = 0; keys && k < (keys == ch.mPositionKeys ? ch.mNumPositionKeys : ch.mNumScalingKeys); ++k) {
          aiVector3D& v = keys[k].mValue;
          if (!finite(v.x) || !finite(v.y) || !finite(v.z)) v = keys == ch.mScalingKeys ? aiVector3D(1, 1, 1) : aiVector3D();
        }
      for (unsigned k = 0; k < ch.mNumRotationKeys; ++k) {
        aiQuaternion& q = ch.mRotationKeys[k].mValue;
        if (!finite(q.x) || !finite(q.y) || !finite(q.z) || !finite(q.w)) q = aiQuaternion();
      }
    }
  }
}

std::string folder_of(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

// Faces of the asset that are triangles (the rest are points or lines).
std::int64_t triangle_count(const aiScene& scene) {
  std::int64_t n = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m)
    for (unsigned f = 0; f < scene.mMeshes[m]->mNumFaces; ++f) n += scene.mMeshes[m]->mFaces[f].mNumIndices == 3;
  return n;
}

}  // namespace

MeshFile read_assimp(const std::string& bytes, const std::string& name, const std::string& ext,
                     const ReadOptions& options, bool from_file) {
  Assimp::Importer importer;
  const aiScene& scene = *import(importer, bytes, name, ext, from_file);
  const std::int64_t triangles = triangle_count(scene);
  if (triangles == 0)
    throw_input(name + ": no triangles (" + std::to_string(scene.mNumMeshes) +
                " meshes, none with a face of three or more corners)");
  if (triangles > face_limit(options))
    throw_input(name + ": " + std::to_string(triangles) + " triangles, more than the limit of " +
                std::to_string(face_limit(options)));
  // The importer's scene is ours to change: nothing reads it after the export.
  make_exportable(const_cast<aiScene&>(scene));
  Assimp::Exporter exporter;
  const aiExportDataBlob* blob = exporter.ExportToBlob(&scene, "glb2");
  if (!blob || !blob->data)
    throw_input(name + ": assimp cannot turn it into glTF: " + std::string(exporter.GetErrorString()));
  const std::string glb(static_cast<const char*>(blob->data), blob->size);
  GltfDocument doc = gltf::load_document(glb, name, "", false);
  if (from_file) doc.folder = folder_of(name);
  return read_gltf_document(std::move(doc), options);
}

}  // namespace intrinsic::io
