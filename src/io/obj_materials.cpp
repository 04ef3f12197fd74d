// The material files an atlas OBJ needs beside it (docs/formats.md "OBJ
// materials travel with the output"), so that its `mtllib` and the texture
// maps resolve from the output's folder wherever it is written:
// - an OBJ input's .mtl files, when the output goes to another folder, are
//   copied there with every map they name (a map path inside the input's
//   folder keeps its relative path, any other becomes its file name);
// - a glTF input (and every format read through assimp, which arrives as a
//   glTF document) gets STEM.mtl written from its materials: Kd and d from
//   the base colour, Pm/Pr from metallic/roughness, Ke from the emission,
//   map_Kd, norm and map_Ke from its textures, the images written beside it.
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "io/gltf_document.h"
#include "io/gltf_images.h"
#include "io/obj_materials.h"
#include "io/text_file.h"

namespace intrinsic::io {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

std::string read_file(const fs::path& p) { return detail::read_text_file(p.string(), "file"); }

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

// Where a file named in the input's folder goes in the output's: the same
// relative path when it stays inside the folder, else its file name.
std::string placed_name(const std::string& name) {
  const fs::path p = fs::path(name).lexically_normal();
  if (p.is_relative() && !p.empty() && *p.begin() != "..") return p.generic_string();
  const std::size_t cut = name.find_last_of("/\\");
  return cut == std::string::npos ? name : name.substr(cut + 1);
}

bool is_map(const std::string& key) {
  std::string k;
  for (char c : key) k += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return k.rfind("map_", 0) == 0 || k == "bump" || k == "disp" || k == "decal" || k == "refl" || k == "norm";
}

struct Collector {
  fs::path out_folder;
  bool allow_missing;
  ObjSideFiles out;
  std::set<std::string> written;

  void add(const std::string& name, std::string bytes) {
    if (!written.insert(name).second) return;
    out.files.emplace_back((out_folder / name).string(), std::move(bytes));
    // A map in a sub-folder keeps it (the .mtl's text then stays as it was).
    const fs::path sub = (out_folder / name).parent_path();
    if (sub != out_folder) out.folders.push_back(sub.string());
  }

  // A map statement's file copied beside the output; returns the name to write.
  std::string copy_map(const std::string& file, const fs::path& from, const std::string& where) {
    fs::path found = from / file;
    if (!is_file(found)) found = from / fs::path(placed_name(file)).filename();
    if (!is_file(found)) {
      if (!allow_missing)
        throw_input(where + ": texture '" + file + "' not found (--allow-missing-images writes the output without it)");
      out.missing.push_back(file);
      return file;
    }
    const std::string name = placed_name(file);
    add(name, read_file(found));
    return name;
  }

