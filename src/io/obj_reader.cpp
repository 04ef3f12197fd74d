// Wavefront OBJ reader: positions, texture coordinates and polygonal faces
// (fan-triangulated), and what the writers give back (obj_extras.h):
// normals, material libraries, usemtl/g/o/s per face. Everything else an OBJ
// may hold (vp, l, p, curves, ...) is ignored.
#include <algorithm>
#include <atomic>
#include <climits>
#include <cmath>
#include <optional>
#include <thread>
#include <vector>

#include "io/mesh_builder.h"
#include "io/obj_extras.h"
#include "io/text_scan.h"
#include "util/parallel_for.h"

namespace intrinsic::io {

namespace {

struct Corner {
  std::int64_t v;
  std::int64_t vt;  // -1: none given
  std::int64_t vn;  // -1: none given
};

// Turns an OBJ index (1-based, or negative counting back from the last
// element defined so far) into a 0-based one. Positive indices may refer
// forward (some exporters write faces first), so they are range-checked once
// the whole file is read.
std::int64_t resolve(TextScanner& s, std::int64_t idx, std::int64_t defined, const char* what) {
  if (idx == 0) s.fail(std::string("face ") + what + " index 0 is invalid (OBJ indices start at 1)");
  if (idx > 0) {
    if (idx > INT_MAX) s.fail(std::string("face ") + what + " index " + std::to_string(idx) + " is too large");
    return idx - 1;
  }
  if (idx < -defined) {
    s.fail(std::string("face ") + what + " index " + std::to_string(idx) + " out of range (only " +
           std::to_string(defined) + " defined so far)");
  }
  return defined + idx;
}

// What the line loop carries from one line to the next.
struct ObjState {
  MeshBuilder b;
  std::int64_t max_v = 0, max_f = 0;  // the options' limits
  std::int64_t n_tc = 0;              // texture coordinates so far
  bool every_face_has_vt = true;
  std::vector<Corner> poly;  // the current face, reused to avoid allocations
  ObjExtrasBuilder extras;
  // A piece of the file parsed on its own (read_obj_in_pieces): indices that
  // count back from what is defined so far cannot be resolved there.
  bool piece = false;
};

// Thrown inside a piece for what only the whole-file parse can handle; the
// file is then read again by it (which also gives every error its message).
struct NotInPieces {};

// Counting 'v', 'vt', 'vn' and 'f' lines first costs one memchr pass but
// spares the repeated regrowth (and page faults) of the big arrays.
struct LineCounts {
  std::size_t v = 0, vt = 0, vn = 0, f = 0;
};

LineCounts count_lines(const char* data, std::size_t size) {
  LineCounts n;
  const char* q = data;
  const char* end = data + size;
  while (q < end) {
    if (end - q > 1 && q[1] == ' ') {
      if (q[0] == 'v') ++n.v;
      if (q[0] == 'f') ++n.f;
    } else if (end - q > 2 && q[0] == 'v' && q[2] == ' ') {
      if (q[1] == 't') ++n.vt;
      if (q[1] == 'n') ++n.vn;
    }
    const void* nl = std::memchr(q, '\n', static_cast<std::size_t>(end - q));
    q = nl ? static_cast<const char*>(nl) + 1 : end;
  }
  return n;
}

void reserve_for(const LineCounts& n, ObjState& st) {
  const std::size_t limit_v = static_cast<std::size_t>(st.max_v), limit_f = static_cast<std::size_t>(st.max_f);
  const std::size_t nf = std::min(n.f, limit_f);
  st.b.xyz.reserve(std::min(n.v, limit_v) * 3);
  st.b.tri.reserve(nf * 3);
  st.b.line.reserve(nf);
  if (n.vt > 0) {
    st.b.uv.reserve(std::min(n.vt, limit_v) * 2);
    st.b.tri_uv.reserve(nf * 3);
  }
  st.extras.normal.reserve(std::min(n.vn, limit_v) * 3);
  st.extras.triangle_hint = nf;  // per-face arrays, if the file needs them
}

// Reads the x y z of a 'v' line (keyword already consumed).
void read_vertex(TextScanner& s, ObjState& st) {
  MeshBuilder& b = st.b;
  double c[3];
  for (double& x : c) {
    if (!s.parse_double(x)) s.fail("expected a number after 'v'");
  }
  if (b.vertex_count() >= st.max_v)
    s.fail("more than " + std::to_string(st.max_v) + " vertices (the limit)");
  if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]))
    s.fail("vertex " + std::to_string(b.vertex_count() + 1) + " has a non-finite coordinate");
  b.xyz.insert(b.xyz.end(), c, c + 3);
  // Whatever follows (w, vertex colours) is not ours to read.
}

