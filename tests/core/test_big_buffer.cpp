#include <catch2/catch.hpp>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/big_buffer.h"

namespace {

// The kB of anonymous huge pages (/proc/self/smaps, AnonHugePages) of the mapping holding `address`;
// -1 where smaps cannot be read (not Linux).
long huge_kb_at(const void* address) {
  std::ifstream smaps("/proc/self/smaps");
  if (!smaps) return -1;
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  bool inside = false;
  std::string line;
  while (std::getline(smaps, line)) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-') {
      inside = lo <= a && a < hi;
    } else if (inside && line.rfind("AnonHugePages:", 0) == 0) {
      return std::stol(line.substr(14));
    }
  }
  return 0;
}

bool huge_pages_on_advice() {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string text;
  std::getline(f, text);
  return text.find("[madvise]") != std::string::npos || text.find("[always]") != std::string::npos;
}

}  // namespace

TEST_CASE("assign_big and copy_big hold what assign and copy hold, above and below the size that is advised", "[core]") {
  for (std::size_t count : {std::size_t(0), std::size_t(1000), std::size_t(3) << 20, (std::size_t(3) << 20) + 7}) {
    std::vector<float> v(5, 2.0f);
    prt::assign_big(v, count, 1.5f);
    REQUIRE(v.size() == count);
    for (float x : v) REQUIRE(x == 1.5f);
    for (std::size_t k = 0; k < count; ++k) v[k] = float(k % 977) - 3.0f;
    const std::vector<float> copy = prt::copy_big(v);
    REQUIRE(copy == v);
    // Enough capacity already: the storage is reused.
    const float* before = v.data();
    prt::assign_big(v, count / 2, -1.0f);
    REQUIRE(v.data() == before);
    REQUIRE(v.size() == count / 2);
    for (float x : v) REQUIRE(x == -1.0f);
  }
  // Unaligned, small and null ranges are advice that does nothing.
  std::vector<char> small(100);
  prt::advise_huge_pages(small.data() + 1, small.size() - 1);
  prt::advise_huge_pages(nullptr, std::size_t(64) << 20);
}

TEST_CASE("assign_big's storage gets huge pages where the kernel gives them on advice", "[core]") {
  if (!huge_pages_on_advice()) SUCCEED("transparent huge pages off: nothing to check");
  else {
    std::vector<float> v;
    prt::assign_big(v, std::size_t(16) << 20, 0.0f);  // 64 MiB
    const long kb = huge_kb_at(v.data() + v.size() / 2);
    INFO("AnonHugePages of the buffer's mapping: " << kb << " kB");
    if (kb >= 0) CHECK(kb >= 2048);
  }
}
