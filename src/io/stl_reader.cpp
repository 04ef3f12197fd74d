// STL reader (ASCII and binary). STL stores every triangle's three corners
// as coordinates, not indices; corners with equal coordinates are welded into
// one vertex here, so the mesh comes out connected. Faces keep file order.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <unordered_map>
#include <vector>

#include "io/mesh_builder.h"
#include "io/text_scan.h"

namespace intrinsic::io {

namespace {

constexpr std::size_t kBinaryHeader = 84;  // 80-byte header + uint32 facet count
constexpr std::size_t kBinaryFacet = 50;   // normal, 3 corners (float32 x 12), uint16 attribute

// Welds corners: bitwise-equal float32 coordinates give one vertex (-0 counts
// as +0, since both denote the same point). No tolerance: nearby but
// distinct corners stay distinct vertices, as the file says.
class Welder {
 public:
  Welder(MeshBuilder& b, std::int64_t max_vertices) : b_(b), max_(max_vertices) {}
  void reserve(std::size_t facets) {
    map_.reserve(facets / 2 + 3);
    b_.xyz.reserve((facets / 2 + 3) * 3);
  }
  // The vertex index of p, creating the vertex if new; -1 past the limit.
  int vertex(const float p[3]) {
    Key k;
    for (int a = 0; a < 3; ++a) {
      const float x = p[a] == 0.0f ? 0.0f : p[a];
      std::memcpy(&k.bits[a], &x, sizeof x);
    }
    auto it = map_.find(k);
    if (it != map_.end()) return it->second;
    if (b_.vertex_count() >= max_) return -1;
    const int id = static_cast<int>(b_.vertex_count());
    map_.emplace(k, id);
    for (int a = 0; a < 3; ++a) b_.xyz.push_back(p[a]);
    return id;
  }