// Reads the u [v] of a 'vt' line (keyword already consumed).
void read_texcoord(TextScanner& s, ObjState& st) {
  double u = 0, v = 0;
  if (!s.parse_double(u)) s.fail("expected a number after 'vt'");
  if (!s.at_line_end() && !s.parse_double(v)) s.fail("expected a number after 'vt'");
  if (!std::isfinite(u) || !std::isfinite(v))
    s.fail("texture coordinate " + std::to_string(st.n_tc + 1) + " is not finite");
  if (st.n_tc >= st.max_v) s.fail("more than " + std::to_string(st.max_v) + " texture coordinates (the limit)");
  st.b.uv.push_back(u);
  st.b.uv.push_back(v);
  ++st.n_tc;
}

// The usual face line of a large file, "f a b c" with three positive indices
// and nothing else, read with a digit loop (from_chars and the general
// corner loop were half of the reading time). False, with nothing changed,
// for anything else (slashes, signs, a leading 0, more corners, a comment, a
// limit reached): read_face then reads the line from its start, and reports
// what is wrong with it.
bool read_plain_triangle(TextScanner& s, ObjState& st) {
  const char* p = s.pos();
  const char* const end = s.end();
  int idx[3];
  for (int& out : idx) {
    while (p < end && is_blank(*p)) ++p;
    if (p >= end || *p < '1' || *p > '9') return false;
    std::int64_t v = 0;
    for (int digits = 0; p < end && *p >= '0' && *p <= '9'; ++p) {
      if (++digits > 10) return false;
      v = 10 * v + (*p - '0');
    }
    if (v > INT_MAX || (p < end && !is_blank(*p) && *p != '\n')) return false;
    out = static_cast<int>(v - 1);
  }
  while (p < end && is_blank(*p)) ++p;
  if (p < end && *p != '\n') return false;
  MeshBuilder& b = st.b;
  if (b.triangle_count() + 1 > st.max_f) return false;
  const std::size_t before = static_cast<std::size_t>(b.triangle_count());
  b.tri.insert(b.tri.end(), idx, idx + 3);
  st.extras.add_triangle_normals(before, -1, -1, -1);
  b.line.push_back(s.line());
  st.extras.tag_triangles(before, 1);
  st.every_face_has_vt = false;  // no texture index given
  b.tri_uv.clear();
  s.skip_to(p);
  return true;
}

// Reads the corners ("v", "v/vt", "v//vn" or "v/vt/vn") of an 'f' line
// (keyword already consumed) and appends its fan of triangles; texture
// indices are kept only while every face has them. The corner loop stays in
// this function: it runs for every corner of the file.
void read_face(TextScanner& s, ObjState& st) {
  if (read_plain_triangle(s, st)) return;
  MeshBuilder& b = st.b;
  std::vector<Corner>& poly = st.poly;
  poly.clear();
  bool all_vt = true;
  while (!s.at_line_end()) {
    Corner c{0, -1, -1};
    std::int64_t written;
    if (!s.parse_int64_prefix(written)) {
      s.fail("expected a vertex index in face, found " + quote_token(s.word()));
    }
    if (st.piece && written < 0) throw NotInPieces{};
    c.v = resolve(s, written, b.vertex_count(), "vertex");
    if (s.consume('/')) {
      if (s.pos() < s.end() && *s.pos() != '/') {
        std::int64_t t;
        if (!s.parse_int64_prefix(t)) s.fail("expected a texture index after '/' in face");
        if (st.piece && t < 0) throw NotInPieces{};
        c.vt = resolve(s, t, st.n_tc, "texture");
      }
      if (s.consume('/')) {
        std::int64_t n;
        if (!s.at_token_end()) {
          if (!s.parse_int64_prefix(n)) s.fail("expected a normal index after '/' in face");
          if (st.piece) throw NotInPieces{};  // normals are kept by the whole-file parse only
          c.vn = resolve(s, n, st.extras.normal_count(), "normal");
        }
      }
    }
    if (!s.at_token_end()) s.fail("unexpected " + quote_token(s.word()) + " in face");
    if (c.vt < 0) all_vt = false;
    poly.push_back(c);
  }
  if (poly.size() < 3) s.fail("face has " + std::to_string(poly.size()) + " vertices (at least 3 needed)");
  if (!all_vt) st.every_face_has_vt = false;
  if (b.triangle_count() + static_cast<std::int64_t>(poly.size()) - 2 > st.max_f)
    s.fail("more than " + std::to_string(st.max_f) + " faces (the limit)");
  const std::size_t before = static_cast<std::size_t>(b.triangle_count());
  for (std::size_t k = 1; k + 1 < poly.size(); ++k) {
    const Corner* t[3] = {&poly[0], &poly[k], &poly[k + 1]};
    for (const Corner* c : t) {
      b.tri.push_back(static_cast<int>(c->v));
      if (st.every_face_has_vt) b.tri_uv.push_back(static_cast<int>(c->vt));
    }
    st.extras.add_triangle_normals(before + k - 1, static_cast<int>(t[0]->vn), static_cast<int>(t[1]->vn),
                                   static_cast<int>(t[2]->vn));
    b.line.push_back(s.line());
  }
  st.extras.tag_triangles(before, poly.size() - 2);
  if (!st.every_face_has_vt) b.tri_uv.clear();
}