  // One .mtl of an OBJ input, its map lines pointing at their copies.
  void copy_library(const std::string& name, const fs::path& in_folder) {
    const fs::path file = in_folder / name;
    if (!is_file(file)) {
      if (!allow_missing)
        throw_input("material library '" + file.string() + "' not found (--allow-missing-images writes the output without it)");
      out.missing.push_back(name);
      out.mtllib.push_back(name);
      return;
    }
    std::istringstream lines(read_file(file));
    std::string text;
    int line_no = 0;
    for (std::string line; std::getline(lines, line);) {
      ++line_no;
      std::istringstream words(line);
      std::string key, last, w;
      words >> key;
      while (words >> w) last = w;
      if (is_map(key) && !last.empty()) {
        const std::string to = copy_map(last, file.parent_path(), file.string() + ":" + std::to_string(line_no));
        line.replace(line.rfind(last), last.size(), to);
      }
      text += line + '\n';
    }
    const std::string placed = placed_name(name);
    add(placed, text);
    out.mtllib.push_back(placed);
  }
};

// The bytes of image `i` of the document and, for an embedded image, an
// extension for its file; for an image file, "/" and the file's name.
std::pair<std::string, std::string> image_bytes(const GltfDocument& doc, int i, Collector& c) {
  const json& img = doc.json["images"][static_cast<std::size_t>(i)];
  if (img.contains("bufferView")) {
    const json& view = doc.json["bufferViews"][img["bufferView"].get<std::size_t>()];
    const std::string& buf = doc.buffers.at(view.value("buffer", std::size_t{0}));
    const std::string b = buf.substr(view.value("byteOffset", std::size_t{0}), view["byteLength"].get<std::size_t>());
    return {b, img.value("mimeType", "") == "image/jpeg" ? ".jpg" : ".png"};
  }
  const std::string uri = img.value("uri", "");
  if (uri.rfind("data:", 0) == 0) {
    const std::size_t comma = uri.find(";base64,");
    if (comma == std::string::npos) return {"", ""};
    return {gltf::base64_decode(uri, comma + 8, doc.name, "/images/" + std::to_string(i) + "/uri"),
            uri.find("jpeg") < comma ? ".jpg" : ".png"};
  }
  const std::string file = gltf::image_file(doc, uri);
  if (file.empty()) {
    if (!c.allow_missing)
      throw_input(doc.name + ": /images/" + std::to_string(i) + ": image '" + uri +
                  "' not found (--allow-missing-images writes the output without it)");
    c.out.missing.push_back(uri);
    return {"", ""};
  }
  return {read_file(file), "/" + fs::path(file).filename().string()};
}

std::string safe(const std::string& s) {
  std::string out;
  for (char c : s) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
  return out;
}

// "map_Kd NAME" for the texture a material slot reads, its image written beside.
std::string texture_line(const GltfDocument& doc, const json& slot, const char* key, const std::string& stem,
                         Collector& c) {
  if (!slot.is_object() || !slot.contains("index") || !doc.json.contains("textures")) return "";
  const json& tex = doc.json["textures"][slot["index"].get<std::size_t>()];
  if (!tex.contains("source")) return "";
  const int image = tex["source"].get<int>();
  auto [bytes, ext] = image_bytes(doc, image, c);
  if (bytes.empty()) return "";
  // An image file keeps its name; an embedded one is named after the output.
  const std::string name = ext[0] == '/' ? ext.substr(1) : stem + "_image" + std::to_string(image) + ext;
  c.add(name, std::move(bytes));
  return std::string(key) + " " + name + "\n";
}

std::string material_text(const GltfDocument& doc, const json& m, const std::string& stem, Collector& c) {
  std::ostringstream s;
  s.precision(9);
  const json none = json::object();
  const json& pbr = m.contains("pbrMetallicRoughness") ? m["pbrMetallicRoughness"] : none;
  const json colour = pbr.value("baseColorFactor", json::array({1.0, 1.0, 1.0, 1.0}));
  s << "Kd " << colour[0].get<double>() << ' ' << colour[1].get<double>() << ' ' << colour[2].get<double>() << '\n';
  if (colour[3].get<double>() < 1) s << "d " << colour[3].get<double>() << '\n';
  s << "Pm " << pbr.value("metallicFactor", 1.0) << "\nPr " << pbr.value("roughnessFactor", 1.0) << '\n';
  if (m.contains("emissiveFactor")) {
    const json& e = m["emissiveFactor"];
    s << "Ke " << e[0].get<double>() << ' ' << e[1].get<double>() << ' ' << e[2].get<double>() << '\n';
  }
  s << texture_line(doc, pbr.value("baseColorTexture", json()), "map_Kd", stem, c);
  s << texture_line(doc, m.value("normalTexture", json()), "norm", stem, c);
  s << texture_line(doc, m.value("emissiveTexture", json()), "map_Ke", stem, c);
  return s.str();
}

// STEM.mtl from the document's materials, one `newmtl` per name the faces use.
void write_document_library(const MeshDocument& d, const std::string& stem, Collector& c) {
  const GltfDocument& doc = *d.gltf;
  if (d.obj.materials.empty() || !doc.json.contains("materials")) return;
  const json& mats = doc.json["materials"];
  std::map<std::string, std::size_t> index;  // the reader's label of each material
  for (std::size_t i = 0; i < mats.size(); ++i) {
    std::string name = mats[i].is_object() ? mats[i].value("name", "") : "";
    for (char& ch : name)
      if (ch == '\n' || ch == '\r' || ch == '\0') ch = ' ';
    index.emplace(name.empty() ? "material_" + std::to_string(i) : name, i);
  }
  std::string text = "# materials of " + fs::path(doc.name).filename().string() + "\n";
  for (const std::string& name : d.obj.materials.names) {
    const auto it = index.find(name);
    if (it == index.end()) continue;
    text += "\nnewmtl " + name + "\n" + material_text(doc, mats[it->second], stem, c);
  }
  c.add(stem + ".mtl", text);
  c.out.mtllib.push_back(stem + ".mtl");
}

}  // namespace

ObjSideFiles obj_side_files(const MeshFile& input, const std::string& obj_path, bool allow_missing) {
  fs::path out_folder = fs::path(obj_path).parent_path();
  if (out_folder.empty()) out_folder = ".";
  Collector c{out_folder, allow_missing, {}, {}};
  std::string stem = fs::path(obj_path).filename().string();
  if (stem.size() > 3 && stem.compare(stem.size() - 3, 3, ".gz") == 0) stem.resize(stem.size() - 3);
  stem = fs::path(stem).stem().string();
  if (input.document.gltf) {
    write_document_library(input.document, safe(stem), c);
    return std::move(c.out);
  }
  const std::vector<std::string>& libraries = input.document.obj.material_libraries;
  fs::path in_folder = fs::path(input.mesh.path).parent_path();
  if (in_folder.empty()) in_folder = ".";
  std::error_code ec;
  if (libraries.empty() || fs::equivalent(in_folder, out_folder, ec)) {
    c.out.mtllib = libraries;  // they resolve from the output as they did from the input
    return std::move(c.out);
  }
  for (const std::string& line : libraries) {
    std::istringstream names(line);
    for (std::string name; names >> name;) c.copy_library(name, in_folder);
  }
  return std::move(c.out);
}

}  // namespace intrinsic::io
