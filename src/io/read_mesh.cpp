// Entry points for reading: load the file in one read, undo gzip if the bytes
// say so, and hand the buffer to the reader chosen by the file extension:
// ours for OBJ, OFF, PLY, STL and glTF, assimp for any other extension it
// imports; a name whose extension says nothing gets the format its bytes show.
// Every reader gives a MeshFile; read_mesh keeps its geometry.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "intrinsic/io.h"
#include "io/assimp_reader.h"
#include "io/gltf_document.h"
#include "io/gzip.h"
#include "io/mesh_builder.h"

namespace intrinsic {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string extension_of(const std::string& name) {
  const std::size_t slash = name.find_last_of('/');
  const std::size_t dot = name.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  return lower(name.substr(dot));
}

// The format named by a file name ("a.stl.gz" -> ".stl").
std::string format_of(const std::string& name) {
  const std::string ext = extension_of(name);
  return ext == ".gz" ? extension_of(name.substr(0, name.size() - 3)) : ext;
}

// Large enough for any mesh the options admit (a text vertex or face line
// rarely exceeds ~100 bytes; an ASCII STL facet, which spells out its three
// corners on seven lines, ~300), small enough that a bomb cannot take the
// machine.
std::uint64_t inflate_cap(const ReadOptions& opt, const std::string& format) {
  const std::uint64_t cap = 8ull << 30;
  const std::uint64_t nv = static_cast<std::uint64_t>(std::max<std::int64_t>(opt.max_vertices, 0));
  const std::uint64_t nf = static_cast<std::uint64_t>(std::max<std::int64_t>(opt.max_faces, 0));
  const std::uint64_t derived = format == ".stl" ? nf * 400 + (1ull << 20) : nv * 128 + nf * 128 + (1ull << 20);
  return std::min(cap, derived);
}

std::string unknown_format(const std::string& ext, const std::string& name) {
  std::string others;
  for (const io::AssimpExtension& e : io::assimp_extensions()) others += " " + e.extension;
  return "unknown input format '" + ext + "' for " + name +
         " (use .obj, .off, .ply, .stl, .gltf or .glb, optionally .gz, or one assimp reads:" + others +
         "; `intrinsic formats` lists them)";
}

bool is_ours(const std::string& ext) {
  return ext == ".obj" || ext == ".off" || ext == ".ply" || ext == ".stl" || ext == ".gltf" || ext == ".glb";
}

// The format of a file whose name says nothing, from its first bytes: glb's
// magic, glTF's JSON, PLY's and OFF's headers, ASCII STL's "solid ... facet",
// a binary STL's size (84 bytes + 50 per announced triangle), OBJ's v and f
// lines. "" when none fits.
std::string sniff_format(const std::string& b) {
  const std::string head = b.substr(0, 4096);
  auto starts = [&head](const char* s) { return head.rfind(s, 0) == 0; };
  if (starts("glTF")) return ".glb";
  const std::size_t first = head.find_first_not_of(" \t\r\n\xEF\xBB\xBF");
  if (first != std::string::npos && head[first] == '{' && head.find("\"asset\"") != std::string::npos) return ".gltf";
  if (starts("ply\n") || starts("ply\r\n")) return ".ply";
  const std::string word = head.substr(0, head.find_first_of(" \t\r\n"));
  if (word.size() >= 3 && word.size() <= 6 && word.compare(word.size() - 3, 3, "OFF") == 0) return ".off";
  if (starts("solid") && head.find("facet") != std::string::npos) return ".stl";
  if (b.size() >= 84) {
    std::uint32_t n = 0;
    std::memcpy(&n, b.data() + 80, 4);
    if (b.size() == 84 + 50 * static_cast<std::uint64_t>(n)) return ".stl";
  }
  if ((head.find("\nv ") != std::string::npos || starts("v ")) && b.find("\nf ") != std::string::npos) return ".obj";
  return "";
}

// `files_allowed`: a glTF document may read buffer files beside `name`
// (only when `name` is a file that was read, not bytes handed over).
MeshFile read_bytes(const std::string& bytes, const std::string& name, const ReadOptions& options,
                    bool files_allowed) {
  std::string ext = format_of(name);
  const bool known = is_ours(ext) || io::assimp_reads(ext);
  std::string inflated;
  const std::string* data = &bytes;
  if (io::is_gzip(bytes)) {
    inflated = io::gunzip(bytes, name, inflate_cap(options, ext));
    data = &inflated;
  }
  if (!known) {
    const std::string sniffed = sniff_format(*data);
    if (sniffed.empty() && ext.empty())
      throw_usage("cannot tell the format of " + name +
                  ": it has no extension and its bytes look like none of OBJ, OFF, PLY, STL, glTF, glb "
                  "(name it with the format's extension)");
    if (sniffed.empty()) throw_usage(unknown_format(ext, name) + "; nor do its bytes look like one of ours");
    ext = sniffed;
  }
  const bool ours = is_ours(ext);
  // assimp opens a file itself when it can (some formats name companion
  // files beside it); decompressed or in-memory bytes are handed over.
  if (!ours) return io::read_assimp(*data, name, ext, options, files_allowed && data == &bytes);
  if (ext == ".gltf" || ext == ".glb") return io::read_gltf(*data, name, options, files_allowed);
  // (Each reader below checks the bytes itself; a sniffed format is no looser.)
  const char* begin = data->data();
  std::size_t size = data->size();
  // Editors on Windows may prepend a UTF-8 byte order mark; left in place it
  // would hide the first statement of the file. (PLY and STL may be binary:
  // those bytes could be data; the STL reader looks for it itself.)
  if (ext != ".ply" && ext != ".stl" && size >= 3 && std::memcmp(begin, "\xEF\xBB\xBF", 3) == 0) {
    begin += 3;
    size -= 3;
  }
  if (ext == ".obj") return io::read_obj(begin, size, name, options);
  // OFF, STL and PLY carry nothing the writers give back.
  if (ext == ".off") return {io::read_off(begin, size, name, options), {}};
  if (ext == ".stl") return {io::read_stl(begin, size, name, options), {}};
  return {io::read_ply(data->data(), data->size(), name, options), {}};
}

}  // namespace