// Range-checks the face indices once every element is known (positive
// indices may refer forward); drops the texture coordinates if unused.
void check_face_indices(const TextScanner& s, ObjState& st) {
  MeshBuilder& b = st.b;
  const std::int64_t nv = b.vertex_count();
  for (std::size_t i = 0; i < b.tri.size(); ++i) {
    if (b.tri[i] >= nv) {
      s.fail_at(b.line[i / 3], "face index " + std::to_string(std::int64_t(b.tri[i]) + 1) +
                                   " out of range (file has " + std::to_string(nv) + " vertices)");
    }
  }
  if (!b.tri_uv.empty()) {
    for (std::size_t i = 0; i < b.tri_uv.size(); ++i) {
      if (b.tri_uv[i] >= st.n_tc) {
        s.fail_at(b.line[i / 3], "face texture index " + std::to_string(std::int64_t(b.tri_uv[i]) + 1) +
                                     " out of range (file has " + std::to_string(st.n_tc) +
                                     " texture coordinates)");
      }
    }
  } else {
    b.uv.clear();
  }
}

// The statement loop over every line of the scanner's range. In a piece,
// statements other than v, vt, f and comments hand the file back to the
// whole-file parse.
void parse_lines(TextScanner& s, ObjState& st) {
  while (!s.at_end()) {
    s.skip_blanks();
    if (s.at_end()) break;
    const char* p = s.pos();
    const std::size_t left = s.remaining();
    auto keyword_is = [&](const char* kw, std::size_t n) {
      return left >= n && std::memcmp(p, kw, n) == 0 && (left == n || is_blank(p[n]) || p[n] == '\n');
    };
    if (keyword_is("v", 1)) {
      s.word();
      read_vertex(s, st);
    } else if (keyword_is("vt", 2)) {
      s.word();
      read_texcoord(s, st);
    } else if (keyword_is("f", 1)) {
      s.word();
      read_face(s, st);
    } else if (st.piece && *p != '#' && *p != '\n') {
      throw NotInPieces{};
    } else if (keyword_is("vn", 2)) {
      s.word();
      st.extras.read_normal(s, st.max_v);
    } else {
      // mtllib, usemtl, g, o, s are kept; other statements (vp, l, comments)
      // are skipped, like whatever follows the values we read.
      const std::string_view keyword = s.word();
      st.extras.read_statement(keyword, s);
    }
    s.next_line();
  }
}

// Where the pieces of a file start: near equal byte counts, each moved to
// the start of a line; cut[parts] is the end.
std::vector<std::size_t> piece_starts(const char* data, std::size_t size, int parts) {
  std::vector<std::size_t> cut(static_cast<size_t>(parts) + 1, size);
  cut[0] = 0;
  for (int k = 1; k < parts; ++k) {
    const std::size_t from = std::max(cut[k - 1], size / parts * k);
    const void* nl = std::memchr(data + from, '\n', size - from);
    cut[k] = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - data) + 1 : size;
  }
  return cut;
}

