#include "core/parallel.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include <xmmintrin.h>

namespace prt {

int resolve_thread_count(int requested) {
  if (requested > 0) return requested;
  unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

ScopedFlushDenormals::ScopedFlushDenormals() : saved_(_mm_getcsr()) {
  _mm_setcsr(saved_ | 0x8040u);  // FTZ (bit 15) | DAZ (bit 6)
}

ScopedFlushDenormals::~ScopedFlushDenormals() { _mm_setcsr(saved_); }

namespace {

// One parallel_for call: its chunks, claimed by the caller and the pool threads that join it.
struct Job {
  std::size_t count = 0, grain = 1, chunks = 0;
  const std::function<void(std::size_t, std::size_t)>* body = nullptr;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex error_mutex;
  std::exception_ptr first_error;

  void run() {
    for (;;) {
      if (stop.load(std::memory_order_relaxed)) return;
      const std::size_t chunk = next.fetch_add(1);
      if (chunk >= chunks) return;
      const std::size_t begin = chunk * grain;
      const std::size_t end = std::min(count, begin + grain);
      try {
        (*body)(begin, end);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
        stop.store(true);
      }
    }
  }
};

// Threads started once and kept for the life of the process; one job at a time. A parallel_for that
// finds the pool busy (a nested call from a body, or a second caller thread) runs its chunks on its
// own thread: the outputs are the same, since every chunk writes only its own items.
class Pool {
 public:
  ~Pool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      quit_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

  // Hands `job` to `helpers` pool threads (started if missing); false if the pool is busy.
  bool start(Job& job, std::size_t helpers) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (busy_ || quit_) return false;
    busy_ = true;
    while (threads_.size() < helpers) threads_.emplace_back([this, index = threads_.size()] { work(index); });
    job_ = &job;
    wanted_ = helpers;
    finished_ = 0;
    ++generation_;
    wake_.notify_all();
    return true;
  }

  // Waits until every helper of the current job has left it.
  void finish() {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return finished_ == wanted_; });
    job_ = nullptr;
    busy_ = false;
  }

 private:
  void work(std::size_t index) {
    ScopedFlushDenormals ftz;  // for the thread's whole life: it runs only parallel_for chunks
    std::uint64_t seen = 0;
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      wake_.wait(lock, [&] { return quit_ || (generation_ != seen && index < wanted_); });
      if (quit_) return;
      seen = generation_;
      Job* job = job_;
      lock.unlock();
      job->run();
      lock.lock();
      if (++finished_ == wanted_) done_.notify_one();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::vector<std::thread> threads_;
  Job* job_ = nullptr;
  std::uint64_t generation_ = 0;
  std::size_t wanted_ = 0, finished_ = 0;
  bool busy_ = false, quit_ = false;
};

Pool& pool() {
  static Pool instance;
  return instance;
}

}  // namespace

void parallel_for(std::size_t count, std::size_t grain, int threads,
                  const std::function<void(std::size_t, std::size_t)>& body) {
  if (count == 0) return;
  Job job;
  job.count = count;
  job.grain = std::max<std::size_t>(grain, 1);
  job.chunks = (count + job.grain - 1) / job.grain;
  job.body = &body;
  const std::size_t workers = std::min<std::size_t>(static_cast<std::size_t>(resolve_thread_count(threads)), job.chunks);
  const bool shared = workers > 1 && pool().start(job, workers - 1);
  {
    ScopedFlushDenormals ftz;
    job.run();
  }
  if (shared) pool().finish();
  if (job.first_error) std::rethrow_exception(job.first_error);
}

}  // namespace prt
