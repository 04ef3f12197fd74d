// How the supernodal factorizations and solves share the cores (internal).
//
// A nested-dissection ordering makes the supernodal elimination tree split
// at each separator into subtrees that touch disjoint parts of the factor:
// the subtrees below the top separators are independent tasks, and the top
// separators (where most flops of a 2D mesh are: the dense blocks of the
// largest separators) are then factored one after the other, each split in
// column blocks between the threads. The split depends only on the tree and
// its costs, never on the thread count or timing, and each supernode applies
// its updates in a fixed order, so results are bit-identical whatever the
// number of threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "solve/suitesparse.h"

namespace intrinsic::detail {

// Column blocks of a supernode with nscol columns (the supernodal Cholesky
// and LU alike): about 128 wide, so a top separator of 2000 columns gives the
// threads 15 blocks to share; narrower supernodes stay whole. A function of
// nscol only, and every supernode is blocked the same way whatever runs it,
// so the BLAS calls (and their results) do not depend on the threads.
inline int column_blocks(int nscol) { return std::max(1, nscol / 128); }
inline int block_start(int nscol, int b) {
  return static_cast<int>(static_cast<std::int64_t>(nscol) * b / column_blocks(nscol));
}

// Supernodes with fewer flops run on one thread even at the top: a thread
// costs tens of microseconds.
constexpr double kParallelFlops = 2e6;

struct SupernodalSchedule {
  // Independent subtrees, as ranges [first, last] of the (postordered)
  // supernodes, the costliest first.
  std::vector<std::pair<int, int>> subtrees;
  std::vector<int> top;  // the supernodes above them, ascending (children first)
};

// For each supernode s, the descendants d whose rows reach s's columns, in
// ascending d (the fixed order of s's updates), with the position of d's
// first row among s's columns: entries [start[s], start[s + 1]).
struct DescendantLists {
  std::vector<std::int64_t> start;
  std::vector<int> d, p;
};
DescendantLists descendant_lists(const SupernodalSymbolic& S);

// Splits the tree (cost[s]: supernode s's own work) until no subtree holds
// more than 1/16 of the total, or a subtree is a single supernode.
SupernodalSchedule subtree_schedule(const SupernodalSymbolic& S, const std::vector<double>& cost);

// The machine's cores (at least 1, at most 8): the factorizations' default.
int hardware_threads();

// Calls fn(task, worker) for task = 0 .. ntasks-1, taken in order by up to
// `threads` workers (worker 0 is the calling thread). The first exception a
// task throws is rethrown here once every worker has stopped.
template <class Fn>
void run_tasks(int ntasks, int threads, Fn&& fn) {
  if (threads <= 1 || ntasks <= 1) {
    for (int t = 0; t < ntasks; ++t) fn(t, 0);
    return;
  }
  std::atomic<int> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto work = [&](int worker) {
    for (int t = next++; t < ntasks; t = next++) {
      try {
        fn(t, worker);
      } catch (...) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = ntasks;
      }
    }
  };
  std::vector<std::thread> helpers;
  const int workers = std::min(threads, ntasks);
  for (int w = 1; w < workers; ++w) helpers.emplace_back(work, w);
  work(0);
  for (std::thread& h : helpers) h.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace intrinsic::detail
