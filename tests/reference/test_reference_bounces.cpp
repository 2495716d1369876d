// Interreflection, signed environments, rays and determinism of the reference path tracer:
//  - a hemispherical bowl (exact answer for every bounce count: every point of a sphere's inside sees
//    any region of it with view factor = the region's share of the sphere's area);
//  - the white furnace on a closed torus;
//  - a band-limited environment with large negative lobes on a sphere, against Funk-Hecke;
//  - the band-limited image's discretisation error, by quadrature;
//  - radiance along camera rays; bit-identical results for any thread count.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "core/constants.h"
#include "light/projection.h"
#include "reference/estimator.h"
#include "reference/reference.h"
#include "reference/reference_test_util.h"
#include "sh/zonal.h"
#include "support/shapes.h"
#include "trace/scene.h"

using namespace prt;
using prt::test::constant_environment;
using prt::test::equirect_environment;

namespace {


reference::ReferenceOptions options_for(int samples, int bounces, glm::vec3 albedo, std::uint32_t seed = 1) {
  reference::ReferenceOptions o;
  o.samples = samples;
  o.bounces = bounces;
  o.albedo = albedo;
  o.seed = seed;
  o.threads = 2;
  return o;
}

}  // namespace

TEST_CASE("hemispherical bowl: L_K = albedo c / 2 * sum_{k<=K} (albedo / 2)^k for every bounce count", "[reference]") {
  const mesh::Mesh bowl = test::bowl(24, 64);
  // Front faces look at the centre (inward).
  for (std::size_t t = 0; t < bowl.triangle_count(); ++t) {
    const glm::vec3 a = bowl.positions[bowl.indices[3 * t]], b = bowl.positions[bowl.indices[3 * t + 1]],
                    c = bowl.positions[bowl.indices[3 * t + 2]];
    REQUIRE(glm::dot(glm::cross(b - a, c - a), -(a + b + c)) > 0.0f);
  }
  const reference::EnvironmentSampler sky(constant_environment(glm::dvec3(1.0)));
  const double albedo = 0.8;
  // Tessellation (flat facets slightly inside the sphere, a polygonal rim) moves the answer by about
  // (pi / 64)^2 / 6 ~ 4e-4 relative; the allowance is 2e-3.
  for (int bounces : {0, 1, 3, 6}) {
    double exact = 0.0;
    for (int k = 0; k <= bounces; ++k) exact += albedo / 2 * std::pow(albedo / 2, k);
    const std::vector<glm::vec3> values =
        reference::vertex_radiance(bowl, sky, options_for(64, bounces, glm::vec3(float(albedo))));
    const test::Spread s = test::spread(values, 0);
    INFO("bounces " << bounces << ": mean " << s.mean << " exact " << exact << " stddev " << s.stddev);
    CHECK(std::abs(s.mean - exact) <= 4.0 * s.stddev / std::sqrt(double(s.count)) + 2e-3 * exact);
    CHECK(s.stddev < 0.1 * exact);
  }
}

TEST_CASE("white furnace on a torus: 1 - L_o decays geometrically with the bounces and stays positive", "[reference]") {
  // Albedo 1, environment radiance 1, a closed torus whose inner side sees much of itself. With K
  // bounces the exact answer is the probability that a path escapes within K + 1 segments: below 1 for
  // every finite K, tending to 1. Noise: per-vertex i.i.d. standard errors (an overestimate here).
  const mesh::Mesh torus = test::torus(1.0f, 0.6f, 48, 24);
  const reference::EnvironmentSampler white(constant_environment(glm::dvec3(1.0)));
  std::vector<double> deficit, deficit_se;
  const std::vector<int> bounce_counts = {0, 1, 2, 3, 4, 6, 10};
  for (int bounces : bounce_counts) {
    std::vector<glm::vec3> error;
    const std::vector<glm::vec3> values =
        reference::vertex_radiance(torus, white, options_for(128, bounces, glm::vec3(1.0f)), nullptr, &error);
    double sum = 0.0, se_sq = 0.0;
    for (std::size_t v = 0; v < values.size(); ++v) {
      sum += 1.0 - values[v].x;
      se_sq += double(error[v].x) * error[v].x;
      REQUIRE(values[v].x <= 1.0 + 5.0 * error[v].x + 1e-6);  // no vertex above 1 beyond its noise
    }
    deficit.push_back(sum / values.size());
    deficit_se.push_back(std::sqrt(se_sq) / values.size());
    INFO("bounces " << bounces << ": mean 1 - L_o = " << deficit.back() << " +- " << deficit_se.back());
    CHECK(deficit.back() > -4.0 * deficit_se.back());
    if (bounces <= 3) CHECK(deficit.back() > 4.0 * deficit_se.back());  // visibly below 1
  }
  // Geometric decay while the deficit is well above the noise: every added bounce multiplies it by about
  // the same ratio (the mean fraction of a bounce's light that hits the torus again).
  std::vector<double> ratios;
  for (std::size_t i = 0; i + 1 < deficit.size() && bounce_counts[i + 1] <= 3; ++i) ratios.push_back(deficit[i + 1] / deficit[i]);
  for (double r : ratios) {
    INFO("ratios " << ratios[0] << " " << ratios[1] << " " << ratios[2]);
    CHECK(r > 0.15);
    CHECK(r < 0.8);
    CHECK(std::abs(r - ratios[0]) < 0.1);
  }
  CHECK(deficit.back() < 4.0 * deficit_se.back() + 1e-3);  // 10 bounces: 1 to within the noise
}
