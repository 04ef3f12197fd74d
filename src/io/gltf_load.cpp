// Loading a glTF 2.0 document (docs/formats.md "glTF"): the GLB container or
// the JSON text, the buffers (GLB binary chunk, base64 data URIs, files
// beside the document) and the buffer views checked against them, so that
// later reads can trust every byte range. Every refusal names the file and
// the JSON path of the object at fault.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "io/gltf_document.h"

namespace intrinsic::gltf {

using nlohmann::json;

const json& array_at(const json& j, const char* key, const std::string& name, const std::string& path) {
  static const json empty = json::array();
  if (!j.is_object()) fail(name, path, "expected an object");
  const auto it = j.find(key);
  if (it == j.end()) return empty;
  if (!it->is_array()) fail(name, path + "/" + key, "expected an array");
  return *it;
}

std::int64_t integer(const json& j, const std::string& name, const std::string& path) {
  if (j.is_number_unsigned()) {
    if (j.get<std::uint64_t>() > static_cast<std::uint64_t>(INT64_MAX)) fail(name, path, "integer too large");
    return static_cast<std::int64_t>(j.get<std::uint64_t>());
  }
  if (j.is_number_integer()) return j.get<std::int64_t>();
  fail(name, path, "expected an integer");
}

int index_at(const json& j, const char* key, std::size_t size, const std::string& name, const std::string& path,
             bool optional) {
  if (!j.is_object()) fail(name, path, "expected an object");
  const auto it = j.find(key);
  const std::string at = path + "/" + key;
  if (it == j.end()) {
    if (optional) return -1;
    fail(name, at, "missing");
  }
  const std::int64_t i = integer(*it, name, at);
  if (i < 0 || static_cast<std::uint64_t>(i) >= size)
    fail(name, at, "index " + std::to_string(i) + " out of range (" + std::to_string(size) + " entries)");
  return static_cast<int>(i);
}

double number(const json& j, const std::string& name, const std::string& path) {
  if (!j.is_number()) fail(name, path, "expected a number");
  return j.get<double>();
}

namespace {

// nlohmann's parser is iterative, but destroying and printing a value
// recurse: a file of a million '[' would exhaust the stack. No glTF document
// nests deeper than a dozen levels.
void check_depth(const std::string& text, const std::string& name) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > 64) throw_input(name + ": JSON nested more than 64 levels deep (byte " + std::to_string(i) + ")");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

json parse_json(const std::string& text, const std::string& name) {
  check_depth(text, name);
  try {
    json j = json::parse(text);
    if (!j.is_object()) throw_input(name + ": the JSON document is not an object");
    return j;
  } catch (const json::exception& e) {
    throw_input(name + ": invalid JSON: " + e.what());
  }
}

std::uint32_t le32(const std::string& b, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;  // glTF is little-endian, as every machine this builds on
}

// The GLB container: 12-byte header, a JSON chunk, an optional BIN chunk.
void split_glb(const std::string& b, const std::string& name, std::string& text, std::string& bin, bool& has_bin) {
  if (b.size() < 20) throw_input(name + ": GLB shorter than its 20-byte header");
  if (le32(b, 4) != 2) throw_input(name + ": GLB version " + std::to_string(le32(b, 4)) + " (only 2 is read)");
  const std::uint64_t total = le32(b, 8);
  if (total > b.size())
    throw_input(name + ": GLB header announces " + std::to_string(total) + " bytes, the file has " +
                std::to_string(b.size()));
  std::uint64_t at = 12;
  int chunk = 0;
  has_bin = false;
  while (at + 8 <= total) {
    const std::uint64_t len = le32(b, at), type = le32(b, at + 4);
    if (at + 8 + len > total)
      throw_input(name + ": GLB chunk " + std::to_string(chunk) + " runs past the end of the file");
    const std::string data = b.substr(at + 8, len);
    if (chunk == 0) {
      if (type != 0x4E4F534Au) throw_input(name + ": the first GLB chunk is not JSON");
      text = data;
      // The spec pads with spaces; some writers pad with zeros.
      while (!text.empty() && text.back() == '\0') text.pop_back();
    } else if (chunk == 1 && type == 0x004E4942u) {
      bin = data;
      has_bin = true;
    }
    at += 8 + len;
    ++chunk;
  }
  if (chunk == 0) throw_input(name + ": GLB without a JSON chunk");
}


std::string read_buffer_file(const std::string& uri, std::uint64_t length, const std::string& name,
                             const std::string& folder, const std::string& path) {
  const std::string file = percent_decode(uri);
  if (file.empty() || file[0] == '/' || file.find(':') != std::string::npos)
    fail(name, path, "buffer uri '" + uri + "' is not a relative file name or a data URI");
  const std::string full = folder.empty() ? file : folder + "/" + file;
  const int fd = ::open(full.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail(name, path, "cannot open buffer file '" + full + "': " + std::strerror(errno));
  std::string bytes(length, '\0');
  std::uint64_t have = 0;
  while (have < length) {
    const ssize_t n = ::read(fd, &bytes[have], length - have);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    have += static_cast<std::uint64_t>(n);
  }
  ::close(fd);
  if (have < length)
    fail(name, path, "buffer file '" + full + "' has " + std::to_string(have) + " bytes, byteLength is " +
                         std::to_string(length));
  return bytes;
}

void load_buffers(GltfDocument& doc, const std::string& bin, bool has_bin, const std::string& folder,
                  bool files_allowed) {
  const std::string& name = doc.name;
  const json& buffers = array_at(doc.json, "buffers", name, "");
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    const std::string path = "/buffers/" + std::to_string(i);
    const json& b = buffers[i];
    if (!b.is_object()) fail(name, path, "expected an object");
    if (!b.contains("byteLength")) fail(name, path + "/byteLength", "missing");
    const std::int64_t length = integer(b["byteLength"], name, path + "/byteLength");
    if (length < 1) fail(name, path + "/byteLength", "must be at least 1");
    const auto uri = b.find("uri");
    std::string data;
    if (uri == b.end()) {
      if (i != 0 || !has_bin) fail(name, path, "no uri and no GLB binary chunk for it");
      data = bin;
    } else if (!uri->is_string()) {
      fail(name, path + "/uri", "expected a string");
    } else {
      const std::string& u = uri->get_ref<const std::string&>();
      if (u.compare(0, 5, "data:") == 0) {
        const std::size_t comma = u.find(";base64,");
        if (comma == std::string::npos) fail(name, path + "/uri", "data URI that is not base64");
        data = base64_decode(u, comma + 8, name, path + "/uri");
      } else if (!files_allowed) {
        fail(name, path + "/uri", "external buffer '" + u + "' cannot be read (the document was given in memory)");
      } else {
        data = read_buffer_file(u, static_cast<std::uint64_t>(length), name, folder, path + "/uri");
      }
    }
    if (data.size() < static_cast<std::uint64_t>(length))
      fail(name, path, "byteLength " + std::to_string(length) + " but the data has " + std::to_string(data.size()) +
                           " bytes");
    data.resize(static_cast<std::size_t>(length));
    doc.buffers.push_back(std::move(data));
  }
}

void check_buffer_views(const GltfDocument& doc) {
  const std::string& name = doc.name;
  const json& views = array_at(doc.json, "bufferViews", name, "");
  for (std::size_t i = 0; i < views.size(); ++i) {
    const std::string path = "/bufferViews/" + std::to_string(i);
    const json& v = views[i];
    const int buffer = index_at(v, "buffer", doc.buffers.size(), name, path);
    const std::int64_t offset = v.contains("byteOffset") ? integer(v["byteOffset"], name, path + "/byteOffset") : 0;
    if (!v.contains("byteLength")) fail(name, path + "/byteLength", "missing");
    const std::int64_t length = integer(v["byteLength"], name, path + "/byteLength");
    const auto size = static_cast<std::int64_t>(doc.buffers[static_cast<std::size_t>(buffer)].size());
    if (offset < 0 || length < 1 || offset > size || length > size - offset)
      fail(name, path, "bytes " + std::to_string(offset) + " + " + std::to_string(length) + " past the end of buffer " +
                           std::to_string(buffer) + " (" + std::to_string(size) + " bytes)");
    if (v.contains("byteStride")) {
      const std::int64_t stride = integer(v["byteStride"], name, path + "/byteStride");
      if (stride < 4 || stride > 252 || stride % 4)
        fail(name, path + "/byteStride", std::to_string(stride) + " is not a multiple of 4 in [4, 252]");
    }
  }
}

// Extensions that change how geometry is stored: without decoding them the
// triangles cannot be read (Draco is decoded: gltf_draco.cpp).
void check_required_extensions(const GltfDocument& doc) {
  const json& required = array_at(doc.json, "extensionsRequired", doc.name, "");
  for (std::size_t i = 0; i < required.size(); ++i) {
    const std::string path = "/extensionsRequired/" + std::to_string(i);
    if (!required[i].is_string()) fail(doc.name, path, "expected a string");
    const std::string& e = required[i].get_ref<const std::string&>();
    if (e == "EXT_meshopt_compression" || e == "KHR_meshopt_compression")
      fail(doc.name, path,
           e + " is not supported: decompress the file first (e.g. gltf-transform or gltfpack without compression)");
  }
}

}  // namespace

std::string percent_decode(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
      out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

GltfDocument load_document(const std::string& bytes, const std::string& name, const std::string& folder,
                           bool files_allowed) {
  GltfDocument doc;
  doc.name = name;
  if (files_allowed) doc.folder = folder.empty() ? "." : folder;
  std::string text, bin;
  bool has_bin = false;
  if (bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0) split_glb(bytes, name, text, bin, has_bin);
  else text = bytes;
  doc.json = parse_json(text, name);
  const auto asset = doc.json.find("asset");
  if (asset == doc.json.end() || !asset->is_object() || !asset->contains("version") ||
      !(*asset)["version"].is_string())
    fail(name, "/asset/version", "missing (not a glTF 2.0 document)");
  const std::string version = (*asset)["version"].get<std::string>();
  if (version.compare(0, 2, "2.") != 0) fail(name, "/asset/version", "'" + version + "' (only glTF 2.x is read)");
  check_required_extensions(doc);
  load_buffers(doc, bin, has_bin, folder, files_allowed);
  check_buffer_views(doc);
  decode_draco(doc);
  return doc;
}

}  // namespace intrinsic::gltf