// Copies the pieces into one MeshData, face lines shifted by the lines of the
// pieces before; nullopt if an index is out of range or the result is empty
// (the whole-file parse then says so, with its messages).
std::optional<MeshData> join_pieces(std::vector<ObjState>& pieces, const std::vector<int>& lines,
                                    const std::string& name) {
  std::int64_t nv = 0, ntc = 0, ntri = 0;
  bool every_face_has_vt = true;
  for (const ObjState& p : pieces) {
    nv += p.b.vertex_count();
    ntc += p.n_tc;
    ntri += p.b.triangle_count();
    every_face_has_vt = every_face_has_vt && p.every_face_has_vt;
  }
  if (nv == 0 || ntri == 0 || nv > pieces[0].max_v || ntc > pieces[0].max_v || ntri > pieces[0].max_f)
    return std::nullopt;
  // Texture indices on every face: kept, and range-checked like the vertices.
  const bool with_uv = every_face_has_vt;
  MeshData m;
  m.V.resize(nv, 3);
  m.F.resize(ntri, 3);
  m.face_line.resize(static_cast<size_t>(ntri));
  if (with_uv) {
    m.TC.resize(ntc, 2);
    m.FTC.resize(ntri, 3);
  }
  std::vector<std::int64_t> v0(pieces.size() + 1, 0), t0(v0), f0(v0), line0(v0);
  for (size_t k = 0; k < pieces.size(); ++k) {
    v0[k + 1] = v0[k] + pieces[k].b.vertex_count();
    t0[k + 1] = t0[k] + pieces[k].n_tc;
    f0[k + 1] = f0[k] + pieces[k].b.triangle_count();
    line0[k + 1] = line0[k] + lines[k];
  }
  std::atomic<bool> in_range{true};
  detail::parallel_for_parts(static_cast<std::int64_t>(pieces.size()), static_cast<int>(pieces.size()),
                             [&](int k, std::int64_t, std::int64_t) {
    const MeshBuilder& b = pieces[k].b;
    for (std::int64_t i = 0; i < b.vertex_count(); ++i)
      for (int c = 0; c < 3; ++c) m.V(v0[k] + i, c) = b.xyz[3 * i + c];
    for (std::int64_t t = 0; t < b.triangle_count(); ++t) {
      for (int c = 0; c < 3; ++c) {
        const int v = b.tri[3 * t + c];
        if (v >= nv || (with_uv && b.tri_uv[3 * t + c] >= ntc)) in_range = false;
        m.F(f0[k] + t, c) = v;
        if (with_uv) m.FTC(f0[k] + t, c) = b.tri_uv[3 * t + c];
      }
      m.face_line[f0[k] + t] = static_cast<int>(line0[k] + b.line[t]);
    }
    for (std::int64_t i = 0; with_uv && i < pieces[k].n_tc; ++i)
      for (int c = 0; c < 2; ++c) m.TC(t0[k] + i, c) = b.uv[2 * i + c];
  });
  if (!in_range) return std::nullopt;
  m.had_texcoords = ntc > 0;
  m.path = name;
  return m;
}

// A large file of v, vt, f lines and comments (what the writers produce)
// parsed in pieces on all cores; nullopt for anything else, or any error,
// which the whole-file parse then reads (or reports) as always.
std::optional<MeshData> read_obj_in_pieces(const char* data, std::size_t size, const std::string& name,
                                           const ReadOptions& opt) {
  const int parts = static_cast<int>(std::min<std::size_t>(
      {size / (4u << 20), std::max(1u, std::thread::hardware_concurrency()), 8u}));
  if (parts < 2) return std::nullopt;
  const std::vector<std::size_t> cut = piece_starts(data, size, parts);
  std::vector<ObjState> pieces(parts);
  std::vector<LineCounts> counts(parts);
  detail::parallel_for_parts(parts, parts, [&](int k, std::int64_t, std::int64_t) {
    counts[k] = count_lines(data + cut[k], cut[k + 1] - cut[k]);
  });
  // The arrays are reserved on this thread: memory a worker allocates stays
  // in its own malloc arena after it is freed, as resident memory.
  for (int k = 0; k < parts; ++k) {
    ObjState& st = pieces[k];
    st.piece = true;
    st.max_v = vertex_limit(opt);
    st.max_f = face_limit(opt);
    st.poly.reserve(16);
    reserve_for(counts[k], st);
  }
  std::vector<int> lines(parts, 0);
  std::atomic<bool> ok{true};
  detail::parallel_for_parts(parts, parts, [&](int k, std::int64_t, std::int64_t) {
    ObjState& st = pieces[k];
    try {
      TextScanner s(data + cut[k], data + cut[k + 1], name);
      parse_lines(s, st);
      lines[k] = s.line() - 1;  // the piece ends just after a newline
      if (!st.extras.tri_n.empty()) ok = false;
    } catch (...) {  // an error or NotInPieces: the whole-file parse decides
      ok = false;
    }
  });
  if (!ok) return std::nullopt;
  return join_pieces(pieces, lines, name);
}

}  // namespace

MeshFile read_obj(const char* data, std::size_t size, const std::string& name, const ReadOptions& opt) {
  // Pieces hold only v, vt and f lines: there are no extras to keep.
  if (std::optional<MeshData> m = read_obj_in_pieces(data, size, name, opt)) return {std::move(*m), {}};
  TextScanner s(data, data + size, name);
  ObjState st;
  st.max_v = vertex_limit(opt);
  st.max_f = face_limit(opt);
  st.poly.reserve(16);
  reserve_for(count_lines(data, size), st);
  parse_lines(s, st);
  st.b.had_texcoords = st.n_tc > 0;
  check_face_indices(s, st);
  st.extras.check(s, st.b.line);
  MeshFile file;
  file.mesh = st.b.finish(name);
  file.document.obj = st.extras.finish();
  return file;
}

}  // namespace intrinsic::io
