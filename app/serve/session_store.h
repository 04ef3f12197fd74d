// Sessions of `intrinsic serve` by id (the X-Session header or the
// `session` query parameter): each has its own EditSession and mutex, so
// two tabs never disturb each other. At most `capacity` sessions are kept;
// the least recently used one is dropped (a request still holding it
// finishes first: sessions are shared_ptr).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "intrinsic/edit_session.h"

namespace intrinsic::app {

// A running boundary optimization's energies so far, read by the progress
// endpoint while the optimization holds its request thread (own mutex: it
// never waits for the session's).
struct OptimizeProgress {
  std::mutex mutex;
  bool running = false;
  std::vector<double> energies;  // after each iteration
};

struct Session {
  explicit Session(const Mesh& mesh) : state(mesh) {}
  std::mutex mutex;
  EditSession state;
  OptimizeProgress progress;
};

class SessionStore {
 public:
  SessionStore(const Mesh& mesh, size_t capacity) : mesh_(mesh), capacity_(capacity) {}
  std::shared_ptr<Session> get(const std::string& id);
  size_t size() const;

 private:
  struct Entry {
    std::shared_ptr<Session> session;
    std::uint64_t last_used = 0;
  };
  const Mesh& mesh_;
  size_t capacity_;
  mutable std::mutex mutex_;
  std::map<std::string, Entry> sessions_;
  std::uint64_t clock_ = 0;
};

}  // namespace intrinsic::app
