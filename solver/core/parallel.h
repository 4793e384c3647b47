// ParallelFor: the one place radflux uses threads. Work is split into blocks of
// consecutive indices; results must not depend on which thread runs which block.
#pragma once

#include <omp.h>

#include <algorithm>
#include <cstdint>

namespace radflux {

// Number of threads ParallelFor uses when asked for 0 ("all cores", or a ScopedThreadCount's).
inline int DefaultThreadCount() { return omp_get_max_threads(); }

// The threads ParallelFor(count, block, threads, body) runs on: ThreadIndex() is below it, so
// per-thread scratch sized by it is never indexed past its end.
inline int ThreadCount(int threads) { return threads > 0 ? threads : DefaultThreadCount(); }

// While it lives, ParallelFor(..., 0, ...) on the calling thread (and DefaultThreadCount)
// uses `threads` threads when threads > 0: a job's --threads then bounds every phase, the
// ones that take no thread count of their own too (the grouping's light probe, the picture's
// vertex fit). OpenMP keeps the count per thread, so jobs on other threads are not affected.
class ScopedThreadCount {
 public:
  explicit ScopedThreadCount(int threads) : previous_(omp_get_max_threads()) {
    if (threads > 0) omp_set_num_threads(threads);
  }
  ~ScopedThreadCount() { omp_set_num_threads(previous_); }
  ScopedThreadCount(const ScopedThreadCount&) = delete;
  ScopedThreadCount& operator=(const ScopedThreadCount&) = delete;

 private:
  int previous_;
};

// Calls body(begin, end) for consecutive blocks [begin, end) of [0, count), in parallel
// with `threads` threads (0 = all cores), dynamically scheduled.
template <typename Body>
void ParallelFor(int64_t count, int64_t block_size, int threads, Body&& body) {
  if (count <= 0) return;
  block_size = std::max<int64_t>(1, block_size);
  const int64_t blocks = (count + block_size - 1) / block_size;
  const int nthreads = ThreadCount(threads);
#pragma omp parallel for schedule(dynamic, 1) num_threads(nthreads) if (blocks > 1 && nthreads > 1)
  for (int64_t b = 0; b < blocks; ++b) {
    const int64_t begin = b * block_size;
    body(begin, std::min(count, begin + block_size));
  }
}

}  // namespace radflux

namespace radflux {
// Index of the calling thread inside ParallelFor, in [0, DefaultThreadCount()).
inline int ThreadIndex() { return omp_get_thread_num(); }
}  // namespace radflux
