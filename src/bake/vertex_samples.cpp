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

}  // namespace prt::bake
