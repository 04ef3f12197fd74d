// The OBJ side of the texture transfer (docs/textures.md): the materials of
// the input's mtllib files whose map_Kd, map_Ks or map_Bump/bump image is
// read through the OBJ's vt are baked into the atlas layout, each over the
// faces that use the material: PNGs beside the output (STEM_<material>_Kd.png),
// a new STEM.mtl that is the old one with those map lines pointing at them,
// and the atlas OBJ's mtllib on it. OBJ vt have v up; the transfer's UVs v
// down. All files or none.
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "intrinsic/atlas_files.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"
#include "intrinsic/texture.h"
#include "texture/obj_textures.h"
#include "texture/texture_internal.h"

namespace intrinsic {
namespace {

namespace fs = std::filesystem;

std::string read_bytes(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw_input_file("cannot open " + what + " '" + path + "': " + std::strerror(errno), errno);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A map line of a .mtl: which material, which map, and where its file name is.
struct MapLine {
  std::size_t line = 0;     // in the concatenated .mtl text's lines
  std::string material, kind;  // kind: Kd, Ks, Bump
  std::string file;         // the last word of the line, as written
  std::string where;        // "lib.mtl:12" for messages
};

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) {
    if (!l.empty() && l.back() == '\r') l.pop_back();
    lines.push_back(l);
  }
  return lines;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The .mtl files of `input` (each mtllib line may name several), their lines
// in one list, the map lines found in them, and each file's folder per map line.
struct Library {
  std::vector<std::string> lines;
  std::vector<MapLine> maps;
  std::vector<std::string> folder;  // per map
};

Library read_libraries(const MeshFile& input) {
  Library lib;
  const fs::path folder = fs::path(input.mesh.path).parent_path();
  for (const std::string& names : input.document.obj.material_libraries) {
    std::istringstream words(names);
    for (std::string name; words >> name;) {
      const fs::path file = folder / name;
      const std::vector<std::string> lines = split_lines(read_bytes(file.string(), "material library"));
      std::string material;
      for (std::size_t i = 0; i < lines.size(); ++i) {
        std::istringstream w(lines[i]);
        std::string key, last, word;
        w >> key;
        while (w >> word) last = word;
        key = lower(key);
        if (key == "newmtl") material = lines[i].substr(lines[i].find("newmtl") + 7);
        const std::string kind = key == "map_kd" ? "Kd" : key == "map_ks" ? "Ks" : key == "map_bump" || key == "bump" ? "Bump" : "";
        if (!kind.empty() && !last.empty() && !material.empty()) {
          lib.maps.push_back({lib.lines.size() + i, material, kind, last, file.string() + ":" + std::to_string(i + 1)});
          lib.folder.push_back(file.parent_path().string());
        }
      }
      lib.lines.insert(lib.lines.end(), lines.begin(), lines.end());
    }
  }
  return lib;
}

std::string file_safe(const std::string& s) {
  std::string out;
  for (const char c : s) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
  return out;
}

// The faces of `material` through both layouts (v down), corners in the
// result's order (a face the atlas reoriented lists its input corners 0, 2, 1).
TransferMesh material_mesh(const MeshFile& input, const AtlasResult& r, const std::string& material) {
  const MeshData& m = input.mesh;
  std::vector<int> faces;
  for (int f = 0; f < r.F.rows(); ++f)
    if (const std::string* name = input.document.obj.materials.of(f); name && *name == material) faces.push_back(f);
  TransferMesh tm;
  tm.old_uv.resize(static_cast<Eigen::Index>(3 * faces.size()), 2);
  tm.new_uv.resize(tm.old_uv.rows(), 2);
  Eigen::Index row = 0;
  for (const int f : faces)
    for (int c = 0; c < 3; ++c, ++row) {
      const int k = c == 0 || r.F(f, c) == m.F(f, c) ? c : 3 - c;
      const int t = m.FTC(f, k), u = r.FUV(f, c);
      tm.old_uv.row(row) << m.TC(t, 0), 1 - m.TC(t, 1);
      tm.new_uv.row(row) << r.UV(u, 0), 1 - r.UV(u, 1);
    }
  return tm;
}

}  // namespace

TextureTransferReport write_obj_with_textures(const std::string& path, const MeshFile& input, const AtlasResult& r,
                                              const TextureTransferOptions& options) {
  TextureTransferReport report;
  Library lib = read_libraries(input);
  const fs::path out(path);
  const std::string stem = out.stem().string(), mtl_name = stem + ".mtl";
  std::vector<std::pair<std::string, std::string>> files;
  for (std::size_t i = 0; i < lib.maps.size(); ++i) {
    MapLine& map = lib.maps[i];
    const TransferMesh tm = material_mesh(input, r, map.material);
    if (tm.old_uv.rows() == 0) {
      report.notes.push_back(map.where + ": material '" + map.material + "' is used by no face: map left as it was");
      continue;
    }
    const std::string source = (fs::path(lib.folder[i]) / map.file).string();
    const std::string where = map.where + " (material '" + map.material + "', map_" + map.kind + ")";
    Texture src;
    try {
      src = decode_texture(read_bytes(source, "texture"), source);
    } catch (const Error& e) {
      throw Error(ErrorKind::Input, where + ": cannot use the image: " + e.what(), e.os_error());
    }
    TransferOptions to;
    to.role = map.kind == "Bump" ? TextureRole::Data : TextureRole::Color;
    to.padding = options.padding, to.supersample = options.supersample;
    to.width = to.height = options.size;
    if (options.size == 0) {
      const double scale = std::sqrt(detail::corner_uv_area(tm.old_uv) / std::max(detail::corner_uv_area(tm.new_uv), 1e-30));
      to.width = static_cast<int>(std::clamp<double>(std::lround(src.width * scale), 16, 16384));
      to.height = static_cast<int>(std::clamp<double>(std::lround(src.height * scale), 16, 16384));
    }
    const TransferResult res = transfer_texture(tm, src, TextureSampler{}, to);
    const std::string png = stem + "_" + file_safe(map.material) + "_" + map.kind + ".png";
    const std::string png_path = (out.parent_path() / png).string();
    files.emplace_back(png_path, encode_texture_png(res.texture));
    std::string& line = lib.lines[map.line];
    line.replace(line.rfind(map.file), map.file.size(), png);
    report.baked.push_back({static_cast<int>(i), map.material, "map_" + map.kind, map.file, png_path,
                            res.texture.width, res.texture.height, res.texels_covered});
    report.files.push_back(png_path);
  }
  std::string text = "# intrinsic atlas --transfer-textures: the input's materials, maps baked for the atlas\n";
  for (const std::string& l : lib.lines) text += l + "\n";
  const std::string mtl_path = (out.parent_path() / mtl_name).string();
  files.emplace_back(mtl_path, text);
  report.files.push_back(mtl_path);
  // All files or none: each is atomic, and a failure removes those before it.
  std::vector<std::string> written;
  try {
    for (const auto& [file, bytes] : files) {
      write_file_atomically(file, bytes);
      written.push_back(file);
    }
    write_atlas_obj_naming(path, input, r, {mtl_name});
  } catch (...) {
    std::error_code ec;
    for (const std::string& f : written) fs::remove(f, ec);
    throw;
  }
  return report;
}

}  // namespace intrinsic
