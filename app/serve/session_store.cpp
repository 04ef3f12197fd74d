// Session lookup with a cap and least-recently-used eviction (session_store.h).
#include "serve/session_store.h"

namespace intrinsic::app {

std::shared_ptr<Session> SessionStore::get(const std::string& id) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = sessions_.find(id);
  if (it == sessions_.end()) {
    if (sessions_.size() >= capacity_) {
      auto oldest = sessions_.begin();
      for (auto e = sessions_.begin(); e != sessions_.end(); ++e)
        if (e->second.last_used < oldest->second.last_used) oldest = e;
      sessions_.erase(oldest);
    }
    it = sessions_.emplace(id, Entry{std::make_shared<Session>(mesh_), 0}).first;
  }
  it->second.last_used = ++clock_;
  return it->second.session;
}

size_t SessionStore::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return sessions_.size();
}

}  // namespace intrinsic::app
