// The merge's kept worker threads (atlas/batch_workers.h): every item of
// every batch run exactly once, whatever the batch size and thread count,
// the calling thread back only when all are done, an item's exception
// passed on after the workers have let go of the batch, whichever thread
// ran it. (The atlas the same with 1, 2 and 3 threads: test_atlas_parts.cpp.)
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include "atlas/batch_workers.h"

namespace intrinsic::detail {
namespace {

TEST(MergeWorkers, EveryItemOnceInEveryBatch) {
  for (int threads : {1, 2, 4}) {
    BatchWorkers workers(threads);
    for (int batch = 0; batch < 200; ++batch) {
      const int n = batch % 23;
      std::vector<std::atomic<int>> calls(n);
      workers.run(n, [&](std::int64_t i) { calls[i].fetch_add(1); });
      // All done on return: read without waiting.
      for (int i = 0; i < n; ++i) ASSERT_EQ(calls[i].load(), 1) << threads << " threads, batch " << batch << ", item " << i;
    }
  }
}

TEST(MergeWorkers, AnItemsExceptionReachesTheCaller) {
  BatchWorkers workers(3);
  std::atomic<int> done{0};
  EXPECT_THROW(workers.run(50,
                           [&](std::int64_t i) {
                             if (i == 7) throw std::runtime_error("item 7");
                             done.fetch_add(1);
                           }),
               std::runtime_error);
  EXPECT_LE(done.load(), 49);
  // An item only a worker can take (the caller is held in item 0 until
  // another thread has passed item 1): its exception reaches the caller too.
  std::atomic<bool> passed{false};
  EXPECT_THROW(workers.run(2,
                           [&](std::int64_t i) {
                             if (i == 0) {
                               while (!passed.load()) std::this_thread::yield();
                               return;
                             }
                             passed = true;
                             throw std::runtime_error("item 1");
                           }),
               std::runtime_error);
  // The workers are still usable afterwards.
  std::atomic<int> calls{0};
  workers.run(40, [&](std::int64_t) { calls.fetch_add(1); });
  EXPECT_EQ(calls.load(), 40);
}

}  // namespace
}  // namespace intrinsic::detail
