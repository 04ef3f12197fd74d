// Atomic file replacement: readers of `path` see either the old file or the
// complete new one, never a partial write, and failures leave nothing behind.
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
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

// Temporary files being written, for the signal handler: fixed storage and
// atomic flags only, since a handler may use nothing else. A path that does
// not fit (or more concurrent writes than slots) is simply not tracked.
constexpr int kSlots = 16;
constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};
std::atomic<bool> g_slot_taken[kSlots];
std::atomic<bool> g_slot_live[kSlots];
char g_slot_path[kSlots][PATH_MAX];

int track_temporary(const std::string& tmp) {
  if (tmp.size() >= PATH_MAX) return -1;
  for (int i = 0; i < kSlots; ++i) {
    bool expected = false;
    if (g_slot_taken[i].compare_exchange_strong(expected, true)) {
      std::memcpy(g_slot_path[i], tmp.c_str(), tmp.size() + 1);
      g_slot_live[i].store(true);
      return i;
    }
  }
  return -1;
}

void untrack_temporary(int slot) {
  if (slot < 0) return;
  g_slot_live[slot].store(false);
  g_slot_taken[slot].store(false);
}

extern "C" void remove_temporaries_and_reraise(int sig) {
  for (int i = 0; i < kSlots; ++i)
    if (g_slot_live[i].load()) ::unlink(g_slot_path[i]);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

// Untracks the temporary file when the write finishes, however it finishes.
struct TrackedTemporary {
  int slot;
  ~TrackedTemporary() { untrack_temporary(slot); }
};

}  // namespace

void remove_temporary_files_on_signals() {
  for (int sig : kCleanupSignals) {
    struct sigaction sa {};
    sa.sa_handler = remove_temporaries_and_reraise;
    sigemptyset(&sa.sa_mask);
    struct sigaction old {};
    // A signal the caller's parent ignores (nohup) stays ignored.
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    ::sigaction(sig, &sa, nullptr);
  }
  // With a file size limit (ulimit -f), exceeding it must fail the write with
  // EFBIG (reported, temporary removed), not kill the process.
  std::signal(SIGXFSZ, SIG_IGN);
}

void write_file_atomically(const std::string& path, const std::string& contents) {
  write_file_atomically(path, [&](const ByteSink& sink) { sink(contents.data(), contents.size()); });
}

void write_file_atomically(const std::string& path, const std::function<void(const ByteSink&)>& produce) {
  if (path.empty()) throw_output("cannot write a file with an empty name");
  const std::size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  if (base.empty()) throw_output_file("cannot write " + path + ": it names a directory", EISDIR);
  // The temporary file must be in the same directory: rename(2) is only
  // atomic within one file system.
  std::string tmpl = dir + "/." + base + ".tmp.XXXXXX";
  std::vector<char> buf(tmpl.begin(), tmpl.end());
  buf.push_back('\0');
  // The cleanup signals wait while the file is created and tracked, so that
  // none can land between the two and leave it behind.
  sigset_t cleanup_signals, previous;
  sigemptyset(&cleanup_signals);
  for (int sig : kCleanupSignals) sigaddset(&cleanup_signals, sig);
  ::pthread_sigmask(SIG_BLOCK, &cleanup_signals, &previous);
  const int fd = ::mkstemp(buf.data());
  const int mkstemp_errno = errno;
  const std::string tmp(fd >= 0 ? buf.data() : "");
  const TrackedTemporary tracked{fd >= 0 ? track_temporary(tmp) : -1};
  ::pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  if (fd < 0) throw_output_file("cannot write " + path + ": " + std::strerror(mkstemp_errno), mkstemp_errno);

  bool removed = false;
  auto fail = [&](int err) {
    ::close(fd);
    ::unlink(tmp.c_str());
    removed = true;
    throw_output_file("cannot write " + path + ": " + std::strerror(err), err);
  };

  auto sink = [&](const char* p, std::size_t left) {
    while (left > 0) {
      const ssize_t n = ::write(fd, p, left);
      if (n < 0) {
        if (errno == EINTR) continue;
        fail(errno);
      }
      p += n;
      left -= static_cast<std::size_t>(n);
    }
  };
  try {
    produce(sink);
  } catch (...) {
    if (!removed) {  // a failed write has already cleaned up
      ::close(fd);
      ::unlink(tmp.c_str());
    }
    throw;
  }
  // mkstemp creates the file private (0600); results are ordinary files, so
  // give them the permissions a plain open(..., 0666) would under the umask.
  if (::fchmod(fd, 0666 & ~process_umask()) != 0) fail(errno);
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw_output_file("cannot write " + path + ": " + std::strerror(err), err);
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw_output_file("cannot write " + path + ": " + std::strerror(err), err);
  }
}

void write_all(const std::vector<std::pair<std::string, std::string>>& files,
               const std::vector<std::string>& written_before) {
  std::vector<std::string> written = written_before;
  try {
    for (const auto& [path, bytes] : files) {
      write_file_atomically(path, bytes);
      written.push_back(path);
    }
  } catch (...) {
    std::error_code ec;
    for (const std::string& path : written) std::filesystem::remove(path, ec);
    throw;
  }
}

}  // namespace intrinsic
