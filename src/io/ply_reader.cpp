// PLY reader (ASCII, binary little- and big-endian): vertex positions,
// optional per-vertex u/v, and polygon faces; any other property or element
// is skipped by walking its declared layout.
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <vector>

#include "io/mesh_builder.h"
#include "io/text_scan.h"

namespace intrinsic::io {

namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

bool parse_type(std::string_view w, PlyType& t) {
  static const struct {
    const char* name;
    PlyType type;
  } kTypes[] = {{"char", PlyType::Int8},     {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
                {"uint8", PlyType::UInt8},   {"short", PlyType::Int16},     {"int16", PlyType::Int16},
                {"ushort", PlyType::UInt16}, {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
                {"int32", PlyType::Int32},   {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
                {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64},
                {"float64", PlyType::Float64}};
  for (const auto& k : kTypes) {
    if (w == k.name) {
      t = k.type;
      return true;
    }
  }
  return false;
}

std::size_t type_size(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8: return 1;
    case PlyType::Int16:
    case PlyType::UInt16: return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 1;
}

struct Property {
  std::string name;
  bool is_list = false;
  PlyType type = PlyType::Float32;
  PlyType count_type = PlyType::UInt8;
};

struct Element {
  std::string name;
  std::int64_t count = 0;
  std::vector<Property> props;
  int line = 0;
};

enum class Format { Ascii, BinaryLE, BinaryBE };

// Which element is being read, for messages.
struct Where {
  const std::string* element;
  std::int64_t index;
};

std::string plural(const std::string& element) {
  if (element == "vertex") return "vertices";
  if (element == "face") return "faces";
  return "'" + element + "' elements";
}

// Reads binary values, swapping bytes when the file's endianness is not the
// machine's, and reporting byte offsets on failure.
class BinaryCursor {
 public:
  BinaryCursor(const char* begin, const char* end, const char* file_start, bool swap, const std::string& name)
      : p_(begin), end_(end), start_(file_start), swap_(swap), name_(name) {}

  [[noreturn]] void fail(const Where& w, const std::string& what) const {
    throw_input(name_ + ": " + *w.element + " " + std::to_string(w.index) + " (byte offset " +
                std::to_string(p_ - start_) + "): " + what);
  }
  std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }
  int line() const { return 0; }  // binary faces have no source line

  double value(PlyType t, const Where& w) {
    const std::size_t n = type_size(t);
    if (remaining() < n) fail(w, "file ends inside the element (truncated file)");
    unsigned char b[8];
    std::memcpy(b, p_, n);
    if (swap_) std::reverse(b, b + n);
    p_ += n;
    switch (t) {
      case PlyType::Int8: { std::int8_t v; std::memcpy(&v, b, 1); return v; }
      case PlyType::UInt8: return b[0];
      case PlyType::Int16: { std::int16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::UInt16: { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::Int32: { std::int32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::UInt32: { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::Float32: { float v; std::memcpy(&v, b, 4); return v; }
      case PlyType::Float64: { double v; std::memcpy(&v, b, 8); return v; }
    }
    return 0;
  }
  void skip(PlyType t, std::int64_t n, const Where& w) {
    const std::size_t sz = type_size(t);
    if (n < 0 || static_cast<std::uint64_t>(n) > remaining() / sz)
      fail(w, "file ends inside the element (truncated file)");
    p_ += static_cast<std::size_t>(n) * sz;
  }
  // Whether `n` values of type t can still be read: lets a list's length be
  // checked before anything is allocated for it.
  bool can_hold(PlyType t, std::int64_t n) const {
    return n >= 0 && static_cast<std::uint64_t>(n) <= remaining() / type_size(t);
  }

 private:
  const char* p_;
  const char* end_;
  const char* start_;
  bool swap_;
  const std::string& name_;
};

// Reads whitespace-separated ASCII values; elements need not keep to one line.
class AsciiCursor {
 public:
  explicit AsciiCursor(TextScanner s) : s_(std::move(s)) {}

  [[noreturn]] void fail(const Where& w, const std::string& what) const {
    s_.fail(*w.element + " " + std::to_string(w.index) + ": " + what);
  }
  int line() const { return s_.line(); }
  double value(PlyType, const Where& w) {
    s_.skip_space_and_comments();
    if (s_.at_end()) fail(w, "file ends inside the element (truncated file)");
    double v;
    if (!s_.parse_double(v)) fail(w, "expected a number, found " + quote_token(s_.word()));
    return v;
  }
  void skip(PlyType t, std::int64_t n, const Where& w) {
    for (std::int64_t i = 0; i < n; ++i) value(t, w);
  }
  bool can_hold(PlyType, std::int64_t n) const {
    // Each value takes at least a digit and a separator.
    return n >= 0 && static_cast<std::uint64_t>(n) <= s_.remaining() / 2 + 1;
  }

 private:
  TextScanner s_;
};

template <class Cursor>
std::int64_t integer(double v, const char* what, const Cursor& cur, const Where& w) {
  if (!(v >= -2147483648.0 && v <= 4294967295.0) || v != std::floor(v))
    cur.fail(w, std::string(what) + " is not an integer in range");
  return static_cast<std::int64_t>(v);
}

struct Layout {
  const Element* vertex = nullptr;
  const Element* face = nullptr;
  int xyz[3] = {-1, -1, -1};  // property positions in the vertex element
  int uv[2] = {-1, -1};
  int indices = -1;  // the vertex index list in the face element
  bool strips = false;  // the faces are a 'tristrips' element (-1 ends a strip)
};

// Skips one property of an element that is not read (a list or a scalar).
template <class Cursor>
void skip_property(Cursor& cur, const Property& p, const Where& w) {
  if (!p.is_list) {
    cur.skip(p.type, 1, w);
    return;
  }
  const std::int64_t n = integer(cur.value(p.count_type, w), "list length", cur, w);
  if (!cur.can_hold(p.type, n)) cur.fail(w, "list of " + std::to_string(n) + " values runs past the end of the file");
  cur.skip(p.type, n, w);
}

template <class Cursor>
void read_vertices(Cursor& cur, const Element& e, const Layout& lay, MeshBuilder& b) {
  const bool want_uv = lay.uv[0] >= 0;
  std::vector<int> role(e.props.size(), -1);
  for (int k = 0; k < 3; ++k) role[lay.xyz[k]] = k;
  if (want_uv) role[lay.uv[0]] = 3, role[lay.uv[1]] = 4;
  b.xyz.reserve(static_cast<std::size_t>(e.count) * 3);
  if (want_uv) b.uv.reserve(static_cast<std::size_t>(e.count) * 2);
  Where w{&e.name, 0};
  for (w.index = 0; w.index < e.count; ++w.index) {
    double val[5] = {0, 0, 0, 0, 0};
    for (std::size_t k = 0; k < e.props.size(); ++k) {
      const Property& p = e.props[k];
      if (!p.is_list && role[k] >= 0) val[role[k]] = cur.value(p.type, w);
      else skip_property(cur, p, w);
    }
    for (int k = 0; k < 5; ++k) {
      if (!std::isfinite(val[k])) cur.fail(w, k < 3 ? "non-finite coordinate" : "non-finite texture coordinate");
    }
    b.xyz.insert(b.xyz.end(), val, val + 3);
    if (want_uv) b.uv.insert(b.uv.end(), val + 3, val + 5);
  }
}

// One face's vertex index list, fanned into triangles.
template <class Cursor>
void read_face(Cursor& cur, const Property& p, const Where& w, std::int64_t nv, MeshBuilder& b,
               const ReadOptions& opt, std::vector<int>& poly) {
  const std::int64_t n = integer(cur.value(p.count_type, w), "vertex count", cur, w);
  if (n < 3) cur.fail(w, "face has " + std::to_string(n) + " vertices (at least 3 needed)");
  if (!cur.can_hold(p.type, n)) cur.fail(w, "face of " + std::to_string(n) + " vertices runs past the end of the file");
  poly.clear();
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t idx = integer(cur.value(p.type, w), "vertex index", cur, w);
    if (idx < 0 || idx >= nv)
      cur.fail(w, "face index " + std::to_string(idx) + " out of range (file has " + std::to_string(nv) + " vertices)");
    poly.push_back(static_cast<int>(idx));
  }
  if (b.triangle_count() + n - 2 > face_limit(opt))
    cur.fail(w, "more than " + std::to_string(face_limit(opt)) + " faces (the limit)");
  for (std::size_t i = 1; i + 1 < poly.size(); ++i) {
    b.tri.insert(b.tri.end(), {poly[0], poly[i], poly[i + 1]});
    b.line.push_back(cur.line());
  }
}

// One triangle strip list (the 'tristrips' element of scanners' PLY files):
// -1 ends a strip; triangle i of a strip is (s_i, s_i+1, s_i+2), every second
// one reversed so all keep the strip's orientation. Triangles with a repeated
// vertex only join strips and are dropped.
template <class Cursor>
void read_strip(Cursor& cur, const Property& p, const Where& w, std::int64_t nv, MeshBuilder& b,
                const ReadOptions& opt) {
  const std::int64_t n = integer(cur.value(p.count_type, w), "strip length", cur, w);
  if (!cur.can_hold(p.type, n)) cur.fail(w, "strip of " + std::to_string(n) + " indices runs past the end of the file");
  int a = -1, c = -1;  // the previous two indices of the current strip
  std::int64_t in_strip = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t idx = integer(cur.value(p.type, w), "vertex index", cur, w);
    if (idx == -1) {
      in_strip = 0;
      continue;
    }
    if (idx < 0 || idx >= nv)
      cur.fail(w, "strip index " + std::to_string(idx) + " out of range (file has " + std::to_string(nv) + " vertices)");
    const int v = static_cast<int>(idx);
    if (in_strip >= 2 && a != c && c != v && v != a) {
      if (b.triangle_count() + 1 > face_limit(opt))
        cur.fail(w, "more than " + std::to_string(face_limit(opt)) + " faces (the limit)");
      if (in_strip % 2 == 0) b.tri.insert(b.tri.end(), {a, c, v});
      else b.tri.insert(b.tri.end(), {c, a, v});
      b.line.push_back(cur.line());
    }
    a = c;
    c = v;
    ++in_strip;
  }
}

template <class Cursor>
void read_faces(Cursor& cur, const Element& e, const Layout& lay, MeshBuilder& b, const ReadOptions& opt) {
  b.tri.reserve(static_cast<std::size_t>(e.count) * 3);
  b.line.reserve(static_cast<std::size_t>(e.count));
  std::vector<int> poly;
  Where w{&e.name, 0};
  for (w.index = 0; w.index < e.count; ++w.index) {
    for (std::size_t k = 0; k < e.props.size(); ++k) {
      if (static_cast<int>(k) != lay.indices) skip_property(cur, e.props[k], w);
      else if (lay.strips) read_strip(cur, e.props[k], w, lay.vertex->count, b, opt);
      else read_face(cur, e.props[k], w, lay.vertex->count, b, opt, poly);
    }
  }
}

template <class Cursor>
void read_body(Cursor& cur, const std::vector<Element>& elements, const Layout& lay, MeshBuilder& b,
               const ReadOptions& opt) {
  for (const Element& e : elements) {
    if (e.props.empty()) continue;  // nothing to read, however many there are
    if (&e == lay.vertex) {
      read_vertices(cur, e, lay, b);
    } else if (&e == lay.face) {
      read_faces(cur, e, lay, b, opt);
    } else {
      Where w{&e.name, 0};
      for (w.index = 0; w.index < e.count; ++w.index)
        for (const Property& p : e.props) skip_property(cur, p, w);
    }
  }
}

// What the header declares: the body format and the elements in file order.
struct Header {
  Format format = Format::Ascii;
  bool have_format = false;
  std::vector<Element> elements;
};

// Parses the rest of a "format" line into h.
void read_format_line(TextScanner& s, Header& h) {
  std::string_view f = s.word();
  if (f == "ascii") h.format = Format::Ascii;
  else if (f == "binary_little_endian") h.format = Format::BinaryLE;
  else if (f == "binary_big_endian") h.format = Format::BinaryBE;
  else s.fail("unknown PLY format " + quote_token(f));
  h.have_format = true;
}

// Parses the rest of an "element" line and appends the element.
void read_element_line(TextScanner& s, std::vector<Element>& elements) {
  Element e;
  e.name = std::string(s.word());
  e.line = s.line();
  if (e.name.empty()) s.fail("element without a name");
  if (!s.parse_int64(e.count) || e.count < 0) s.fail("expected the number of '" + e.name + "' elements");
  elements.push_back(std::move(e));
}

// Parses the rest of a "property" line and adds it to the last element.
void read_property_line(TextScanner& s, std::vector<Element>& elements) {
  if (elements.empty()) s.fail("property before any element");
  Property p;
  std::string_view t = s.word();
  if (t == "list") {
    p.is_list = true;
    std::string_view ct = s.word();
    if (!parse_type(ct, p.count_type)) s.fail("unknown PLY type " + quote_token(ct));
    t = s.word();
  }
  if (!parse_type(t, p.type)) s.fail("unknown PLY type " + quote_token(t));
  p.name = std::string(s.word());
  if (p.name.empty()) s.fail("property without a name");
  elements.back().props.push_back(std::move(p));
}

// Reads the header lines after "ply" up to and including "end_header".
// Lines that start with no keyword of the format are skipped, as the common
// readers do: old exporters wrote free text there (Blender 2.47: "Created by
// Blender3D 247 - www.blender3d.com"), and nothing after it depends on such a
// line. ReadOptions has no channel for warnings, so they are skipped
// silently. A malformed 'format', 'element' or 'property' line is still
// refused, since the body cannot be read without it.
Header read_header(TextScanner& s) {
  Header h;
  while (true) {
    if (s.at_end()) s.fail("the header has no 'end_header' line");
    std::string_view kw = s.word();
    if (kw == "end_header") {
      s.next_line();
      break;
    }
    if (kw.empty() || kw == "comment" || kw == "obj_info") {
      s.next_line();
      continue;
    }
    if (kw == "format") read_format_line(s, h);
    else if (kw == "element") read_element_line(s, h.elements);
    else if (kw == "property") read_property_line(s, h.elements);
    s.next_line();
  }
  return h;
}

// Finds the x/y/z properties (required) and the first complete u/v pair
// under any of the usual names (optional) in the vertex element.
void find_vertex_properties(const TextScanner& s, const Element& v, Layout& lay) {
  const char* axis[3] = {"x", "y", "z"};
  const char* uv_names[][2] = {{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
  for (int k = 0; k < static_cast<int>(v.props.size()); ++k) {
    const Property& p = v.props[k];
    if (p.is_list) continue;
    for (int a = 0; a < 3; ++a)
      if (p.name == axis[a]) lay.xyz[a] = k;
  }
  for (int a = 0; a < 3; ++a)
    if (lay.xyz[a] < 0) s.fail_at(v.line, std::string("the vertex element has no '") + axis[a] + "' property");
  for (const auto& pair : uv_names) {
    int found[2] = {-1, -1};
    for (int k = 0; k < static_cast<int>(v.props.size()); ++k) {
      if (v.props[k].is_list) continue;
      if (v.props[k].name == pair[0]) found[0] = k;
      if (v.props[k].name == pair[1]) found[1] = k;
    }
    if (found[0] >= 0 && found[1] >= 0) {
      lay.uv[0] = found[0];
      lay.uv[1] = found[1];
      break;
    }
  }
}

// Locates the vertex and face elements and the properties read from them;
// throws if one is missing, empty or duplicated. Points into `elements`.
Layout find_layout(const TextScanner& s, const std::vector<Element>& elements, const std::string& name) {
  Layout lay;
  for (const Element& e : elements) {
    if (e.name == "vertex") {
      if (lay.vertex) s.fail_at(e.line, "more than one 'vertex' element");
      lay.vertex = &e;
    } else if (e.name == "face" || e.name == "tristrips") {
      if (lay.face) s.fail_at(e.line, "more than one 'face' or 'tristrips' element");
      lay.face = &e;
      lay.strips = e.name == "tristrips";
    }
  }
  if (!lay.vertex || lay.vertex->count == 0) throw_input(name + ": no vertices");
  if (!lay.face || lay.face->count == 0) throw_input(name + ": no faces");
  find_vertex_properties(s, *lay.vertex, lay);
  const Element& f = *lay.face;
  for (int k = 0; k < static_cast<int>(f.props.size()); ++k) {
    if (f.props[k].is_list && (f.props[k].name == "vertex_indices" || f.props[k].name == "vertex_index"))
      lay.indices = k;
  }
  if (lay.indices < 0) s.fail_at(f.line, "the face element has no 'vertex_indices' list");
  return lay;
}

// Refuse counts the remaining bytes cannot hold, before allocating: every
// element needs at least its fixed-size properties and list lengths
// (binary), or a digit and a separator per property (ASCII).
void check_counts_fit(std::uint64_t body, const Header& h, const std::string& name) {
  std::uint64_t needed = 0;
  for (const Element& e : h.elements) {
    std::uint64_t min_size = 0;
    for (const Property& p : e.props) {
      min_size += h.format == Format::Ascii ? 2 : type_size(p.is_list ? p.count_type : p.type);
    }
    if (min_size == 0) continue;
    const std::uint64_t left = body > needed ? body - needed : 0;
    // ASCII: the last value needs no separator.
    const std::uint64_t room = h.format == Format::Ascii ? left + 1 : left;
    if (static_cast<std::uint64_t>(e.count) > room / min_size) {
      throw_input(name + ": header announces " + std::to_string(e.count) + " " + plural(e.name) +
                  ", but the file holds at most " + std::to_string(left) + " bytes of " + e.name + " data");
    }
    needed += static_cast<std::uint64_t>(e.count) * min_size;
  }
}

// Refuses vertex and face counts above the options' limits.
void check_limits(const TextScanner& s, const Layout& lay, const ReadOptions& opt) {
  if (lay.vertex->count > vertex_limit(opt))
    s.fail_at(lay.vertex->line, "header announces " + std::to_string(lay.vertex->count) +
                                    " vertices, more than the limit of " + std::to_string(vertex_limit(opt)));
  if (lay.face->count > face_limit(opt))
    s.fail_at(lay.face->line, "header announces " + std::to_string(lay.face->count) +
                                  " faces, more than the limit of " + std::to_string(face_limit(opt)));
}

// Whether this machine stores integers least significant byte first.
bool host_is_little_endian() {
  const std::uint16_t probe = 1;
  unsigned char first;
  std::memcpy(&first, &probe, 1);
  return first == 1;
}

}  // namespace

MeshData read_ply(const char* data, std::size_t size, const std::string& name, const ReadOptions& opt) {
  TextScanner s(data, data + size, name);
  if (s.word() != "ply" || !s.at_line_end()) s.fail("not a PLY file (the first line must be 'ply')");
  s.next_line();
  const Header h = read_header(s);
  if (!h.have_format) throw_input(name + ": the PLY header has no 'format' line");
  const Layout lay = find_layout(s, h.elements, name);
  check_counts_fit(s.remaining(), h, name);
  check_limits(s, lay, opt);

  MeshBuilder b;
  if (h.format == Format::Ascii) {
    AsciiCursor cur(TextScanner(s.pos(), s.end(), name, s.line()));
    read_body(cur, h.elements, lay, b, opt);
  } else {
    const bool swap = (h.format == Format::BinaryLE) != host_is_little_endian();
    BinaryCursor cur(s.pos(), s.end(), data, swap, name);
    read_body(cur, h.elements, lay, b, opt);
  }
  if (lay.uv[0] >= 0) b.tri_uv = b.tri;  // per-vertex u,v: corners index TC like V
  return b.finish(name);
}

}  // namespace intrinsic::io
