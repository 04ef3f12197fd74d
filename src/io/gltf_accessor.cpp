// glTF accessors (glTF 2.0 spec §3.6): typed views into buffer views, with
// optional byteStride and sparse substitutions. read_accessor checks every
// byte range against its buffer view before copying, and hands back the
// elements tightly packed with the sparse values applied, so the reader and
// writer never see strides or sparse storage. Also base64 for data URIs.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "io/gltf_document.h"

namespace intrinsic::gltf {

using nlohmann::json;

namespace {

int component_size(int component) {
  switch (component) {
    case 5120: case 5121: return 1;  // BYTE, UNSIGNED_BYTE
    case 5122: case 5123: return 2;  // SHORT, UNSIGNED_SHORT
    case 5125: case 5126: return 4;  // UNSIGNED_INT, FLOAT
    default: return 0;
  }
}

int components_of(const std::string& type) {
  static const std::pair<const char*, int> types[] = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4},
                                                      {"MAT2", 4},   {"MAT3", 9}, {"MAT4", 16}};
  for (const auto& [t, n] : types)
    if (type == t) return n;
  return 0;
}

struct View {
  const std::string* buffer = nullptr;
  std::int64_t offset = 0, length = 0, stride = 0;
};

View view_at(const GltfDocument& doc, int index) {
  const json& v = doc.json["bufferViews"][static_cast<std::size_t>(index)];
  View out;
  out.buffer = &doc.buffers[static_cast<std::size_t>(v["buffer"].get<std::int64_t>())];
  out.offset = v.value("byteOffset", std::int64_t{0});
  out.length = v["byteLength"].get<std::int64_t>();
  out.stride = v.value("byteStride", std::int64_t{0});
  return out;
}

std::int64_t optional_offset(const json& j, const std::string& name, const std::string& path) {
  if (!j.contains("byteOffset")) return 0;
  const std::int64_t o = integer(j["byteOffset"], name, path + "/byteOffset");
  if (o < 0) fail(name, path + "/byteOffset", "negative");
  return o;
}

// Copies `count` elements of `size` bytes, `stride` apart, from the view
// starting at `offset`, after checking the last one ends inside the view.
std::string copy_elements(const View& v, std::int64_t offset, std::int64_t stride, std::int64_t count, int size,
                          const std::string& name, const std::string& path) {
  const std::int64_t step = stride > 0 ? stride : size;
  if (stride > 0 && stride < size) fail(name, path, "byteStride " + std::to_string(stride) + " is shorter than an element");
  if (offset > v.length || v.length - offset < size || (count - 1) > (v.length - offset - size) / step)
    fail(name, path, std::to_string(count) + " elements of " + std::to_string(size) + " bytes from offset " +
                         std::to_string(offset) + " run past the end of their buffer view (" +
                         std::to_string(v.length) + " bytes)");
  std::string out(static_cast<std::size_t>(count * size), '\0');
  const char* src = v.buffer->data() + v.offset + offset;
  for (std::int64_t i = 0; i < count; ++i) std::memcpy(&out[i * size], src + i * step, static_cast<std::size_t>(size));
  return out;
}

void apply_sparse(const GltfDocument& doc, const json& sparse, Accessor& a, const std::string& path) {
  const std::string& name = doc.name;
  const std::size_t nviews = doc.json.contains("bufferViews") ? doc.json["bufferViews"].size() : 0;
  if (!sparse.is_object()) fail(name, path, "expected an object");
  if (!sparse.contains("count")) fail(name, path + "/count", "missing");
  const std::int64_t n = integer(sparse["count"], name, path + "/count");
  if (n < 1 || n > a.count) fail(name, path + "/count", std::to_string(n) + " not in [1, " + std::to_string(a.count) + "]");
  if (!sparse.contains("indices") || !sparse["indices"].is_object()) fail(name, path + "/indices", "missing");
  if (!sparse.contains("values") || !sparse["values"].is_object()) fail(name, path + "/values", "missing");
  const json& ji = sparse["indices"];
  const json& jv = sparse["values"];
  const std::string pi = path + "/indices", pv = path + "/values";
  const int ic = static_cast<int>(integer(ji.value("componentType", json(0)), name, pi + "/componentType"));
  if (ic != 5121 && ic != 5123 && ic != 5125)
    fail(name, pi + "/componentType", std::to_string(ic) + " is not UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  const View iv = view_at(doc, index_at(ji, "bufferView", nviews, name, pi));
  const View vv = view_at(doc, index_at(jv, "bufferView", nviews, name, pv));
  const int isize = component_size(ic);
  const std::string idx = copy_elements(iv, optional_offset(ji, name, pi), 0, n, isize, name, pi);
  const std::string val = copy_elements(vv, optional_offset(jv, name, pv), 0, n, a.element_size(), name, pv);
  std::int64_t previous = -1;
  for (std::int64_t k = 0; k < n; ++k) {
    std::uint32_t i = 0;
    if (isize == 1) i = static_cast<unsigned char>(idx[k]);
    else if (isize == 2) { std::uint16_t s; std::memcpy(&s, &idx[k * 2], 2); i = s; }
    else std::memcpy(&i, &idx[k * 4], 4);
    if (static_cast<std::int64_t>(i) <= previous || static_cast<std::int64_t>(i) >= a.count)
      fail(name, pi, "index " + std::to_string(i) + " at " + std::to_string(k) +
                         (static_cast<std::int64_t>(i) >= a.count ? " out of range (" + std::to_string(a.count) + " elements)"
                                                                  : " not strictly increasing"));
    previous = i;
    std::memcpy(&a.bytes[i * a.element_size()], &val[k * a.element_size()], static_cast<std::size_t>(a.element_size()));
  }
}

}  // namespace