MeshFile read_mesh_file_from_memory(const std::string& bytes, const std::string& name, const ReadOptions& options) {
  return read_bytes(bytes, name, options, false);
}

MeshData read_mesh_from_memory(const std::string& bytes, const std::string& name, const ReadOptions& options) {
  return read_mesh_file_from_memory(bytes, name, options).mesh;
}

MeshFile read_mesh_file(const std::string& path, const ReadOptions& options) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;  // before anything else can change it
    throw_input_file("cannot open " + path + ": " + std::strerror(err), err);
  }
  std::string bytes;
  try {
    struct stat st {};
    if (::fstat(fd, &st) != 0) {
      const int err = errno;
      throw_input_file("cannot read " + path + ": " + std::strerror(err), err);
    }
    if (S_ISDIR(st.st_mode)) throw_input_file("cannot read " + path + ": it is a directory", EISDIR);
    // A file larger than any mesh within the limits could be (the same bound
    // as for inflated gzip data) is refused before it is read into memory.
    const std::uint64_t max_bytes = inflate_cap(options, format_of(path));
    auto too_big = [&] {
      char mib[32];
      std::snprintf(mib, sizeof mib, "%.1f MiB", static_cast<double>(max_bytes) / (1 << 20));
      throw_input(path + ": the file is larger than " + mib + ", the most a mesh within the limits (" +
                  std::to_string(options.max_vertices) + " vertices, " + std::to_string(options.max_faces) +
                  " faces) can take");
    };
    if (S_ISREG(st.st_mode) && static_cast<std::uint64_t>(st.st_size) > max_bytes) too_big();
    // One read of the announced size; pipes and growing files fall back to
    // reading in chunks until EOF.
    std::size_t have = 0;
    bytes.resize(S_ISREG(st.st_mode) ? static_cast<std::size_t>(st.st_size) + 1 : (1u << 20));
    while (true) {
      if (have == bytes.size()) {
        if (have > max_bytes) too_big();
        bytes.resize(bytes.size() * 2);
      }
      const ssize_t n = ::read(fd, &bytes[have], bytes.size() - have);
      if (n < 0) {
        const int err = errno;
        if (err == EINTR) continue;
        throw_input_file("cannot read " + path + ": " + std::strerror(err), err);
      }
      if (n == 0) break;
      have += static_cast<std::size_t>(n);
    }
    bytes.resize(have);
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  return read_bytes(bytes, path, options, true);
}

MeshData read_mesh(const std::string& path, const ReadOptions& options) {
  return read_mesh_file(path, options).mesh;
}

// How the command line, Python and the reports spell these (intrinsic/choice.h).
template <>
ChoiceTable<InstanceMode> choice_table<InstanceMode>() {
  static const Choice<InstanceMode> rows[] = {{InstanceMode::Shared, "shared"}, {InstanceMode::Unique, "unique"}};
  return make_choice_table(rows);
}

}  // namespace intrinsic
