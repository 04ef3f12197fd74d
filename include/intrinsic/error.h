// The project's single exception type. Every failure that reaches the API
// boundary is an intrinsic::Error carrying a message that names the problem
// and where it is (file, line, element), plus a category the command-line
// tool maps to its exit code (see docs/formats.md "Exit codes"), and, for a
// file that could not be opened, read or written, the errno of the failed
// system call (so a caller can tell a missing file from a malformed one
// without reading the message; the Python module raises FileNotFoundError or
// PermissionError from it).
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>

namespace intrinsic {

enum class ErrorKind {
  Usage = 1,      // bad options or arguments
  Input = 2,      // unreadable or malformed file, or a mesh we refuse
  Numerical = 3,  // singular system, non-finite result, residual too large
  Output = 4,     // the result could not be written
};

class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, const std::string& message, int os_error = 0)
      : std::runtime_error(message), kind_(kind), os_error_(os_error) {}
  ErrorKind kind() const { return kind_; }
  int exit_code() const { return static_cast<int>(kind_); }
  // ENOENT, EACCES, EISDIR, ...: the file system's reason when a file could
  // not be opened, read or written; 0 for every other failure.
  int os_error() const { return os_error_; }

 private:
  ErrorKind kind_;
  int os_error_;
};

// "1.5e-12", "0.25": numbers in messages (std::to_string prints 0.000000).
inline std::string short_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

[[noreturn]] inline void throw_usage(const std::string& m) { throw Error(ErrorKind::Usage, m); }
[[noreturn]] inline void throw_input(const std::string& m) { throw Error(ErrorKind::Input, m); }
[[noreturn]] inline void throw_numerical(const std::string& m) { throw Error(ErrorKind::Numerical, m); }
[[noreturn]] inline void throw_output(const std::string& m) { throw Error(ErrorKind::Output, m); }
// A file that could not be opened, read or written: `os_error` is the errno.
[[noreturn]] inline void throw_input_file(const std::string& m, int os_error) {
  throw Error(ErrorKind::Input, m, os_error);
}
[[noreturn]] inline void throw_output_file(const std::string& m, int os_error) {
  throw Error(ErrorKind::Output, m, os_error);
}

}  // namespace intrinsic
