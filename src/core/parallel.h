#pragma once
// Deterministic parallel loops. Work is split into fixed chunks of `grain` items; threads claim chunks
// dynamically, so a body must write only to outputs indexed by its own items (never accumulate across
// chunks in claim order). Results are then identical for any thread count.
// The threads are a pool started on first use and kept until the process exits (no thread start per
// call); one call runs on the pool at a time, and a call made while it is busy (from inside a body, or
// from a second thread) runs its chunks on the calling thread alone, with the same results.
#include <cstddef>
#include <functional>

namespace prt {

/// Number of worker threads for a request: `requested` if > 0, else the hardware concurrency (>= 1).
int resolve_thread_count(int requested);

/// Calls body(begin, end) for consecutive chunks [begin, end) of [0, count), each of at most `grain`
/// (>= 1) items, on up to resolve_thread_count(threads) threads (the caller is one of them). Every worker runs
/// with flush-to-zero and denormals-are-zero set, so float results do not depend on which thread ran a
/// chunk. The first exception thrown by a body is rethrown after all workers stop.
void parallel_for(std::size_t count, std::size_t grain, int threads,
                  const std::function<void(std::size_t begin, std::size_t end)>& body);

/// Sets FTZ/DAZ on the calling thread and restores the previous mode when destroyed.
class ScopedFlushDenormals {
 public:
  ScopedFlushDenormals();
  ~ScopedFlushDenormals();
  ScopedFlushDenormals(const ScopedFlushDenormals&) = delete;
  ScopedFlushDenormals& operator=(const ScopedFlushDenormals&) = delete;

 private:
  unsigned int saved_;
};

}  // namespace prt
