#include <cmath>

#include <glm/geometric.hpp>

#include "bake/passes.h"
#include "core/parallel.h"
#include "sh/basis.h"
#include "sh/zonal.h"

namespace prt::bake {

std::vector<double> unshadowed_factors(int bands) {
  std::vector<double> factors(static_cast<std::size_t>(bands));
  for (int l = 0; l < bands; ++l) factors[l] = sh::clamped_cosine_factor(l) / M_PI;
  return factors;
}

void unshadowed_vertex(int bands, const std::vector<double>& factors, const glm::vec3& normal, float* out) {
  double y[sh::kMaxBands * sh::kMaxBands];
  sh::eval(bands, glm::normalize(glm::dvec3(normal)), y);
  for (int l = 0; l < bands; ++l)
    for (int m = -l; m <= l; ++m) out[sh::index(l, m)] = static_cast<float>(factors[l] * y[sh::index(l, m)]);
}

void unshadowed_geometric(const std::vector<glm::vec3>& normals, int bands, int threads, std::vector<float>& out) {
  const std::size_t n = static_cast<std::size_t>(bands) * bands;
  const std::vector<double> factors = unshadowed_factors(bands);
  out.assign(normals.size() * n, 0.0f);
  parallel_for(normals.size(), 1024, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) unshadowed_vertex(bands, factors, normals[v], out.data() + v * n);
  });
}

}  // namespace prt::bake
