#pragma once
// A progress bar with rate and ETA on stderr. Drawn only when enabled and stderr is a terminal;
// otherwise every call is a cheap no-op. Thread-safe: workers call advance() concurrently.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace prt {

class Progress {
 public:
  /// `label` is printed before the bar, `unit` after the rate (e.g. "vertices"), `total` > 0 items.
  /// The bar is drawn only if `enabled` and stderr is a terminal.
  Progress(std::string label, std::string unit, std::size_t total, bool enabled);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Records `n` more items done; redraws at most ten times a second.
  void advance(std::size_t n);
  /// Draws the final state and ends the line (also done by the destructor).
  void finish();
  bool active() const { return active_; }

 private:
  void draw(std::size_t done, bool final_line);

  std::string label_, unit_;
  std::size_t total_;
  bool active_;
  bool finished_ = false;
  std::atomic<std::size_t> done_{0};
  std::chrono::steady_clock::time_point start_;
  std::atomic<long long> last_draw_ns_{0};
  std::mutex draw_mutex_;
};

}  // namespace prt