 private:
  struct Key {
    std::uint32_t bits[3];
    bool operator==(const Key& o) const { return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2]; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = (static_cast<std::uint64_t>(k.bits[0]) << 32 | k.bits[1]) * 0x9E3779B97F4A7C15ull;
      h ^= (h >> 29) ^ (static_cast<std::uint64_t>(k.bits[2]) * 0xFF51AFD7ED558CCDull);
      h *= 0xC4CEB9FE1A85EC53ull;
      return static_cast<std::size_t>(h ^ (h >> 32));
    }
  };
  MeshBuilder& b_;
  std::int64_t max_;
  std::unordered_map<Key, int, Hash> map_;
};

std::uint32_t load_u32_le(const char* p) {
  const auto* u = reinterpret_cast<const unsigned char*>(p);
  return static_cast<std::uint32_t>(u[0]) | static_cast<std::uint32_t>(u[1]) << 8 |
         static_cast<std::uint32_t>(u[2]) << 16 | static_cast<std::uint32_t>(u[3]) << 24;
}

float load_f32_le(const char* p) {
  const std::uint32_t bits = load_u32_le(p);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

// ---------------------------------------------------------------- binary

std::string binary_size_note(std::uint32_t n, std::size_t size) {
  return "the header announces " + std::to_string(n) + " facets, which take " +
         std::to_string(kBinaryHeader + static_cast<std::uint64_t>(n) * kBinaryFacet) +
         " bytes, but the file has " + std::to_string(size) + " bytes";
}

MeshData read_binary(const char* data, std::size_t size, const std::string& name, const ReadOptions& opt) {
  const std::uint32_t n = load_u32_le(data + 80);
  const std::uint64_t expected = kBinaryHeader + static_cast<std::uint64_t>(n) * kBinaryFacet;
  if (size < expected) {
    const std::uint64_t whole = (size - kBinaryHeader) / kBinaryFacet;
    throw_input(name + ": facet " + std::to_string(whole) + " (byte offset " +
                std::to_string(kBinaryHeader + whole * kBinaryFacet) + "): file ends inside it (truncated file; " +
                binary_size_note(n, size) + ")");
  }
  if (size > expected)
    throw_input(name + ": binary STL: " + binary_size_note(n, size) + " (extra bytes after the last facet)");
  if (n == 0) throw_input(name + ": no faces (binary STL with 0 facets)");
  if (n > face_limit(opt))
    throw_input(name + ": header announces " + std::to_string(n) + " facets, more than the limit of " +
                std::to_string(face_limit(opt)));
  MeshBuilder b;
  Welder weld(b, vertex_limit(opt));
  weld.reserve(n);
  b.tri.reserve(static_cast<std::size_t>(n) * 3);
  b.line.assign(n, 0);  // binary facets have no source line
  for (std::uint32_t f = 0; f < n; ++f) {
    const std::size_t off = kBinaryHeader + static_cast<std::size_t>(f) * kBinaryFacet;
    auto fail = [&](const std::string& what) {
      throw_input(name + ": facet " + std::to_string(f) + " (byte offset " + std::to_string(off) + "): " + what);
    };
    for (int c = 0; c < 3; ++c) {
      float p[3];
      for (int a = 0; a < 3; ++a) {
        p[a] = load_f32_le(data + off + 12 + 12 * c + 4 * a);
        if (!std::isfinite(p[a])) fail("corner " + std::to_string(c) + " has a non-finite coordinate");
      }
      const int v = weld.vertex(p);
      if (v < 0) fail("more than " + std::to_string(vertex_limit(opt)) + " distinct vertices (the limit)");
      b.tri.push_back(v);
    }
  }
  return b.finish(name);
}

// ---------------------------------------------------------------- ASCII

bool same_word(std::string_view w, const char* kw) {
  const std::size_t n = std::strlen(kw);
  if (w.size() != n) return false;
  for (std::size_t i = 0; i < n; ++i) {
    char c = w[i];
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    if (c != kw[i]) return false;
  }
  return true;
}

// Skips blanks and line ends: ASCII STL tokens may be laid out freely.
void skip_space(TextScanner& s) {
  while (true) {
    s.skip_blanks();
    if (s.at_end() || *s.pos() != '\n') return;
    s.next_line();
  }
}

// Reads the next token, which must be the keyword kw (ASCII STL keywords are
// lower case; upper case, as some CAD tools write, is accepted too).
void expect(TextScanner& s, const char* kw, const char* context) {
  skip_space(s);
  if (s.at_end()) s.fail(std::string("file ends ") + context + ", expected '" + kw + "' (truncated file)");
  const std::string_view w = s.word();
  if (!same_word(w, kw)) s.fail(std::string("expected '") + kw + "' " + context + ", found " + quote_token(w));
}

void read_numbers(TextScanner& s, double out[3], const char* what) {
  for (int a = 0; a < 3; ++a) {
    skip_space(s);
    if (s.at_end()) s.fail(std::string("file ends inside ") + what + " (truncated file)");
    if (!s.parse_double(out[a])) s.fail(std::string("expected 3 numbers in ") + what + ", found " + quote_token(s.word()));
  }
}

// Reads one "facet normal ... endfacet" block (the keyword 'facet' already
// consumed) and appends its triangle.
void read_facet(TextScanner& s, Welder& weld, MeshBuilder& b, const ReadOptions& opt) {
  const int line = s.line();
  if (b.triangle_count() >= face_limit(opt))
    s.fail("more than " + std::to_string(face_limit(opt)) + " facets (the limit)");
  expect(s, "normal", "after 'facet'");
  double normal[3];  // recomputed from the corners by whoever needs it
  read_numbers(s, normal, "the facet normal");
  expect(s, "outer", "after the facet normal");
  expect(s, "loop", "after 'outer'");
  for (int c = 0; c < 3; ++c) {
    expect(s, "vertex", c == 0 ? "after 'outer loop'" : "(a facet has 3 vertices)");
    double d[3];
    read_numbers(s, d, "a vertex");
    if (!std::isfinite(d[0]) || !std::isfinite(d[1]) || !std::isfinite(d[2]))
      s.fail("vertex has a non-finite coordinate");
    // STL coordinates are float32, in text too: rounding here makes an ASCII
    // and a binary file of one mesh read alike, and welds as binary does.
    for (double x : d)
      if (std::fabs(x) > FLT_MAX) s.fail("vertex has a coordinate beyond the float32 range of STL");
    const float p[3] = {static_cast<float>(d[0]), static_cast<float>(d[1]), static_cast<float>(d[2])};
    const int v = weld.vertex(p);
    if (v < 0) s.fail("more than " + std::to_string(vertex_limit(opt)) + " distinct vertices (the limit)");
    b.tri.push_back(v);
  }
  expect(s, "endloop", "after the third vertex (a facet has 3 vertices)");
  expect(s, "endfacet", "after 'endloop'");
  b.line.push_back(line);
}

// Reads the rest of one solid after its 'solid NAME' line, up to and
// including its 'endsolid' line.
void read_solid(TextScanner& s, Welder& weld, MeshBuilder& b, const ReadOptions& opt) {
  while (true) {
    skip_space(s);
    if (s.at_end()) s.fail("file ends before 'endsolid' (truncated file)");
    const std::string_view w = s.word();
    if (same_word(w, "endsolid")) {
      s.next_line();  // the solid's name, repeated or not
      return;
    }
    if (!same_word(w, "facet")) s.fail("expected 'facet' or 'endsolid', found " + quote_token(w));
    read_facet(s, weld, b, opt);
  }
}

MeshData read_ascii(const char* data, std::size_t size, const std::string& name, const ReadOptions& opt) {
  TextScanner s(data, data + size, name);
  MeshBuilder b;
  Welder weld(b, vertex_limit(opt));
  // A facet takes at least ~60 bytes of text; exporters write 200 or more.
  const std::size_t guess = std::min<std::size_t>(size / 200 + 1, static_cast<std::size_t>(face_limit(opt)));
  weld.reserve(guess);
  b.tri.reserve(guess * 3);
  b.line.reserve(guess);
  skip_space(s);
  while (!s.at_end()) {  // several solids may follow one another
    const std::string_view w = s.word();
    if (!same_word(w, "solid")) s.fail("expected 'solid', found " + quote_token(w));
    s.next_line();  // the solid's name, if any
    read_solid(s, weld, b, opt);
    skip_space(s);
  }
  return b.finish(name);
}

// ---------------------------------------------------------------- choice

bool starts_with_solid(const char* data, std::size_t size) {
  std::size_t i = size >= 3 && std::memcmp(data, "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;
  while (i < size && (is_blank(data[i]) || data[i] == '\n')) ++i;
  if (size - i < 5 || !same_word(std::string_view(data + i, 5), "solid")) return false;
  return size - i == 5 || is_blank(data[i + 5]) || data[i + 5] == '\n';
}

// Offset of the first byte no text file holds (control characters other than
// whitespace; bytes >= 0x80 may be UTF-8 in a solid's name), or size if none.
std::size_t first_binary_byte(const char* data, std::size_t size) {
  for (std::size_t i = 0; i < size; ++i) {
    const unsigned char c = static_cast<unsigned char>(data[i]);
    if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\v' && c != '\f') || c == 0x7f) return i;
  }
  return size;
}

}  // namespace

// ASCII or binary: a binary file is exactly 84 + 50 n bytes with n its facet
// count, and its 80-byte header may start with "solid" too (many exporters
// write one). So: a size that fits the count means binary, unless the file
// starts with "solid" and is all text; otherwise "solid" and text mean ASCII.
MeshData read_stl(const char* data, std::size_t size, const std::string& name, const ReadOptions& opt) {
  if (size == 0) throw_input(name + ": no vertices (empty file)");
  const bool solid = starts_with_solid(data, size);
  const bool size_fits = size >= kBinaryHeader &&
                         size == kBinaryHeader + static_cast<std::uint64_t>(load_u32_le(data + 80)) * kBinaryFacet;
  const std::size_t bad = first_binary_byte(data, size);  // binary files stop this at once
  const bool text = bad == size;
  if (size_fits && !(solid && text)) return read_binary(data, size, name, opt);
  if (solid && text) {
    // Editors on Windows may prepend a UTF-8 byte order mark.
    if (size >= 3 && std::memcmp(data, "\xEF\xBB\xBF", 3) == 0) return read_ascii(data + 3, size - 3, name, opt);
    return read_ascii(data, size, name, opt);
  }
  if (text) throw_input(name + ": not an STL file: text that does not start with 'solid'");
  if (size < kBinaryHeader) {
    throw_input(name + ": not an STL file: too short for binary STL (84 bytes at least)" +
                (solid ? ", and not ASCII STL although it starts with 'solid': byte " + std::to_string(bad) +
                             " is not text"
                       : std::string()));
  }
  // Binary data whose size disagrees with its count (truncated or padded):
  // read_binary says where, and why it is not ASCII either when it claims to be.
  if (!solid) return read_binary(data, size, name, opt);
  try {
    return read_binary(data, size, name, opt);
  } catch (const Error& e) {
    throw_input(std::string(e.what()) + "; not ASCII STL either, although it starts with 'solid': byte " +
                std::to_string(bad) + " is not text");
  }
}

}  // namespace intrinsic::io
