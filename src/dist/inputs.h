#pragma once
// Checking that every rank of a job works on the same inputs (docs/distributed.md): each rank hashes
// what it read (mesh, environment, options) and the ranks compare. A rank that read a different file
// (another machine's copy, another version) would otherwise bake a silently wrong part of the output.
#include <cstdint>
#include <string>
#include <vector>

#include "dist/context.h"

namespace prt::dist {

/// One input's 64-bit fingerprint. `name` says what it is in messages: a file path, or "the options".
struct Fingerprint {
  std::string name;
  std::uint64_t value = 0;
};

/// FNV-1a 64 of a string (for canonical option strings and whole files).
std::uint64_t fingerprint_of(const std::string& bytes);

/// Collective: compares every rank's `inputs` (same names in the same order on every rank). On any
/// difference every rank throws the same CollectiveError,
///   "<name>: differs between ranks (rank 0: 0x..., rank R: 0x...); every rank must read the same inputs with the same options",
/// for the first input that differs and the lowest rank that differs from rank 0. A no-op on one rank.
void check_same_inputs(const Context& context, const std::vector<Fingerprint>& inputs);

}  // namespace prt::dist
