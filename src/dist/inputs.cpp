#include "dist/inputs.h"

#include <cstdio>

#include "core/fnv.h"

namespace prt::dist {

std::uint64_t fingerprint_of(const std::string& bytes) { return fnv1a64(bytes.data(), bytes.size()); }

namespace {

std::string hex(std::uint64_t v) {
  char text[24];
  std::snprintf(text, sizeof text, "0x%016llx", static_cast<unsigned long long>(v));
  return text;
}

}  // namespace

void check_same_inputs(const Context& context, const std::vector<Fingerprint>& inputs) {
  if (context.size() == 1) return;
  const std::size_t n = inputs.size();
  // The counts first: ranks running different commands send different numbers of fingerprints.
  const std::vector<std::uint64_t> counts = context.allgather_u64({n});
  for (std::size_t r = 1; r < counts.size(); ++r)
    if (counts[r] != counts[0])
      throw CollectiveError("the ranks of this job run different commands (rank " + std::to_string(r) +
                            " has " + std::to_string(counts[r]) + " inputs, rank 0 " + std::to_string(counts[0]) + ")");
  std::vector<std::uint64_t> mine;
  for (const Fingerprint& f : inputs) mine.push_back(f.value);
  const std::vector<std::uint64_t> all = context.allgather_u64(mine);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t r = 1; r < all.size() / n; ++r)
      if (all[r * n + i] != all[i])
        throw CollectiveError(inputs[i].name + ": differs between ranks (rank 0: " + hex(all[i]) + ", rank " +
                              std::to_string(r) + ": " + hex(all[r * n + i]) +
                              "); every rank must read the same inputs with the same options");
}

}  // namespace prt::dist
