// `intrinsic serve` as a child process for the server tests (test_serve.cpp,
// test_serve_guard.cpp): started on a free port, its port and token read
// from the URL it prints, killed at the end of the test (also on failure);
// and a raw HTTP exchange over a socket, for requests no HTTP client writes
// (no Host header, truncated, chunked).
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace intrinsic::test {

// `intrinsic serve MESH --port 0 --max-sessions 4 EXTRA...` with stdout on a
// pipe (and stderr into `stderr_file` when given).
class ServerProcess {
 public:
  explicit ServerProcess(const std::string& mesh, const std::vector<std::string>& extra = {},
                         const std::string& stderr_file = "") {
    int fds[2];
    if (pipe(fds) != 0) return;
    std::vector<std::string> args = {INTRINSIC_CLI, "serve", mesh, "--port", "0", "--max-sessions", "4"};
    args.insert(args.end(), extra.begin(), extra.end());
    pid_ = fork();
    if (pid_ == 0) {
      dup2(fds[1], STDOUT_FILENO);
      close(fds[0]);
      close(fds[1]);
      if (!stderr_file.empty()) std::freopen(stderr_file.c_str(), "w", stderr);
      std::vector<char*> argv;
      for (std::string& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(INTRINSIC_CLI, argv.data());
      _exit(127);
    }
    close(fds[1]);
    read_url(fds[0]);
    close(fds[0]);
  }
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;
  ~ServerProcess() {
    if (pid_ <= 0) return;
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  int port() const { return port_; }
  const std::string& token() const { return token_; }
  // The path and query of the printed URL: "/?token=...".
  const std::string& page() const { return page_; }
  bool alive() const { return pid_ > 0 && waitpid(pid_, nullptr, WNOHANG) == 0; }
  // Resident memory (VmRSS of /proc/PID/status) in KiB; -1 when unknown.
  long rss_kib() const {
    std::ifstream status("/proc/" + std::to_string(pid_) + "/status");
    std::string line;
    while (std::getline(status, line))
      if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
    return -1;
  }

 private:
  // "... at http://127.0.0.1:PORT/?token=HEX".
  void read_url(int fd) {
    std::string line;
    char c;
    pollfd p{fd, POLLIN, 0};
    while (line.find('\n') == std::string::npos && poll(&p, 1, 60000) > 0 && read(fd, &c, 1) == 1) line += c;
    const std::string prefix = "http://127.0.0.1:";
    const size_t at = line.find(prefix);
    if (at == std::string::npos) return;
    port_ = std::atoi(line.c_str() + at + prefix.size());
    const size_t slash = line.find('/', at + prefix.size());
    const size_t end = line.find_first_of(" \r\n", at);
    if (slash != std::string::npos) page_ = line.substr(slash, end - slash);
    const size_t t = line.find("?token=", at);
    if (t != std::string::npos) token_ = line.substr(t + 7, end - t - 7);
  }
  pid_t pid_ = -1;
  int port_ = -1;
  std::string token_, page_;
};

struct RawReply {
  int status = -1;   // -1: no answer (connection failed, or closed without one)
  std::string text;  // what the server sent
  std::string body() const {
    const size_t at = text.find("\r\n\r\n");
    return at == std::string::npos ? "" : text.substr(at + 4);
  }
  // Headers and the whole Content-Length body received.
  bool complete() const {
    const size_t at = text.find("\r\n\r\n");
    if (at == std::string::npos) return false;
    const std::string head = text.substr(0, at);
    size_t length = 0;
    const size_t cl = head.find("\r\nContent-Length: ");
    if (cl != std::string::npos) length = std::strtoull(head.c_str() + cl + 18, nullptr, 10);
    return text.size() >= at + 4 + length;
  }
};

// How a raw request ends: the client closes its sending side (the server
// sees the end of the stream: cpp-httplib then answers nothing, the peer
// being gone), or it stays open (a stalled client: the server answers when
// its read timeout expires).
enum class RequestEnd { Close, Stall };

// Sends `bytes` to 127.0.0.1:port as they are and reads the first answer
// (until it is complete or the server closes).
inline RawReply raw_exchange(int port, const std::string& bytes, RequestEnd end = RequestEnd::Stall,
                             int timeout_s = 60) {
  RawReply r;
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return r;
  timeval tv{timeout_s, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0) {
    size_t sent = 0;
    while (sent < bytes.size()) {
      const ssize_t n = send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) break;  // the server may answer and close before reading a refused body
      sent += static_cast<size_t>(n);
    }
    if (end == RequestEnd::Close) shutdown(fd, SHUT_WR);
    char buf[65536];
    ssize_t n;
    while (!r.complete() && (n = recv(fd, buf, sizeof buf, 0)) > 0) r.text.append(buf, static_cast<size_t>(n));
    if (r.text.rfind("HTTP/1.1 ", 0) == 0) r.status = std::atoi(r.text.c_str() + 9);
  }
  close(fd);
  return r;
}

}  // namespace intrinsic::test