double Accessor::raw(std::int64_t i, int k) const {
  const char* p = bytes.data() + i * element_size() + k * component_size;
  switch (component) {
    case 5120: return static_cast<signed char>(*p);
    case 5121: return static_cast<unsigned char>(*p);
    case 5122: { std::int16_t v; std::memcpy(&v, p, 2); return v; }
    case 5123: { std::uint16_t v; std::memcpy(&v, p, 2); return v; }
    case 5125: { std::uint32_t v; std::memcpy(&v, p, 4); return v; }
    default: { float v; std::memcpy(&v, p, 4); return v; }
  }
}

double Accessor::value(std::int64_t i, int k) const {
  const double r = raw(i, k);
  if (!normalized) return r;
  switch (component) {
    case 5120: return std::max(r / 127.0, -1.0);
    case 5121: return r / 255.0;
    case 5122: return std::max(r / 32767.0, -1.0);
    case 5123: return r / 65535.0;
    case 5125: return r / 4294967295.0;
    default: return r;
  }
}

Accessor read_accessor(const GltfDocument& doc, int index, std::int64_t max_count) {
  const std::string& name = doc.name;
  const std::string path = "/accessors/" + std::to_string(index);
  const json& j = doc.json["accessors"][static_cast<std::size_t>(index)];
  if (!j.is_object()) fail(name, path, "expected an object");
  Accessor a;
  a.component = static_cast<int>(integer(j.value("componentType", json(0)), name, path + "/componentType"));
  a.component_size = component_size(a.component);
  if (a.component_size == 0) fail(name, path + "/componentType", std::to_string(a.component) + " is not a glTF component type");
  if (!j.contains("type") || !j["type"].is_string()) fail(name, path + "/type", "missing");
  a.type = j["type"].get<std::string>();
  a.components = components_of(a.type);
  if (a.components == 0) fail(name, path + "/type", "'" + a.type + "' is not a glTF accessor type");
  if (j.contains("normalized")) {
    if (!j["normalized"].is_boolean()) fail(name, path + "/normalized", "expected true or false");
    a.normalized = j["normalized"].get<bool>();
    if (a.normalized && (a.component == 5126 || a.component == 5125))
      fail(name, path + "/normalized", "only byte and short components can be normalized");
  }
  if (!j.contains("count")) fail(name, path + "/count", "missing");
  a.count = integer(j["count"], name, path + "/count");
  if (a.count < 1) fail(name, path + "/count", "must be at least 1");
  if (a.count > max_count)
    fail(name, path + "/count", std::to_string(a.count) + " elements, more than the limit of " + std::to_string(max_count));
  const std::size_t nviews = doc.json.contains("bufferViews") ? doc.json["bufferViews"].size() : 0;
  const int view = index_at(j, "bufferView", nviews, name, path, true);
  if (view >= 0) {
    const View v = view_at(doc, view);
    const std::int64_t offset = optional_offset(j, name, path);
    if (offset % a.component_size)
      fail(name, path + "/byteOffset", "not a multiple of the component size " + std::to_string(a.component_size));
    a.bytes = copy_elements(v, offset, v.stride, a.count, a.element_size(), name, path);
  } else {
    a.bytes.assign(static_cast<std::size_t>(a.count * a.element_size()), '\0');  // zeros unless sparse says otherwise
  }
  if (j.contains("sparse")) apply_sparse(doc, j["sparse"], a, path + "/sparse");
  return a;
}

std::string base64_encode(const std::string& in) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < in.size(); i += 3) {
    const std::uint32_t b0 = static_cast<unsigned char>(in[i]);
    const std::uint32_t b1 = i + 1 < in.size() ? static_cast<unsigned char>(in[i + 1]) : 0;
    const std::uint32_t b2 = i + 2 < in.size() ? static_cast<unsigned char>(in[i + 2]) : 0;
    const std::uint32_t v = b0 << 16 | b1 << 8 | b2;
    out += t[v >> 18];
    out += t[(v >> 12) & 63];
    out += i + 1 < in.size() ? t[(v >> 6) & 63] : '=';
    out += i + 2 < in.size() ? t[v & 63] : '=';
  }
  return out;
}

std::string base64_decode(const std::string& text, std::size_t begin, const std::string& name,
                          const std::string& path) {
  std::string out;
  out.reserve((text.size() - begin) / 4 * 3);
  std::uint32_t acc = 0;
  int bits = 0;
  for (std::size_t i = begin; i < text.size(); ++i) {
    const char c = text[i];
    int v;
    if (c >= 'A' && c <= 'Z') v = c - 'A';
    else if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
    else if (c >= '0' && c <= '9') v = c - '0' + 52;
    else if (c == '+') v = 62;
    else if (c == '/') v = 63;
    else if (c == '=') break;
    else fail(name, path, "invalid base64 character at " + std::to_string(i));
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += static_cast<char>((acc >> bits) & 0xFF);
    }
  }
  return out;
}

}  // namespace intrinsic::gltf
