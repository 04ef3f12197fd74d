// Atomic file replacement: readers of `path` see either the old file or the
// complete new one, never a partial write, and failures leave nothing behind.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "intrinsic/io.h"

namespace intrinsic {

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
  const mode_t mask = ::umask(0);
  ::umask(mask);
  if (::fchmod(fd, 0666 & ~mask) != 0) fail(errno);
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
