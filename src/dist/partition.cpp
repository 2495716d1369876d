#include "dist/partition.h"

#include "core/error.h"

namespace prt::dist {

Range partition(std::size_t count, int ranks, int rank) {
  if (ranks < 1 || rank < 0 || rank >= ranks) fail("dist: rank " + std::to_string(rank) + " of " + std::to_string(ranks));
  // 128-bit free: count * rank fits in 64 bits for any count below 2^48 and ranks below 2^16.
  const auto bound = [&](int r) { return static_cast<std::size_t>(static_cast<unsigned long long>(count) * r / ranks); };
  return Range{bound(rank), bound(rank + 1)};
}

std::vector<Range> partitions(std::size_t count, int ranks) {
  std::vector<Range> out;
  for (int r = 0; r < ranks; ++r) out.push_back(partition(count, ranks, r));
  return out;
}

}  // namespace prt::dist
