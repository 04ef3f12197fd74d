// The table of formats (io.h supported_formats, `intrinsic formats`): the
// project's own readers and writers, then every extension assimp imports,
// asked of the linked assimp itself so the list is what this build reads.
#include <assimp/Importer.hpp>
#include <assimp/importerdesc.h>

#include <algorithm>
#include <cctype>
#include <set>
#include <sstream>

#include "intrinsic/io.h"
#include "io/assimp_reader.h"

namespace intrinsic {

namespace io {

namespace {

// The extensions read by the project's own readers: assimp is not asked
// about them (ours give line numbers and refuse more).
bool ours(const std::string& ext) {
  return ext == ".obj" || ext == ".off" || ext == ".ply" || ext == ".stl" || ext == ".gltf" || ext == ".glb";
}

}  // namespace

bool assimp_reads(const std::string& ext) {
  if (ext.size() < 2 || ext[0] != '.' || ours(ext)) return false;
  return Assimp::Importer().IsExtensionSupported(ext);
}

std::vector<AssimpExtension> assimp_extensions() {
  const Assimp::Importer importer;
  std::vector<AssimpExtension> out;
  std::set<std::string> seen;
  for (std::size_t i = 0; i < importer.GetImporterCount(); ++i) {
    const aiImporterDesc* d = importer.GetImporterInfo(i);
    if (!d || !d->mFileExtensions) continue;
    std::istringstream words(d->mFileExtensions);
    for (std::string w; words >> w;) {
      std::transform(w.begin(), w.end(), w.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      const std::string ext = "." + w;
      if (ours(ext) || !seen.insert(ext).second) continue;
      out.push_back({ext, d->mName ? d->mName : ""});
    }
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.extension < b.extension; });
  return out;
}

}  // namespace io

std::vector<FormatInfo> supported_formats() {
  using R = FormatReader;
  std::vector<FormatInfo> out = {
      {".obj", "Wavefront OBJ", R::Own, true, true, true},
      {".off", "Object File Format", R::Own, true, false, false},
      {".ply", "Stanford PLY (ASCII and binary)", R::Own, true, true, false},
      {".stl", "STL (ASCII and binary)", R::Own, true, false, false},
      {".gltf", "glTF 2.0 (JSON)", R::Own, true, false, true},
      {".glb", "glTF 2.0 (binary)", R::Own, true, true, true},
  };
  for (const io::AssimpExtension& e : io::assimp_extensions())
    out.push_back({e.extension, e.importer, R::Assimp, true, false, false});
  return out;
}

}  // namespace intrinsic
