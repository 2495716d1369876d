#include "core/memory_check.h"

#include <cstdio>
#include <limits>

#include <unistd.h>

#include "core/error.h"

namespace prt {

std::uint64_t physical_memory_bytes() {
  return std::uint64_t(sysconf(_SC_PHYS_PAGES)) * std::uint64_t(sysconf(_SC_PAGESIZE));
}

void check_memory_need(const std::string& field, const std::string& value, std::uint64_t need_bytes,
                       std::uint64_t available_bytes) {
  if (available_bytes == 0) available_bytes = physical_memory_bytes();
  if (need_bytes <= available_bytes / 10 * 8) return;
  const double gib = double(1ull << 30);
  char text[128];
  std::snprintf(text, sizeof text, ": needs about %.1f GiB, more than 80%% of this machine's %.1f GiB",
                double(need_bytes) / gib, double(available_bytes) / gib);
  fail_option(field, " " + value + text);
}

std::uint64_t saturating_product(std::uint64_t a, std::uint64_t b) {
  if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a) return std::numeric_limits<std::uint64_t>::max();
  return a * b;
}

}  // namespace prt
