// The formats read through assimp (assimp_reader.cpp): whatever Debian's
// libassimp imports that the project has no reader of its own for (FBX,
// Collada, 3DS, LWO, X, .blend...; docs/formats.md "Other formats (assimp)").
#pragma once

#include <string>
#include <vector>

#include "intrinsic/io.h"

namespace intrinsic::io {

// True when assimp has an importer for the lower-case extension `ext`
// (".fbx").
bool assimp_reads(const std::string& ext);

// Every extension assimp imports, lower case with the dot, sorted, each with
// the name of its importer ("Autodesk FBX Importer").
struct AssimpExtension {
  std::string extension;
  std::string importer;
};
std::vector<AssimpExtension> assimp_extensions();

// One mesh from the whole asset: triangles of every mesh at world scale,
// corners at exactly equal world positions welded, material, node and mesh
// names kept as per-face labels, the glTF document assimp's export made kept
// beside the mesh (MeshDocument). `from_file`: `name` is a path assimp may
// open itself (and the files it names beside it); otherwise only `bytes` are
// read, the format taken from `ext`. Throws Error(Input) naming `name`.
MeshFile read_assimp(const std::string& bytes, const std::string& name, const std::string& ext,
                     const ReadOptions& options, bool from_file);

}  // namespace intrinsic::io
