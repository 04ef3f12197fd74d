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
#include <memory>
#include <thread>
#include <vector>

#include "intrinsic/io.h"

namespace intrinsic {

namespace {

// One chunk of the file being formatted: a raw byte buffer written through a
// pointer. Each row first asks for room for its longest possible text (a
// shortest round-trip double is at most 24 characters), so the number
// formatting itself never checks for space; buffers are reused from chunk to
// chunk (fresh ones would cost a page fault per 4 KB).
class OutBuffer {
 public:
  // Room for `bytes` more; write from the returned pointer, then done(end).
  char* room(std::size_t bytes) {
    if (size_ + bytes > capacity_) grow(size_ + bytes);
    return data_.get() + size_;
  }
  void done(char* end) { size_ = static_cast<std::size_t>(end - data_.get()); }
  void clear() { size_ = 0; }
  const char* data() const { return data_.get(); }
  std::size_t size() const { return size_; }

  // Each call may be handed 32 bytes (24 are ever written).
  static char* num(char* p, double x) { return std::to_chars(p, p + 32, x).ptr; }
  static char* num(char* p, long long x) { return std::to_chars(p, p + 24, x).ptr; }
  template <class T>
  static char* raw_le(char* p, T x) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &x, sizeof(T));
    const std::uint16_t probe = 1;
    unsigned char first;
    std::memcpy(&first, &probe, 1);
    if (first != 1) std::reverse(b, b + sizeof(T));
    std::memcpy(p, b, sizeof(T));
    return p + sizeof(T);
  }

 private:
  void grow(std::size_t need) {
    const std::size_t cap = std::max(need, 2 * capacity_);
    std::unique_ptr<char[]> bigger(new char[cap]);
    if (size_ > 0) std::memcpy(bigger.get(), data_.get(), size_);
    data_ = std::move(bigger);
    capacity_ = cap;
  }

  std::unique_ptr<char[]> data_;
  std::size_t size_ = 0, capacity_ = 0;
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

// A file made of sections of rows (vertex lines, face lines, ...), each
// chunk of rows formatted independently.
struct Section {
  Eigen::Index rows;
  std::function<void(Eigen::Index begin, Eigen::Index end, OutBuffer& out)> format;
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
  auto format = [](const Chunk& c, OutBuffer out) {
    out.clear();
    c.section->format(c.begin, c.end, out);
    return out;
  };
  const bool threaded = chunks.size() > 2 && std::thread::hardware_concurrency() > 1;
  if (!threaded) {
    OutBuffer out;
    for (const Chunk& c : chunks) {
      out = format(c, std::move(out));
      sink(out.data(), out.size());
    }
    return;
  }
  // Two chunks formatting ahead of the one being written, each in a buffer
  // handed back once written (only this thread touches the spare list). A
  // future's destructor waits for its task, so an exception from the sink
  // leaves no thread running.
  constexpr std::size_t kAhead = 2;
  std::vector<OutBuffer> spare(kAhead + 1);
  std::deque<std::future<OutBuffer>> pending;
  std::size_t next = 0;
  auto launch = [&] {
    OutBuffer buffer = std::move(spare.back());
    spare.pop_back();
    pending.push_back(std::async(std::launch::async, format, std::cref(chunks[next++]), std::move(buffer)));
  };
  while (next < chunks.size() && pending.size() < kAhead) launch();
  while (!pending.empty()) {
    OutBuffer text = pending.front().get();
    pending.pop_front();
    if (next < chunks.size()) launch();
    sink(text.data(), text.size());
    spare.push_back(std::move(text));
  }
}

void write_obj(const std::string& path, const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV) {
  const bool uv = UV.rows() > 0;
  std::vector<Section> sections;
  sections.push_back({V.rows(), [&](Eigen::Index begin, Eigen::Index end, OutBuffer& o) {
                        for (Eigen::Index i = begin; i < end; ++i) {
                          char* p = o.room(112);
                          *p++ = 'v';
                          for (int k = 0; k < 3; ++k) {
                            *p++ = ' ';
                            p = OutBuffer::num(p, V(i, k));
                          }
                          *p++ = '\n';
                          o.done(p);
                        }
                      }});
  sections.push_back({UV.rows(), [&](Eigen::Index begin, Eigen::Index end, OutBuffer& o) {
                        for (Eigen::Index i = begin; i < end; ++i) {
                          char* p = o.room(64);
                          *p++ = 'v';
                          *p++ = 't';
                          for (int k = 0; k < 2; ++k) {
                            *p++ = ' ';
                            p = OutBuffer::num(p, UV(i, k));
                          }
                          *p++ = '\n';
                          o.done(p);
                        }
                      }});
  sections.push_back({F.rows(), [&](Eigen::Index begin, Eigen::Index end, OutBuffer& o) {
                        for (Eigen::Index f = begin; f < end; ++f) {
                          char* p = o.room(112);
                          *p++ = 'f';
                          for (int k = 0; k < 3; ++k) {
                            const long long idx = static_cast<long long>(F(f, k)) + 1;
                            *p++ = ' ';
                            char* const first = p;
                            p = OutBuffer::num(p, idx);
                            if (uv) {  // the same index again: one UV per vertex
                              const std::size_t digits = static_cast<std::size_t>(p - first);
                              *p++ = '/';
                              std::memcpy(p, first, digits);
                              p += digits;
                            }
                          }
                          *p++ = '\n';
                          o.done(p);
                        }
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
  // Room per row: the longest row plus the span each to_chars is given.
  const std::size_t vertex_bytes = binary ? 40 : 160, face_bytes = binary ? 13 : 64;
  sections.push_back({V.rows(), [&](Eigen::Index begin, Eigen::Index end, OutBuffer& o) {
                        for (Eigen::Index i = begin; i < end; ++i) {
                          char* p = o.room(vertex_bytes);
                          if (binary) {
                            for (int k = 0; k < 3; ++k) p = OutBuffer::raw_le(p, V(i, k));
                            if (uv) p = OutBuffer::raw_le(p, UV(i, 0)), p = OutBuffer::raw_le(p, UV(i, 1));
                          } else {
                            for (int k = 0; k < 3; ++k) {
                              if (k > 0) *p++ = ' ';
                              p = OutBuffer::num(p, V(i, k));
                            }
                            for (int k = 0; uv && k < 2; ++k) {
                              *p++ = ' ';
                              p = OutBuffer::num(p, UV(i, k));
                            }
                            *p++ = '\n';
                          }
                          o.done(p);
                        }
                      }});
  sections.push_back({F.rows(), [&](Eigen::Index begin, Eigen::Index end, OutBuffer& o) {
                        for (Eigen::Index f = begin; f < end; ++f) {
                          char* p = o.room(face_bytes);
                          if (binary) {
                            p = OutBuffer::raw_le(p, static_cast<std::uint8_t>(3));
                            for (int k = 0; k < 3; ++k) p = OutBuffer::raw_le(p, static_cast<std::int32_t>(F(f, k)));
                          } else {
                            *p++ = '3';
                            for (int k = 0; k < 3; ++k) {
                              *p++ = ' ';
                              p = OutBuffer::num(p, static_cast<long long>(F(f, k)));
                            }
                            *p++ = '\n';
                          }
                          o.done(p);
                        }
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
