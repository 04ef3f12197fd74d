// OBJ and PLY writers. Numbers are printed with std::to_chars' shortest
// round-trip form, so reading a written mesh gives back the same doubles.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <thread>
#include <vector>

#include "intrinsic/io.h"

namespace intrinsic {

namespace {

// Appends formatted numbers to one growing buffer; the whole file is then
// handed to write_file_atomically.
class OutBuffer {
 public:
  explicit OutBuffer(std::size_t reserve) { s_.reserve(reserve); }
  void text(const char* t) { s_.append(t); }
  void text(const std::string& t) { s_.append(t); }
  void ch(char c) { s_.push_back(c); }
  void num(double x) {
    char b[32];
    auto r = std::to_chars(b, b + sizeof b, x);
    s_.append(b, r.ptr);
  }
  void num(long long x) {
    char b[24];
    auto r = std::to_chars(b, b + sizeof b, x);
    s_.append(b, r.ptr);
  }
  template <class T>
  void raw_le(T x) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &x, sizeof(T));
    const std::uint16_t probe = 1;
    unsigned char first;
    std::memcpy(&first, &probe, 1);
    if (first != 1) std::reverse(b, b + sizeof(T));
    s_.append(reinterpret_cast<const char*>(b), sizeof(T));
  }
  std::string& str() { return s_; }

 private:
  std::string s_;
};

void check_input(const std::string& path, const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV) {
  if (UV.rows() != 0 && UV.rows() != V.rows())
    throw_output("cannot write " + path + ": " + std::to_string(UV.rows()) + " texture coordinates for " +
                 std::to_string(V.rows()) + " vertices");
  if (!V.allFinite()) throw_output("cannot write " + path + ": the vertex positions are not all finite");
  if (!UV.allFinite()) throw_output("cannot write " + path + ": the texture coordinates are not all finite");
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (F(f, k) < 0 || F(f, k) >= V.rows())
        throw_output("cannot write " + path + ": face " + std::to_string(f) + " has vertex index " +
                     std::to_string(F(f, k)) + " (mesh has " + std::to_string(V.rows()) + " vertices)");
}

// The vertex, texture and face lines of rows [part/parts, (part+1)/parts) of
// each section, into three buffers.
struct ObjPart {
  std::string v, vt, f;
};

void obj_part(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV, int part, int parts, ObjPart& out) {
  auto range = [&](Eigen::Index n, Eigen::Index& b, Eigen::Index& e) {
    b = n * part / parts;
    e = n * (part + 1) / parts;
  };
  Eigen::Index b, e;
  range(V.rows(), b, e);
  OutBuffer v(static_cast<std::size_t>(e - b) * 80);
  for (Eigen::Index i = b; i < e; ++i) {
    v.text("v ");
    v.num(V(i, 0)); v.ch(' ');
    v.num(V(i, 1)); v.ch(' ');
    v.num(V(i, 2)); v.ch('\n');
  }
  out.v = std::move(v.str());
  range(UV.rows(), b, e);
  OutBuffer t(static_cast<std::size_t>(e - b) * 48);
  for (Eigen::Index i = b; i < e; ++i) {
    t.text("vt ");
    t.num(UV(i, 0)); t.ch(' ');
    t.num(UV(i, 1)); t.ch('\n');
  }
  out.vt = std::move(t.str());
  const bool uv = UV.rows() > 0;
  range(F.rows(), b, e);
  OutBuffer o(static_cast<std::size_t>(e - b) * 48);
  for (Eigen::Index f = b; f < e; ++f) {
    o.ch('f');
    for (int k = 0; k < 3; ++k) {
      const long long idx = static_cast<long long>(F(f, k)) + 1;
      o.ch(' ');
      o.num(idx);
      if (uv) {
        o.ch('/');
        o.num(idx);
      }
    }
    o.ch('\n');
  }
  out.f = std::move(o.str());
}

// Formatting (shortest round-trip doubles) dominates writing: large meshes
// are formatted in two halves on two threads, then joined.
std::string obj_text(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV) {
  const int parts = V.rows() + F.rows() >= 200000 && std::thread::hardware_concurrency() > 1 ? 2 : 1;
  std::vector<ObjPart> p(parts);
  std::vector<std::thread> threads;
  for (int k = 1; k < parts; ++k)
    threads.emplace_back(obj_part, std::cref(V), std::cref(F), std::cref(UV), k, parts, std::ref(p[k]));
  obj_part(V, F, UV, 0, parts, p[0]);
  for (std::thread& t : threads) t.join();
  const char* header = "# written by intrinsic\n";
  std::size_t size = std::strlen(header);
  for (const ObjPart& q : p) size += q.v.size() + q.vt.size() + q.f.size();
  std::string s;
  s.reserve(size);
  s.append(header);
  for (const ObjPart& q : p) s.append(q.v);
  for (const ObjPart& q : p) s.append(q.vt);
  for (const ObjPart& q : p) s.append(q.f);
  return s;
}

std::string ply_text(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV, bool binary) {
  const bool uv = UV.rows() > 0;
  OutBuffer o(static_cast<std::size_t>(V.rows()) * (binary ? 40 : 80) +
              static_cast<std::size_t>(F.rows()) * (binary ? 13 : 32) + 256);
  o.text("ply\n");
  o.text(binary ? "format binary_little_endian 1.0\n" : "format ascii 1.0\n");
  o.text("comment written by intrinsic\n");
  o.text("element vertex " + std::to_string(V.rows()) + "\n");
  o.text("property double x\nproperty double y\nproperty double z\n");
  if (uv) o.text("property double u\nproperty double v\n");
  o.text("element face " + std::to_string(F.rows()) + "\n");
  o.text("property list uchar int vertex_indices\nend_header\n");
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    if (binary) {
      for (int k = 0; k < 3; ++k) o.raw_le(V(i, k));
      if (uv) o.raw_le(UV(i, 0)), o.raw_le(UV(i, 1));
    } else {
      o.num(V(i, 0)); o.ch(' ');
      o.num(V(i, 1)); o.ch(' ');
      o.num(V(i, 2));
      if (uv) {
        o.ch(' '); o.num(UV(i, 0));
        o.ch(' '); o.num(UV(i, 1));
      }
      o.ch('\n');
    }
  }
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (binary) {
      o.raw_le(static_cast<std::uint8_t>(3));
      for (int k = 0; k < 3; ++k) o.raw_le(static_cast<std::int32_t>(F(f, k)));
    } else {
      o.ch('3');
      for (int k = 0; k < 3; ++k) {
        o.ch(' ');
        o.num(static_cast<long long>(F(f, k)));
      }
      o.ch('\n');
    }
  }
  return std::move(o.str());
}

}  // namespace

void write_mesh(const std::string& path, const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV,
                const WriteOptions& options) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  std::string ext;
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) ext = path.substr(dot);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".obj" && ext != ".ply")
    throw_usage("unknown output format '" + ext + "' (use .obj or .ply)");
  check_input(path, V, F, UV);
  write_file_atomically(path, ext == ".obj" ? obj_text(V, F, UV) : ply_text(V, F, UV, options.binary));
}

}  // namespace intrinsic
