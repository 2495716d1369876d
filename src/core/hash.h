#pragma once
// The integer hashes every module uses for seeds, scrambles and per-item rotations. Deterministic on
// every machine: integer arithmetic only, and a fixed map to doubles.
#include <cstdint>

namespace prt {

/// 64-bit finaliser of SplitMix64 (Steele, Lea, Flood 2014, "Fast splittable pseudorandom number
/// generators"; Stafford's "Mix13" constants): a bijection that spreads every input bit over all 64.
inline std::uint64_t mix64(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

/// 32-bit finaliser of MurmurHash3 (Appleby): a bijection that spreads small, consecutive seeds over
/// all 32 bits.
inline std::uint32_t mix32(std::uint32_t h) {
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return h;
}

/// A hash of (seed, index, salt) to [0, 1) (53 bits): per-vertex and per-probe rotation angles and
/// scrambles. Different salts give independent-looking values for the same (seed, index).
inline double hash_to_unit(std::uint32_t seed, std::uint64_t index, std::uint32_t salt) {
  const std::uint64_t h = mix64(mix64(index + 0x9e3779b97f4a7c15ull * (seed + 1ull)) ^ (static_cast<std::uint64_t>(salt) << 32));
  return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0);
}

/// A hash of (seed, index, salt) to 32 bits (an Owen-scrambling key, say).
inline std::uint32_t hash_to_u32(std::uint32_t seed, std::uint64_t index, std::uint32_t salt) {
  return static_cast<std::uint32_t>(hash_to_unit(seed, index, salt) * 4294967296.0);
}

}  // namespace prt
