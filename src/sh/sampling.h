#pragma once
// Deterministic, seedable sample sets and random numbers. The same (count, seed) always gives the same
// points on every machine and thread count.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace prt::sh {

/// Point `index` of the 2D Sobol (0,2)-sequence, Owen-scrambled with a hash keyed by `seed` (Burley
/// 2020, "Practical Hash-based Owen Scrambling"), in [0, 1)^2. Any prefix of length 2^k is stratified
/// in every elementary interval.
glm::dvec2 sobol_2d(std::uint32_t index, std::uint32_t seed);

/// `count` low-discrepancy directions uniform on the sphere (each stands for 4 pi / count sr).
std::vector<glm::dvec3> sphere_directions(std::size_t count, std::uint32_t seed);

/// `count` low-discrepancy directions on the hemisphere about +z, uniform in solid angle
/// (pdf 1 / (2 pi)).
std::vector<glm::dvec3> hemisphere_directions_uniform(std::size_t count, std::uint32_t seed);

/// `count` low-discrepancy directions on the hemisphere about +z with pdf cos(theta) / pi.
std::vector<glm::dvec3> hemisphere_directions_cosine(std::size_t count, std::uint32_t seed);

/// Maps a point of [0,1)^2 to the unit sphere (uniform) / hemisphere about +z (uniform / cosine).
glm::dvec3 square_to_sphere(const glm::dvec2& u);
glm::dvec3 square_to_hemisphere_uniform(const glm::dvec2& u);
glm::dvec3 square_to_hemisphere_cosine(const glm::dvec2& u);

/// Small counter-based random generator for Monte Carlo (PCG32). Independent streams come from
/// distinct (seed, stream) pairs, e.g. stream = vertex index, so results do not depend on threads.
class Rng {
 public:
  Rng(std::uint64_t seed, std::uint64_t stream);
  std::uint32_t next_u32();
  /// Uniform double in [0, 1).
  double next_double();

 private:
  std::uint64_t state_;
  std::uint64_t inc_;
};

}  // namespace prt::sh
