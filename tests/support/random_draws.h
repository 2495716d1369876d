// Random test and benchmark inputs drawn in a fixed order. The arguments of one call are evaluated in an
// unspecified order, and GCC and clang differ (GCC draws glm::dvec3(n(rng), n(rng), n(rng))'s z first,
// clang its x), so such an expression gives each compiler's build other inputs from the same seed. These
// draw x, then y, then z (w, then x, y, z for a quaternion), one statement each.
#pragma once

#include <random>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace prt::test {

/// Three draws of `dist`, in order x, y, z.
template <typename T, typename Rng, typename Dist>
glm::vec<3, T> draw_vec3(Rng& rng, Dist& dist) {
  const T x = static_cast<T>(dist(rng));
  const T y = static_cast<T>(dist(rng));
  const T z = static_cast<T>(dist(rng));
  return {x, y, z};
}

/// Four draws of `dist`, in order x, y, z, w.
template <typename T, typename Rng, typename Dist>
glm::vec<4, T> draw_vec4(Rng& rng, Dist& dist) {
  const glm::vec<3, T> xyz = draw_vec3<T>(rng, dist);
  const T w = static_cast<T>(dist(rng));
  return {xyz, w};
}

/// A uniformly distributed unit direction (a normalised standard normal vector).
template <typename Rng>
glm::dvec3 random_direction(Rng& rng) {
  std::normal_distribution<double> n;
  return glm::normalize(draw_vec3<double>(rng, n));
}

/// A uniformly distributed rotation (a normalised standard normal quaternion, drawn w, x, y, z).
template <typename Rng>
glm::dmat3 random_rotation(Rng& rng) {
  std::normal_distribution<double> n;
  const glm::dvec4 q = draw_vec4<double>(rng, n);
  return glm::mat3_cast(glm::normalize(glm::dquat(q.x, q.y, q.z, q.w)));
}

}  // namespace prt::test
