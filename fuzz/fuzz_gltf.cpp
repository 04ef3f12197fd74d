// Fuzzes glTF reading (.gltf JSON and .glb, detected from the bytes) through
// read_mesh_file_from_memory and, for every document it accepts, writing it back
// with a stand-in atlas (one coordinate per corner) as .glb, so the vertex
// splitting and attribute copying see the same hostile accessors.
#include <cstdlib>
#include <filesystem>

#include "fuzz_support.h"
#include "intrinsic/atlas_files.h"
#include "intrinsic/gltf.h"

namespace {

const std::string& output_path() {
  static const std::string path = [] {
    std::string tmpl = (std::filesystem::temp_directory_path() / "fuzz-gltf-XXXXXX").string();
    return std::string(mkdtemp(tmpl.data())) + "/out.glb";
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace intrinsic;
  return fuzz::expect_only_error([&] {
    const MeshFile file = read_mesh_file_from_memory(std::string(reinterpret_cast<const char*>(data), size),
                                                     "fuzz.gltf", fuzz::small_limits());
    const MeshData& m = file.mesh;
    AtlasResult r;
    r.F = m.F;
    r.FUV.resize(m.F.rows(), 3);
    r.UV.resize(3 * m.F.rows(), 2);
    for (Eigen::Index f = 0; f < m.F.rows(); ++f)
      for (int c = 0; c < 3; ++c) {
        r.FUV(f, c) = static_cast<int>(3 * f + c);
        r.UV.row(3 * f + c) << (f % 7) / 7.0, c / 3.0;
      }
    // The input's size picks the set options, so that choosing and refusing
    // a set (the material walk) is fuzzed too.
    GltfWriteOptions o;
    if (size % 3 == 1) o.texcoord_set = 0;
    if (size % 3 == 2) o.texcoord_set = 1, o.replace_used_set = size % 2 == 0;
    write_gltf_atlas(output_path(), file, r, o);
  });
}
