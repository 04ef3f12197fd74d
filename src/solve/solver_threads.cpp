// One level of parallelism during sparse factorizations (see
// solver_threads.h).
#include "solve/solver_threads.h"

#include <mutex>

extern "C" {
#ifdef INTRINSIC_HAVE_OPENMP_RUNTIME
int omp_get_dynamic(void);
void omp_set_dynamic(int);
#endif
#ifdef INTRINSIC_HAVE_OPENBLAS
int openblas_get_num_threads(void);
void openblas_set_num_threads(int);
#endif
}

namespace intrinsic::detail {
namespace {

// The libraries' settings are process-wide, so the scopes that change them
// share one count (the only mutable state of the library outside its
// objects, and it mirrors state that is global in those libraries already).
struct Saved {
  std::mutex mutex;
  int live = 0;
  int blas_threads = 1;
};

Saved& saved() {
  static Saved s;
  return s;
}

}  // namespace

// OpenMP's dynamic flag belongs to the calling thread: each scope sets and
// restores its own. OpenBLAS's thread count is global: counted.
SolverThreads::SolverThreads() {
#ifdef INTRINSIC_HAVE_OPENMP_RUNTIME
  previous_dynamic_ = omp_get_dynamic();
  omp_set_dynamic(1);
#endif
  Saved& s = saved();
  std::lock_guard<std::mutex> lock(s.mutex);
  if (s.live++ > 0) return;
#ifdef INTRINSIC_HAVE_OPENBLAS
  // Set only when it differs: OpenBLAS restarts a stopped thread pool on
  // every call, even for one thread, and each new worker spins for about
  // 0.1 s (the command-line tool stops the pool at start: app/main.cpp).
  s.blas_threads = openblas_get_num_threads();
  if (s.blas_threads != 1) openblas_set_num_threads(1);
#endif
}

SolverThreads::~SolverThreads() {
#ifdef INTRINSIC_HAVE_OPENMP_RUNTIME
  omp_set_dynamic(previous_dynamic_);
#endif
  Saved& s = saved();
  std::lock_guard<std::mutex> lock(s.mutex);
  if (--s.live > 0) return;
#ifdef INTRINSIC_HAVE_OPENBLAS
  if (s.blas_threads != 1) openblas_set_num_threads(s.blas_threads);
#endif
}

}  // namespace intrinsic::detail
