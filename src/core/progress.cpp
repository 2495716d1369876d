#include "core/progress.h"

#include <cstdio>

#include <unistd.h>

namespace prt {

namespace {
std::string format_seconds(double s) {
  if (!(s >= 0) || s > 359999) return "?:??";  // unknown or beyond 99 hours
  int total = static_cast<int>(s + 0.5);
  char buf[32];
  if (total >= 3600)
    std::snprintf(buf, sizeof buf, "%d:%02d:%02d", total / 3600, (total / 60) % 60, total % 60);
  else
    std::snprintf(buf, sizeof buf, "%02d:%02d", total / 60, total % 60);
  return buf;
}

std::string format_rate(double r) {
  char buf[32];
  if (r >= 1e6)
    std::snprintf(buf, sizeof buf, "%.2fM", r / 1e6);
  else if (r >= 1e3)
    std::snprintf(buf, sizeof buf, "%.1fk", r / 1e3);
  else
    std::snprintf(buf, sizeof buf, "%.0f", r);
  return buf;
}
}  // namespace

Progress::Progress(std::string label, std::string unit, std::size_t total, bool enabled)
    : label_(std::move(label)), unit_(std::move(unit)), total_(total == 0 ? 1 : total),
      active_(enabled && isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { finish(); }

void Progress::advance(std::size_t n) {
  std::size_t done = done_.fetch_add(n) + n;
  if (!active_) return;
  auto now = std::chrono::steady_clock::now();
  long long ns = std::chrono::duration_cast<std::chrono::nanoseconds>(now - start_).count();
  long long last = last_draw_ns_.load(std::memory_order_relaxed);
  if (ns - last < 100000000LL) return;
  if (!last_draw_ns_.compare_exchange_strong(last, ns)) return;
  std::unique_lock<std::mutex> lock(draw_mutex_, std::try_to_lock);
  if (lock.owns_lock()) draw(done, false);
}

void Progress::finish() {
  if (!active_ || finished_) return;
  std::lock_guard<std::mutex> lock(draw_mutex_);
  finished_ = true;
  draw(done_.load(), true);
}

void Progress::draw(std::size_t done, bool final_line) {
  if (done > total_) done = total_;
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  double fraction = static_cast<double>(done) / static_cast<double>(total_);
  double rate = elapsed > 0 ? static_cast<double>(done) / elapsed : 0;
  double eta = rate > 0 ? static_cast<double>(total_ - done) / rate : -1;
  constexpr int kWidth = 30;
  int filled = static_cast<int>(fraction * kWidth);
  std::string bar(static_cast<std::size_t>(filled), '=');
  if (filled < kWidth) bar += '>';
  bar.resize(kWidth, ' ');
  std::fprintf(stderr, "\r%s [%s] %3d%% %s %s/s %s %s", label_.c_str(), bar.c_str(),
               static_cast<int>(fraction * 100), format_rate(rate).c_str(), unit_.c_str(),
               final_line ? "in" : "ETA", format_seconds(final_line ? elapsed : eta).c_str());
  if (final_line) std::fputc('\n', stderr);
  std::fflush(stderr);
}

}  // namespace prt
