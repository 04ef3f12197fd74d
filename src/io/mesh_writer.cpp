// OBJ and PLY writers. Numbers are printed with std::to_chars' shortest
// round-trip form, so reading a written mesh gives back the same doubles.
// Large files are formatted in chunks on worker threads and streamed to the
// temporary file as they are ready.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <deque>
#include <functional>
#include <future>
#include <thread>
#include <vector>

#include "intrinsic/io.h"

namespace intrinsic {

namespace {

// Appends formatted numbers to one growing buffer (a chunk of the file).
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

// A file made of sections of rows (vertex lines, face lines, ...), each row
// formatted independently.
struct Section {
  Eigen::Index rows;
  std::size_t bytes_per_row;  // a generous guess, to reserve buffers
  std::function<void(Eigen::Index row, OutBuffer& out)> format;
};

// Formats the sections in chunks of rows on worker threads while this thread
// hands finished chunks, in order, to the sink: formatting (shortest
// round-trip doubles) and the kernel's copy into the page cache overlap, and
// no more than a few chunks are in memory at once (a 1M-vertex OBJ with UVs
// is 190 MB).
void produce_sections(const std::string& header, const std::vector<Section>& sections, const ByteSink& sink) {
  sink(header.data(), header.size());
  constexpr Eigen::Index kChunkRows = 32768;
  struct Chunk {
    const Section* section;
    Eigen::Index begin, end;
  };
  std::vector<Chunk> chunks;
  for (const Section& sec : sections)
    for (Eigen::Index b = 0; b < sec.rows; b += kChunkRows) chunks.push_back({&sec, b, std::min(sec.rows, b + kChunkRows)});
  auto format = [](const Chunk& c) {
    OutBuffer out(static_cast<std::size_t>(c.end - c.begin) * c.section->bytes_per_row);
    for (Eigen::Index r = c.begin; r < c.end; ++r) c.section->format(r, out);
    return std::move(out.str());
  };
  const bool threaded = chunks.size() > 2 && std::thread::hardware_concurrency() > 1;
  if (!threaded) {
    for (const Chunk& c : chunks) {
      const std::string text = format(c);
      sink(text.data(), text.size());
    }
    return;
  }
  // Two chunks formatting ahead of the one being written. A future's
  // destructor waits for its task, so an exception from the sink leaves no
  // thread running.
  constexpr std::size_t kAhead = 2;
  std::deque<std::future<std::string>> pending;
  std::size_t next = 0;
  while (next < chunks.size() && pending.size() < kAhead)
    pending.push_back(std::async(std::launch::async, format, std::cref(chunks[next++])));
  while (!pending.empty()) {
    const std::string text = pending.front().get();
    pending.pop_front();
    if (next < chunks.size()) pending.push_back(std::async(std::launch::async, format, std::cref(chunks[next++])));
    sink(text.data(), text.size());
  }
}

void write_obj(const std::string& path, const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV) {
  const bool uv = UV.rows() > 0;
  std::vector<Section> sections;
  sections.push_back({V.rows(), 80, [&](Eigen::Index i, OutBuffer& o) {
                        o.text("v ");
                        o.num(V(i, 0)); o.ch(' ');
                        o.num(V(i, 1)); o.ch(' ');
                        o.num(V(i, 2)); o.ch('\n');
                      }});
  sections.push_back({UV.rows(), 48, [&](Eigen::Index i, OutBuffer& o) {
                        o.text("vt ");
                        o.num(UV(i, 0)); o.ch(' ');
                        o.num(UV(i, 1)); o.ch('\n');
                      }});
  sections.push_back({F.rows(), 48, [&](Eigen::Index f, OutBuffer& o) {
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
                      }});
  write_file_atomically(path, [&](const ByteSink& sink) { produce_sections("# written by intrinsic\n", sections, sink); });
}

void write_ply(const std::string& path, const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV, bool binary) {
  const bool uv = UV.rows() > 0;
  std::string header = "ply\n";
  header += binary ? "format binary_little_endian 1.0\n" : "format ascii 1.0\n";
  header += "comment written by intrinsic\n";
  header += "element vertex " + std::to_string(V.rows()) + "\n";
  header += "property double x\nproperty double y\nproperty double z\n";
  if (uv) header += "property double u\nproperty double v\n";
  header += "element face " + std::to_string(F.rows()) + "\n";
  header += "property list uchar int vertex_indices\nend_header\n";
  std::vector<Section> sections;
  sections.push_back({V.rows(), binary ? 40u : 112u, [&](Eigen::Index i, OutBuffer& o) {
                        if (binary) {
                          for (int k = 0; k < 3; ++k) o.raw_le(V(i, k));
                          if (uv) o.raw_le(UV(i, 0)), o.raw_le(UV(i, 1));
                          return;
                        }
                        o.num(V(i, 0)); o.ch(' ');
                        o.num(V(i, 1)); o.ch(' ');
                        o.num(V(i, 2));
                        if (uv) {
                          o.ch(' '); o.num(UV(i, 0));
                          o.ch(' '); o.num(UV(i, 1));
                        }
                        o.ch('\n');
                      }});
  sections.push_back({F.rows(), binary ? 13u : 32u, [&](Eigen::Index f, OutBuffer& o) {
                        if (binary) {
                          o.raw_le(static_cast<std::uint8_t>(3));
                          for (int k = 0; k < 3; ++k) o.raw_le(static_cast<std::int32_t>(F(f, k)));
                          return;
                        }
                        o.ch('3');
                        for (int k = 0; k < 3; ++k) {
                          o.ch(' ');
                          o.num(static_cast<long long>(F(f, k)));
                        }
                        o.ch('\n');
                      }});
  write_file_atomically(path, [&](const ByteSink& sink) { produce_sections(header, sections, sink); });
}

}  // namespace

void write_mesh(const std::string& path, const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV,
                const WriteOptions& options) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  std::string ext;
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) ext = path.substr(dot);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".obj" && ext != ".ply" && ext != ".glb")
    throw_usage("unknown output format '" + ext + "' (use .obj, .ply or .glb)");
  check_input(path, V, F, UV);
  if (ext == ".glb") {
    // One UV per vertex: the corners index it like the vertices.
    if (UV.rows() == 0) throw_usage(path + ": .glb output needs texture coordinates");
    write_glb(path, V, F, UV, F);
  } else if (ext == ".obj") write_obj(path, V, F, UV);
  else write_ply(path, V, F, UV, options.binary);
}

}  // namespace intrinsic
