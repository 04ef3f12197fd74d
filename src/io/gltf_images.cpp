// Images of a written glTF document made to travel with it (docs/formats.md
// "Images travel with the output"): a .glb carries every image in its binary
// chunk, a .gltf has its images beside it (copied there when the input's
// folder is not the output's), so no output names a file that only resolves
// from where the input was. An image's file is looked for where its URI
// points from the input's folder, then by the tails of its path from that
// folder and the one above: an exporter on another machine often writes its
// own absolute path ("D:\models\OBJ\tex.jpg") or a relative one with
// backslashes, and the file travels with the asset.
// Images in a format glTF does not carry (TGA, BMP, ...; assimp's sources
// name them) are converted to PNG with stb_image.
#include <filesystem>
#include <set>

#include "io/gltf_document.h"
#include "io/gltf_images.h"
#include "io/text_file.h"

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_STDIO
#define STBI_ONLY_TGA
#define STBI_ONLY_BMP
#define STBI_ONLY_PSD
#define STBI_ONLY_GIF
#define STBI_ONLY_HDR
#define STBI_ONLY_PNM
#include <stb/stb_image.h>
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

namespace intrinsic::gltf {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// `p`, or the file in its folder whose name differs only in case (assets
// made on Windows name "TEST.PNG" for test.png); "" when neither exists.
fs::path existing(const fs::path& p) {
  if (is_file(p)) return p;
  std::error_code ec;
  const std::string want = lower(p.filename().string());
  for (fs::directory_iterator it(p.parent_path(), ec), end; !ec && it != end; it.increment(ec))
    if (lower(it->path().filename().string()) == want && is_file(it->path())) return it->path();
  return {};
}


// The MIME type glTF carries, from the bytes: core's PNG and JPEG, and the
// WebP and KTX2 images of EXT_texture_webp and KHR_texture_basisu (a document
// naming those declares the extension already); "" for any other format.
std::string mime_of(const std::string& b) {
  if (b.size() >= 8 && b.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0) return "image/png";
  if (b.size() >= 3 && b.compare(0, 3, "\xFF\xD8\xFF") == 0) return "image/jpeg";
  if (b.size() >= 12 && b.compare(0, 4, "RIFF") == 0 && b.compare(8, 4, "WEBP") == 0) return "image/webp";
  if (b.size() >= 12 && b.compare(0, 12, "\xABKTX 20\xBB\r\n\x1A\n") == 0) return "image/ktx2";
  return "";
}

// Any image stb_image decodes, as PNG bytes; "" when it cannot.
std::string to_png(const std::string& b) {
  int w = 0, h = 0, n = 0;
  stbi_uc* pixels = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(b.data()), static_cast<int>(b.size()), &w,
                                          &h, &n, 0);
  if (!pixels) return "";
  std::string out;
  stbi_write_png_to_func([](void* ctx, void* data, int size) { static_cast<std::string*>(ctx)->append(static_cast<char*>(data), static_cast<std::size_t>(size)); },
                         &out, w, h, n, pixels, w * n);
  stbi_image_free(pixels);
  return out;
}

std::string file_name_of(const std::string& uri) {
  const std::size_t cut = uri.find_last_of("/\\");
  return cut == std::string::npos ? uri : uri.substr(cut + 1);
}

// A name beside the output not yet taken by another image of this write.
std::string free_name(const std::string& wanted, std::set<std::string>& taken) {
  std::string name = wanted.empty() ? "image" : wanted;
  const fs::path p(name);
  for (int k = 2; !taken.insert(name).second; ++k)
    name = p.stem().string() + "_" + std::to_string(k) + p.extension().string();
  return name;
}

struct Placer {
  const GltfDocument& doc;
  json& j;
  std::string& bin;
  const fs::path out_folder;
  bool glb;
  PortableImages result;
  std::set<std::string> taken;

