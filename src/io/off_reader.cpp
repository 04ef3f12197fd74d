// OFF reader (Geomview object file format): "OFF" and its COFF/NOFF/STOFF
// variants, whose extra per-vertex and per-face values are skipped.
#include <algorithm>
#include <climits>
#include <cmath>
#include <vector>

#include "io/mesh_builder.h"
#include "io/text_scan.h"

namespace intrinsic::io {

namespace {

bool is_off_keyword(std::string_view w) {
  if (w.size() < 3 || w.substr(w.size() - 3) != "OFF") return false;
  for (char c : w.substr(0, w.size() - 3)) {
    // ST (texture), C (colour), N (normal) may prefix it; "4" or "n" change
    // the dimension, which we cannot read.
    if (c != 'S' && c != 'T' && c != 'C' && c != 'N') return false;
  }
  return true;
}

// Reads a count from the header; counts may share the keyword's line.
std::int64_t read_count(TextScanner& s, const char* what) {
  s.skip_space_and_comments();
  std::int64_t n;
  if (!s.parse_int64(n)) s.fail(std::string("expected the number of ") + what + " in the OFF header");
  if (n < 0) s.fail(std::string("negative number of ") + what + " in the OFF header");
  return n;
}

// The counts line of the header.
struct OffHeader {
  std::int64_t nv = 0, nf = 0;  // announced vertex and face counts
  int line = 0;                 // the counts' line, for messages
};

// Reads the keyword and the counts line, leaving s at the first vertex line.
OffHeader read_header(TextScanner& s, const std::string& name) {
  s.skip_space_and_comments();
  if (s.at_end()) throw_input(name + ": no vertices (empty file)");
  std::string_view kw = s.word();
  if (!is_off_keyword(kw)) {
    if (kw.size() > 3 && kw.substr(kw.size() - 3) == "OFF")
      s.fail("unsupported OFF variant " + quote_token(kw) + " (only 3-D OFF, COFF, NOFF, STOFF)");
    s.fail("expected the OFF header, found " + quote_token(kw));
  }
  s.skip_blanks();
  if (!s.at_line_end()) {
    std::string_view w = s.word();
    if (w == "BINARY") s.fail("binary OFF is not supported");
    // Not a keyword: it is the start of the counts line.
    s = TextScanner(w.data(), s.end(), name, s.line());
  }
  OffHeader h;
  h.nv = read_count(s, "vertices");
  h.nf = read_count(s, "faces");
  if (!s.at_line_end()) {
    std::int64_t ne;  // edge count: unused, but must be a number if present
    if (!s.parse_int64(ne)) s.fail("expected the number of edges in the OFF header");
  }
  h.line = s.line();
  s.next_line();
  return h;
}

// Refuses counts above the options' limits, or that the rest of the file
// cannot hold.
void check_counts(const TextScanner& s, const OffHeader& h, const ReadOptions& opt) {
  if (h.nv > vertex_limit(opt))
    s.fail_at(h.line, "header announces " + std::to_string(h.nv) + " vertices, more than the limit of " +
                          std::to_string(vertex_limit(opt)));
  if (h.nf > face_limit(opt))
    s.fail_at(h.line, "header announces " + std::to_string(h.nf) + " faces, more than the limit of " +
                          std::to_string(face_limit(opt)));
  // Each vertex needs at least "0 0 0\n" and each face "3 0 0 0\n": refuse
  // impossible counts before allocating for them.
  const std::uint64_t left = s.remaining();
  if (static_cast<std::uint64_t>(h.nv) > (left + 1) / 6 ||
      static_cast<std::uint64_t>(h.nv) * 6 + static_cast<std::uint64_t>(h.nf) * 8 > left + 8) {
    s.fail_at(h.line, "header announces " + std::to_string(h.nv) + " vertices and " + std::to_string(h.nf) +
                          " faces, but the file holds only " + std::to_string(left) + " more bytes");
  }
}

// Reads nv vertex lines, ignoring anything after x y z.
void read_vertices(TextScanner& s, std::int64_t nv, MeshBuilder& b) {
  for (std::int64_t i = 0; i < nv; ++i) {
    s.skip_space_and_comments();
    if (s.at_end()) s.fail("file ends after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices");
    double c[3];
    for (double& x : c) {
      if (!s.parse_double(x)) s.fail("expected 3 coordinates for vertex " + std::to_string(i));
    }
    if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]))
      s.fail("vertex " + std::to_string(i) + " has a non-finite coordinate");
    b.xyz.insert(b.xyz.end(), c, c + 3);
    s.next_line();  // colours, normals, texture coordinates
  }
}

// Reads nf face lines "n i1 ... in", fanned into triangles.
void read_faces(TextScanner& s, const OffHeader& h, const ReadOptions& opt, MeshBuilder& b) {
  const std::int64_t nv = h.nv, nf = h.nf;
  std::vector<std::int64_t> poly;
  for (std::int64_t i = 0; i < nf; ++i) {
    s.skip_space_and_comments();
    if (s.at_end()) s.fail("file ends after " + std::to_string(i) + " of " + std::to_string(nf) + " faces");
    std::int64_t n;
    if (!s.parse_int64(n)) s.fail("expected the vertex count of face " + std::to_string(i));
    if (n < 3) s.fail("face " + std::to_string(i) + " has " + std::to_string(n) + " vertices (at least 3 needed)");
    poly.clear();
    for (std::int64_t k = 0; k < n; ++k) {
      std::int64_t idx;
      if (s.at_line_end())
        s.fail("face " + std::to_string(i) + " announces " + std::to_string(n) + " vertices but lists " +
               std::to_string(k));
      if (!s.parse_int64(idx)) s.fail("expected a vertex index in face " + std::to_string(i));
      if (idx < 0 || idx >= nv)
        s.fail("face index " + std::to_string(idx) + " out of range (file has " + std::to_string(nv) +
               " vertices)");
      poly.push_back(idx);
    }
    if (b.triangle_count() + n - 2 > face_limit(opt))
      s.fail("more than " + std::to_string(face_limit(opt)) + " faces (the limit)");
    for (std::size_t k = 1; k + 1 < poly.size(); ++k) {
      b.tri.push_back(static_cast<int>(poly[0]));
      b.tri.push_back(static_cast<int>(poly[k]));
      b.tri.push_back(static_cast<int>(poly[k + 1]));
      b.line.push_back(s.line());
    }
    s.next_line();  // per-face colour
  }
}

}  // namespace

MeshData read_off(const char* data, std::size_t size, const std::string& name, const ReadOptions& opt) {
  TextScanner s(data, data + size, name);
  const OffHeader h = read_header(s, name);
  check_counts(s, h, opt);
  MeshBuilder b;
  b.xyz.reserve(static_cast<std::size_t>(h.nv) * 3);
  b.tri.reserve(static_cast<std::size_t>(h.nf) * 3);
  b.line.reserve(static_cast<std::size_t>(h.nf));
  read_vertices(s, h.nv, b);
  read_faces(s, h, opt, b);
  return b.finish(name);
}

}  // namespace intrinsic::io
