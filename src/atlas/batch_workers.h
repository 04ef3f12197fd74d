// Worker threads kept for the whole merge (chart_merge.cpp), which solves
// its unions in a hundred or more small parallel batches (decimated-knight:
// 117 batches of 1-20 unions). A thread started per batch had to be
// scheduled and joined every time: on a loaded machine a new thread waits
// for a core, the calling thread waited for it at the join even when it
// had done every union itself, and the merge's wall time was twice its CPU
// time. Here the calling thread takes items like the workers, and waits
// only for items a worker has started: a worker that wakes late finds
// nothing left and sleeps again. Each item writes its own output, so
// nothing depends on which thread ran it.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace intrinsic::detail {

class BatchWorkers {
 public:
  // `threads` in all, the calling thread included (1: no worker threads).
  explicit BatchWorkers(int threads) {
    for (int t = 1; t < threads; ++t) workers_.emplace_back([this] { work(); });
  }
  ~BatchWorkers() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : workers_) t.join();
  }
  BatchWorkers(const BatchWorkers&) = delete;
  BatchWorkers& operator=(const BatchWorkers&) = delete;

  // Calls fn(i) once for every i in [0, n), in increasing order of claim;
  // returns when every call has returned.
  void run(std::int64_t n, const std::function<void(std::int64_t)>& fn) {
    if (n <= 0) return;
    Job job{n, &fn};
    if (n > 1 && !workers_.empty()) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        job_ = &job;
        ++generation_;
      }
      wake_.notify_all();
    }
    std::exception_ptr error;
    try {
      job.take();
    } catch (...) {  // the workers still hold `job`: wait for them first
      job.next = n;
      error = std::current_exception();
    }
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [this] { return busy_ == 0; });
    job_ = nullptr;
    if (!error) error = job.error;  // a worker's, kept under mutex_
    if (error) std::rethrow_exception(error);
  }

 private:
  struct Job {
    Job(std::int64_t count, const std::function<void(std::int64_t)>* f) : n(count), fn(f) {}
    std::int64_t n;
    const std::function<void(std::int64_t)>* fn;
    std::atomic<std::int64_t> next{0};
    std::exception_ptr error;  // the first item's exception a worker caught
    void take() {
      for (std::int64_t i; (i = next.fetch_add(1)) < n;) (*fn)(i);
    }
  };

  void work() {
    std::uint64_t seen = 0;
    std::unique_lock<std::mutex> lock(mutex_);
    while (true) {
      wake_.wait(lock, [&] { return stop_ || (job_ && generation_ != seen); });
      if (stop_) return;
      seen = generation_;
      Job* job = job_;
      ++busy_;
      lock.unlock();
      std::exception_ptr failure;
      try {
        job->take();
      } catch (...) {  // handed to the caller; the other items are skipped
        job->next = job->n;
        failure = std::current_exception();
      }
      lock.lock();
      if (failure && !job->error) job->error = failure;
      if (--busy_ == 0) idle_.notify_all();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_, idle_;
  Job* job_ = nullptr;
  std::uint64_t generation_ = 0;
  int busy_ = 0;
  bool stop_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace intrinsic::detail