  void embed(json& img, const std::string& bytes) {
    while (bin.size() % 4) bin.push_back('\0');
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}});
    bin += bytes;
    img.erase("uri");
    img["bufferView"] = j["bufferViews"].size() - 1;
    img["mimeType"] = mime_of(bytes);
  }

  // The image file at `found` placed for the output.
  void place(json& img, const std::string& path, const fs::path& found) {
    std::string bytes = detail::read_text_file(found.string(), "image");
    const bool convert = mime_of(bytes).empty();
    if (convert) {
      bytes = to_png(bytes);
      if (bytes.empty()) throw_input(doc.name + ": " + path + ": image '" + found.string() + "' is neither PNG nor JPEG and cannot be converted");
      result.converted.push_back(found.string());
    }
    if (glb) return embed(img, bytes);
    std::error_code ec;
    const bool same_place = !convert && fs::equivalent(out_folder / percent_decode(img["uri"].get<std::string>()), found, ec);
    if (same_place) return;  // the URI already resolves from the output's folder
    std::string name = file_name_of(found.string());
    if (convert) name = fs::path(name).replace_extension(".png").string();
    name = free_name(name, taken);
    result.beside.emplace_back((out_folder / name).string(), std::move(bytes));
    img["uri"] = uri_escape(name);
    img.erase("mimeType");
  }

  // An image in a buffer view that is neither PNG nor JPEG (an FBX's
  // embedded TGA, which assimp's exporter passes on) becomes a PNG in a new view.
  void convert_embedded(json& img, const std::string& path) {
    const json& views = j["bufferViews"];
    if (!img["bufferView"].is_number_integer()) return;
    const auto v = img["bufferView"].get<std::size_t>();
    if (v >= views.size()) return;
    const auto offset = views[v].value("byteOffset", std::size_t{0}), length = views[v].value("byteLength", std::size_t{0});
    if (offset + length > bin.size()) return;
    const std::string bytes = bin.substr(offset, length);
    if (!mime_of(bytes).empty()) return;
    const std::string png = to_png(bytes);
    if (png.empty()) throw_input(doc.name + ": " + path + ": embedded image is neither PNG nor JPEG and cannot be converted");
    result.converted.push_back(path);
    embed(img, png);
  }

  void run(bool allow_missing) {
    if (!j.contains("images") || !j["images"].is_array()) return;
    for (std::size_t i = 0; i < j["images"].size(); ++i) {
      json& img = j["images"][i];
      const std::string path = "/images/" + std::to_string(i);
      if (img.is_object() && img.contains("bufferView")) {
        convert_embedded(img, path);
        continue;
      }
      if (!img.is_object() || !img.contains("uri") || !img["uri"].is_string()) continue;
      const std::string uri = img["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0) continue;
      const fs::path found = image_file(doc, uri);
      if (!found.empty()) {
        place(img, path, found);
        continue;
      }
      if (!allow_missing)
        throw_input(doc.name + ": " + path + ": image '" + uri + "' not found (looked from '" + doc.folder +
                    "' and the folder above; --allow-missing-images writes the output without it)");
      result.missing.push_back(uri);
    }
  }
};

}  // namespace

std::string uri_escape(const std::string& name) {
  static const char* kHex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : name) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~' || c == '/') out += static_cast<char>(c);
    else out += '%', out += kHex[c >> 4], out += kHex[c & 15];
  }
  return out;
}

std::string image_file(const GltfDocument& doc, const std::string& uri) {
  if (doc.folder.empty()) return "";  // given in memory: no folder to look in
  const std::string file = percent_decode(uri);
  if (file.empty()) return "";
  if (fs::path(file).is_absolute() && is_file(file)) return file;
  // The path's parts, whichever separator the exporter's system used; a
  // drive ("D:") or root leads nowhere here and is dropped.
  std::vector<std::string> parts;
  std::string part;
  for (char c : file + "/") {
    if (c != '/' && c != '\\') part += c;
    else if (!part.empty()) parts.push_back(part), part.clear();
  }
  if (!parts.empty() && parts[0].size() == 2 && parts[0][1] == ':') parts.erase(parts.begin());
  // Longest tail first, from the document's folder, then from the folder
  // above it (a sibling folder of textures, as an export from another
  // machine often names it).
  const fs::path folder(doc.folder);
  for (std::size_t start = 0; start < parts.size(); ++start) {
    fs::path tail;
    for (std::size_t k = start; k < parts.size(); ++k) tail /= parts[k];
    for (const fs::path& base : {folder, folder / ".."})
      if (const fs::path f = existing(base / tail); !f.empty()) return f.lexically_normal().string();
  }
  return "";
}

PortableImages make_images_portable(json& j, std::string& bin, const GltfDocument& doc, const std::string& output,
                                    bool allow_missing) {
  const std::string ext = fs::path(output).extension().string();
  fs::path out_folder = fs::path(output).parent_path();
  if (out_folder.empty()) out_folder = ".";
  Placer p{doc, j, bin, out_folder, ext == ".glb" || ext == ".GLB", {}, {}};
  p.run(allow_missing);
  return std::move(p.result);
}

}  // namespace intrinsic::gltf
