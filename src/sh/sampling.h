#pragma once
// Deterministic, seedable sample sets and random numbers. The same (count, seed) always gives the same
// points on every machine and thread count (integer hashing only; the maps to directions use
// sqrt, sin, cos of the same inputs).
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/constants.h"

namespace prt::sh {

/// Point `index` of the 2D Sobol (0,2)-sequence (dimension 0: van der Corput, dimension 1: Sobol's
/// second dimension, primitive polynomial x + 1), shuffled and Owen-scrambled with hashes keyed by
/// `seed` (Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4): the index is scrambled by
/// a nested uniform scramble, then each coordinate by its own one, each a Laine-Karras permutation
/// of the reversed bits). Coordinates are (k + 1/2) / 2^32 for 32-bit integers k: strictly inside
/// (0, 1). Any prefix of length 2^k (k <= 32) is a (0,k,2)-net: every elementary interval
/// [a/2^i, (a+1)/2^i) x [b/2^j, (b+1)/2^j) with i + j = k holds exactly one point. So is every aligned
/// block of indices [m 2^k, (m + 1) 2^k): bit i of the scrambled index depends only on the index's bits
/// >= i, so the scramble maps aligned blocks onto aligned blocks of the (0,2)-sequence (the interleaved
/// sample sets of bake/vertex_samples.h rely on it).
/// Different seeds give independent-looking randomisations of the same net structure.
glm::dvec2 sobol_2d(std::uint32_t index, std::uint32_t seed);

/// `count` low-discrepancy directions uniform on the sphere: square_to_sphere(sobol_2d(i, seed)),
/// i < count (pdf 1 / (4 pi); each stands for 4 pi / count sr). Best stratified when count is a
/// power of two.
std::vector<glm::dvec3> sphere_directions(std::size_t count, std::uint32_t seed);

/// `count` low-discrepancy directions on the hemisphere about +z, uniform in solid angle
/// (pdf 1 / (2 pi)): square_to_hemisphere_uniform(sobol_2d(i, seed)).
std::vector<glm::dvec3> hemisphere_directions_uniform(std::size_t count, std::uint32_t seed);

/// `count` low-discrepancy directions on the hemisphere about +z with pdf cos(theta) / pi:
/// square_to_hemisphere_cosine(sobol_2d(i, seed)).
std::vector<glm::dvec3> hemisphere_directions_cosine(std::size_t count, std::uint32_t seed);

/// Area-preserving maps of the unit square (u in [0,1)^2) to directions:
/// - sphere: z = 1 - 2 u.x, phi = 2 pi u.y (Archimedes' cylinder projection), pdf 1 / (4 pi);
/// - hemisphere about +z, uniform: z = 1 - u.x, phi = 2 pi u.y, pdf 1 / (2 pi);
/// - hemisphere about +z, cosine-weighted: Shirley-Chiu concentric map to the unit disk, lifted to
///   z = sqrt(1 - x^2 - y^2) (Malley's method), pdf cos(theta) / pi. z > 0 when u is strictly inside.
glm::dvec3 square_to_sphere(const glm::dvec2& u);
glm::dvec3 square_to_hemisphere_uniform(const glm::dvec2& u);
glm::dvec3 square_to_hemisphere_cosine(const glm::dvec2& u);

/// Tangents t, b of a unit normal n such that (t, b, n) is a right-handed orthonormal frame: Duff,
/// Burgess, Christensen, Hery, Kensler, Liani, Villemin, "Building an Orthonormal Basis, Revisited",
/// JCGT 6(1), 2017 (branchless; continuous except across n.z = 0 where the sign flips).
void orthonormal_basis(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b);
void orthonormal_basis(const glm::vec3& n, glm::vec3& t, glm::vec3& b);

/// The rotation (columns t', b', n) taking local coordinates about +z to world ones about the unit
/// normal n: orthonormal_basis(n) turned about n by `angle` radians (the sample frames of the bake and
/// of the probes' surface pass; the angle is usually hashed from the vertex index).
glm::mat3 turned_frame(const glm::vec3& n, double angle);

/// turned_frame(n, 2 pi hash_to_unit(seed, index, 0x5eed)) (core/hash.h): the frame of the hemisphere
/// samples at vertex `index`, shared by the bake (bake/) and the probes' surface pass, so the pattern
/// differs from vertex to vertex but not from run to run.
glm::mat3 vertex_frame(const glm::vec3& n, std::uint32_t seed, std::uint64_t index);

/// The densities of the maps above, per steradian, at a unit direction.
inline constexpr double kSpherePdf = 0.25 * kInvPi;
inline constexpr double kHemisphereUniformPdf = 0.5 * kInvPi;
/// cos(theta) / pi for direction.z > 0, else 0.
double hemisphere_cosine_pdf(const glm::dvec3& direction);

/// Small, fast random generator for Monte Carlo (PCG32, O'Neill 2014: 64-bit LCG state,
/// XSH-RR output). Independent streams come from distinct (seed, stream) pairs, e.g. stream = vertex
/// index, so results do not depend on threads. Same seeding as the reference pcg32_srandom_r.
class Rng {
 public:
  Rng(std::uint64_t seed, std::uint64_t stream);
  std::uint32_t next_u32();
  /// Uniform double in [0, 1) with 53 random bits.
  double next_double();

 private:
  std::uint64_t state_;
  std::uint64_t inc_;
};

}  // namespace prt::sh
