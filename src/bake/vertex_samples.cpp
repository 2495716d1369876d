#include "bake/vertex_samples.h"

#include <cmath>

#include "sh/basis.h"
#include "sh/sampling.h"

namespace prt::bake {

namespace {

LocalSampleSet sample_set_from(const std::vector<glm::dvec3>& dirs, int bands) {
  LocalSampleSet set;
  set.bands = bands;
  const int n = bands * bands;
  set.directions.resize(dirs.size());
  set.basis.resize(dirs.size() * static_cast<std::size_t>(n));
  std::vector<double> y(static_cast<std::size_t>(n));
  for (std::size_t s = 0; s < dirs.size(); ++s) {
    set.directions[s] = glm::vec3(dirs[s]);
    sh::eval(bands, dirs[s], y.data());
    for (int i = 0; i < n; ++i) set.basis[s * n + i] = static_cast<float>(y[i]);
  }
  return set;
}

}  // namespace

LocalSampleSet make_local_sample_set(int samples, int bands, std::uint32_t seed) {
  return sample_set_from(sh::hemisphere_directions_cosine(static_cast<std::size_t>(samples), seed), bands);
}

LocalSampleSet make_uniform_sample_set(int samples, int bands, std::uint32_t seed) {
  return sample_set_from(sh::hemisphere_directions_uniform(static_cast<std::size_t>(samples), seed), bands);
}

namespace {
std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
}  // namespace

glm::mat3 turned_frame(const glm::vec3& n, double angle) {
  // Duff, Burgess, Christensen, Hery, Kensler, Liani, Villemin: "Building an Orthonormal Basis,
  // Revisited", JCGT 2017.
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  const glm::vec3 t(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const glm::vec3 bt(b, sign + n.y * n.y * a, -n.y);
  const float c = static_cast<float>(std::cos(angle)), s = static_cast<float>(std::sin(angle));
  return glm::mat3(c * t + s * bt, -s * t + c * bt, n);
}

glm::mat3 vertex_frame(const glm::vec3& n, std::uint32_t seed, std::uint64_t vertex) {
  const std::uint64_t h = splitmix64(splitmix64(seed) ^ vertex);
  return turned_frame(n, static_cast<double>(h >> 11) * (2.0 * M_PI / 9007199254740992.0));
}

}  // namespace prt::bake
