// Who runs in parallel while a sparse factorization runs. The
// solver libraries each assume the whole machine: OpenBLAS starts a thread
// per core for every BLAS call, and Debian's CHOLMOD opens OpenMP teams of 4
// threads per supernode (a compiled-in num_threads clause). Idle threads of
// each spin while the other library works, so on 2 cores they take turns
// stealing each other's core: a 1M-vertex factorization took 10.4 s as a
// user starts it and 3.8 s with one BLAS thread. The library therefore sets
// one level of parallelism itself, through the libraries' APIs rather than
// environment variables the user may or may not have set.
//
// While a SolverThreads is alive: OpenMP teams are dynamic (the runtime may
// shrink CHOLMOD's teams to the idle cores) and OpenBLAS runs on one thread,
// because between the many small BLAS calls of a supernodal factorization
// its spinning workers cost more than they give (measured in
// docs/performance.md#threads). The settings are process-wide in the
// libraries, so the first live scope saves them and the last restores
// them: nested and concurrent scopes (two Parameterizers in two threads) are
// safe. UMFPACK
// (no OpenMP) runs in a scope too: on a loaded machine (load 5, 2 cores) its
// 1M-vertex authalic factorization took 22 s with OpenBLAS's threads, 6.9 s
// of it system time spent spinning, and 11 s with one.
#pragma once

namespace intrinsic::detail {

class SolverThreads {
 public:
  SolverThreads();
  ~SolverThreads();
  SolverThreads(const SolverThreads&) = delete;
  SolverThreads& operator=(const SolverThreads&) = delete;

 private:
  int previous_dynamic_ = 0;
};

}  // namespace intrinsic::detail
