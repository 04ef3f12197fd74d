// Atomic file replacement: readers of `path` see either the old file or the
// complete new one, never a partial write, and failures leave nothing behind.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

#include "intrinsic/io.h"

namespace intrinsic {

namespace {

// umask(2) can only be read by setting it, which would race with files other
// threads create meanwhile; Linux reports it in /proc instead.
mode_t process_umask() {
  mode_t mask = 022;
  if (FILE* f = std::fopen("/proc/self/status", "r")) {
    char line[256];
    while (std::fgets(line, sizeof line, f)) {
      unsigned m;
      if (std::sscanf(line, "Umask: %o", &m) == 1) {
        mask = static_cast<mode_t>(m);
        break;
      }
    }
    std::fclose(f);
  }
  return mask;
}

}  // namespace

void write_file_atomically(const std::string& path, const std::string& contents) {
  if (path.empty()) throw_output("cannot write a file with an empty name");
  const std::size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  if (base.empty()) throw_output("cannot write " + path + ": it names a directory");
  // The temporary file must be in the same directory: rename(2) is only
  // atomic within one file system.
  std::string tmpl = dir + "/." + base + ".tmp.XXXXXX";
  std::vector<char> buf(tmpl.begin(), tmpl.end());
  buf.push_back('\0');
  const int fd = ::mkstemp(buf.data());
  if (fd < 0) throw_output("cannot write " + path + ": " + std::strerror(errno));
  const std::string tmp(buf.data());

  auto fail = [&](int err) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw_output("cannot write " + path + ": " + std::strerror(err));
  };

  const char* p = contents.data();
  std::size_t left = contents.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(errno);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  // mkstemp creates the file private (0600); results are ordinary files, so
  // give them the permissions a plain open(..., 0666) would under the umask.
  if (::fchmod(fd, 0666 & ~process_umask()) != 0) fail(errno);
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw_output("cannot write " + path + ": " + std::strerror(err));
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw_output("cannot write " + path + ": " + std::strerror(err));
  }
}

}  // namespace intrinsic
