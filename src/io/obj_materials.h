// The material files an atlas OBJ needs beside it (obj_materials.cpp,
// docs/formats.md "OBJ materials travel with the output").
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "intrinsic/mesh_document.h"

namespace intrinsic::io {

struct ObjSideFiles {
  std::vector<std::string> mtllib;                         // the OBJ's mtllib names, in order
  std::vector<std::pair<std::string, std::string>> files;  // (path, bytes) to write beside the OBJ
  std::vector<std::string> missing;                        // files not found (allow_missing)
  std::vector<std::string> folders;                        // sub-folders of the output's that `files` need
};

// For the atlas OBJ at `obj_path` of `input`: nothing to write when the input's
// mtllib names resolve from the output's folder as they are; else copies
// of the .mtl files and their maps (OBJ input) or a .mtl written from a
// glTF document's materials with its images. A file that cannot be found is
// Error(Input) naming it, unless `allow_missing` (then listed in `missing`).
ObjSideFiles obj_side_files(const MeshFile& input, const std::string& obj_path, bool allow_missing);

}  // namespace intrinsic::io
