#pragma once
// FNV-1a 64-bit hash over bytes: checksums and fingerprints in prt's files (docs/formats.md).
#include <cstddef>
#include <cstdint>

namespace prt {

inline constexpr std::uint64_t kFnvOffset = 14695981039346656037ull;
inline constexpr std::uint64_t kFnvPrime = 1099511628211ull;

/// FNV-1a 64 of `size` bytes, continuing from `hash` (start with kFnvOffset).
inline std::uint64_t fnv1a64(const void* data, std::size_t size, std::uint64_t hash = kFnvOffset) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= p[i];
    hash *= kFnvPrime;
  }
  return hash;
}

}  // namespace prt
