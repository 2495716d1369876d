#include "sh/sampling.h"

#include <algorithm>
#include <cmath>

#include "core/constants.h"
#include "core/hash.h"

namespace prt::sh {

namespace {

std::uint32_t reverse_bits(std::uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

// Burley 2020, listing 2 (the improved constants): a bijection of 32-bit words in which output bit p
// depends only on input bits <= p. Applied to reversed bits it is an Owen scramble: each digit of the
// value is flipped depending only on the key and the digits above it.
std::uint32_t laine_karras_permutation(std::uint32_t x, std::uint32_t key) {
  x += key;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

std::uint32_t nested_uniform_scramble(std::uint32_t x, std::uint32_t key) {
  return reverse_bits(laine_karras_permutation(reverse_bits(x), key));
}

std::uint32_t hash_combine(std::uint32_t seed, std::uint32_t v) {
  return mix32(seed ^ (v + 0x9e3779b9u + (seed << 6) + (seed >> 2)));
}

// Sobol dimensions 0 and 1 as generator matrices applied to the bits of index; dimension 1's
// direction numbers are v_0 = 2^31, v_k = v_(k-1) ^ (v_(k-1) >> 1).
void sobol_pair(std::uint32_t index, std::uint32_t& d0, std::uint32_t& d1) {
  d0 = reverse_bits(index);
  d1 = 0;
  std::uint32_t v = 0x80000000u;
  for (; index != 0; index >>= 1) {
    if (index & 1u) d1 ^= v;
    v ^= v >> 1;
  }
}

constexpr double kTwoPi = 6.283185307179586476925;

template <typename Map>
std::vector<glm::dvec3> map_sequence(std::size_t count, std::uint32_t seed, Map map) {
  std::vector<glm::dvec3> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) out.push_back(map(sobol_2d(static_cast<std::uint32_t>(i), seed)));
  return out;
}

}  // namespace

glm::dvec2 sobol_2d(std::uint32_t index, std::uint32_t seed) {
  const std::uint32_t key = mix32(seed);
  std::uint32_t d0 = 0, d1 = 0;
  sobol_pair(nested_uniform_scramble(index, hash_combine(key, 0)), d0, d1);
  d0 = nested_uniform_scramble(d0, hash_combine(key, 1));
  d1 = nested_uniform_scramble(d1, hash_combine(key, 2));
  constexpr double kScale = 1.0 / 4294967296.0;
  return {(d0 + 0.5) * kScale, (d1 + 0.5) * kScale};
}

glm::dvec3 square_to_sphere(const glm::dvec2& u) {
  const double z = 1.0 - 2.0 * u.x;
  const double r = 2.0 * std::sqrt(std::max(0.0, u.x * (1.0 - u.x)));  // sin(theta), exact near the poles
  const double phi = kTwoPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

glm::dvec3 square_to_hemisphere_uniform(const glm::dvec2& u) {
  const double z = 1.0 - u.x;
  const double r = std::sqrt(std::max(0.0, u.x * (2.0 - u.x)));
  const double phi = kTwoPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

glm::dvec3 square_to_hemisphere_cosine(const glm::dvec2& u) {
  const double a = 2.0 * u.x - 1.0, b = 2.0 * u.y - 1.0;
  if (a == 0.0 && b == 0.0) return {0.0, 0.0, 1.0};
  double r, phi;
  if (std::abs(a) > std::abs(b)) {
    r = a;
    phi = 0.125 * kTwoPi * (b / a);
  } else {
    r = b;
    phi = 0.25 * kTwoPi - 0.125 * kTwoPi * (a / b);
  }
  const double z = std::sqrt(std::max(0.0, (1.0 - r) * (1.0 + r)));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

double hemisphere_cosine_pdf(const glm::dvec3& direction) {
  return direction.z > 0.0 ? direction.z / 3.14159265358979323846 : 0.0;
}

std::vector<glm::dvec3> sphere_directions(std::size_t count, std::uint32_t seed) {
  return map_sequence(count, seed, square_to_sphere);
}

std::vector<glm::dvec3> hemisphere_directions_uniform(std::size_t count, std::uint32_t seed) {
  return map_sequence(count, seed, square_to_hemisphere_uniform);
}

std::vector<glm::dvec3> hemisphere_directions_cosine(std::size_t count, std::uint32_t seed) {
  return map_sequence(count, seed, square_to_hemisphere_cosine);
}

Rng::Rng(std::uint64_t seed, std::uint64_t stream) : state_(0), inc_((stream << 1u) | 1u) {
  next_u32();
  state_ += seed;
  next_u32();
}

std::uint32_t Rng::next_u32() {
  const std::uint64_t old = state_;
  state_ = old * 6364136223846793005ULL + inc_;
  const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
  const auto rotation = static_cast<std::uint32_t>(old >> 59u);
  return (xorshifted >> rotation) | (xorshifted << ((32u - rotation) & 31u));
}

double Rng::next_double() {
  const std::uint64_t high = next_u32();
  const std::uint64_t low = next_u32();
  return static_cast<double>(((high << 32) | low) >> 11) * (1.0 / 9007199254740992.0);
}

namespace {
template <class V>
void duff_basis(const V& n, V& t, V& b) {
  using T = typename V::value_type;
  const T sign = std::copysign(T(1), n.z);
  const T a = T(-1) / (sign + n.z);
  const T c = n.x * n.y * a;
  t = V(T(1) + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = V(c, sign + n.y * n.y * a, -n.y);
}
}  // namespace

void orthonormal_basis(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b) { duff_basis(n, t, b); }
void orthonormal_basis(const glm::vec3& n, glm::vec3& t, glm::vec3& b) { duff_basis(n, t, b); }

glm::mat3 turned_frame(const glm::vec3& n, double angle) {
  glm::vec3 t, b;
  duff_basis(n, t, b);
  const float c = static_cast<float>(std::cos(angle)), s = static_cast<float>(std::sin(angle));
  return glm::mat3(c * t + s * b, -s * t + c * b, n);
}

glm::mat3 vertex_frame(const glm::vec3& n, std::uint32_t seed, std::uint64_t index) {
  return turned_frame(n, 2.0 * kPi * hash_to_unit(seed, index, 0x5eedu));
}

}  // namespace prt::sh
