// Band-limited (signed) environments, camera rays and determinism of the reference path tracer.
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


// A dim sky over the upper hemisphere and a bright disc of radius 10 degrees: truncated to a few bands
// both ring strongly (negative lobes).
light::Environment disc_and_sky() {
  const glm::dvec3 sun_axis = glm::normalize(glm::dvec3(0.4, 0.7, -0.6));
  const double cos_radius = std::cos(10.0 * kPi / 180.0);
  return equirect_environment(256, 128, [&](int x, int y) {
    const glm::dvec3 d = light::equirect_direction((x + 0.5) / 256, (y + 0.5) / 128);
    if (glm::dot(d, sun_axis) > cos_radius) return glm::dvec3(40.0, 36.0, 30.0);
    return d.y > 0 ? glm::dvec3(0.2, 0.3, 0.5) : glm::dvec3(0.0);
  });
}

double min_value(const image::Image& im) { return *std::min_element(im.pixels.begin(), im.pixels.end()); }
double max_value(const image::Image& im) { return *std::max_element(im.pixels.begin(), im.pixels.end()); }

}  // namespace

TEST_CASE("band-limited environment: its discretised image integrates to the Funk-Hecke closed form", "[reference]") {
  // Integral of the bilinear reconstruction image times max(n.w, 0) by a midpoint rule on 2 x 2
  // sub-cells per texel (each sub-cell within one bilinear patch, so the quadrature itself is accurate
  // to far below the tolerance), against sum_l A_l L_lm Y_lm(n) = sh::irradiance. This measures the
  // whole error that rendering the reconstruction to band_limited_height() rows adds.
  const light::Environment env = disc_and_sky();
  for (int bands : {5, 9}) {
    const sh::RgbCoefficients coefficients = light::project(env, bands);
    const light::Environment limited = reference::band_limited_environment(env, bands);
    REQUIRE(limited.equirect.height == reference::band_limited_height(bands));
    REQUIRE(limited.equirect.width == 2 * limited.equirect.height);
    INFO("bands " << bands << ": min " << min_value(limited.equirect) << " max " << max_value(limited.equirect));
    CHECK(min_value(limited.equirect) < -0.05 * max_value(limited.equirect));  // large negative lobes
    const int w = 2 * limited.equirect.width, h = 2 * limited.equirect.height;
    std::vector<glm::dvec3> directions, weighted;
    for (int y = 0; y < h; ++y) {
      const double omega = light::equirect_texel_solid_angle(y, w, h);
      for (int x = 0; x < w; ++x) {
        const glm::dvec3 d = light::equirect_direction((x + 0.5) / w, (y + 0.5) / h);
        directions.push_back(d);
        weighted.push_back(limited.radiance(d) * omega);
      }
    }
    const std::vector<glm::dvec3> normals = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, -1},
                                             glm::normalize(glm::dvec3(0.4, 0.7, -0.6)),
                                             glm::normalize(glm::dvec3(-0.3, 0.2, 0.9))};
    double worst = 0.0, scale = 0.0;
    for (const glm::dvec3& n : normals) scale = std::max(scale, sh::irradiance(coefficients, n).x);
    for (const glm::dvec3& n : normals) {
      glm::dvec3 integral(0.0);
      for (std::size_t k = 0; k < directions.size(); ++k) integral += weighted[k] * std::max(glm::dot(n, directions[k]), 0.0);
      const glm::dvec3 exact = sh::irradiance(coefficients, n);
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(integral[c] - exact[c]) / scale);
    }
    INFO("bands " << bands << ": largest discretisation error " << worst << " of the largest irradiance");
    CHECK(worst < 2e-4);
  }
}

TEST_CASE("signed band-limited environment on a sphere: estimate equals (albedo/pi) sum A_l L_lm Y_lm(n)", "[reference]") {
  const light::Environment env = disc_and_sky();
  const int bands = 5;
  const sh::RgbCoefficients coefficients = light::project(env, bands);
  const reference::EnvironmentSampler sampler(reference::band_limited_environment(env, bands));
  const mesh::Mesh sphere = test::uv_sphere(12, 24);
  const glm::vec3 albedo(0.9f, 0.7f, 0.5f);
  reference::ReferenceOptions o;
  o.samples = 512;
  o.albedo = albedo;
  o.threads = 2;
  const std::vector<glm::vec3> first = reference::vertex_radiance(sphere, sampler, o);
  o.seed = 2;
  const std::vector<glm::vec3> second = reference::vertex_radiance(sphere, sampler, o);
  // Noise measured from two independent runs: sigma^2 = mean of (a - b)^2 / 2. If the estimator is
  // unbiased the mean of the two deviates from the closed form by sigma / sqrt(2) in rms; a bias b
  // would add b^2. Accept rms <= 1.5 sigma / sqrt(2) + 2e-4 of the scale (discretisation, measured above).
  double diff_sq = 0.0, err_sq = 0.0, scale_sq = 0.0, most_negative = 0.0;
  std::size_t count = 0;
  for (std::size_t v = 0; v < sphere.vertex_count(); ++v) {
    const glm::dvec3 exact = glm::dvec3(albedo) / kPi * sh::irradiance(coefficients, glm::dvec3(sphere.normals[v]));
    for (int c = 0; c < 3; ++c) {
      diff_sq += std::pow(double(first[v][c]) - second[v][c], 2);
      err_sq += std::pow(0.5 * (double(first[v][c]) + second[v][c]) - exact[c], 2);
      scale_sq += exact[c] * exact[c];
      most_negative = std::min(most_negative, exact[c]);
      ++count;
    }
  }
  const double sigma = std::sqrt(diff_sq / count / 2.0), rms_error = std::sqrt(err_sq / count);
  const double scale = std::sqrt(scale_sq / count);
  INFO("noise sigma " << sigma << ", rms error of the mean " << rms_error << ", rms value " << scale
                      << ", most negative exact value " << most_negative);
  CHECK(rms_error <= 1.5 * sigma / std::sqrt(2.0) + 2e-4 * scale);
  CHECK(sigma < 0.02 * scale);
}

TEST_CASE("radiance along camera rays: environment on a miss, surface on a front hit, black on a back hit", "[reference]") {
  const mesh::Mesh ground = test::ground_grid(4);
  const std::vector<glm::vec3> albedo(ground.vertex_count(), glm::vec3(0.5f));
  const trace::Scene scene(ground);
  const reference::EnvironmentSampler sampler(constant_environment(glm::dvec3(2.0, 3.0, 4.0)));
  const reference::PathTracer tracer(ground, albedo, scene, sampler, reference::EstimatorOptions{1});
  reference::PathWorkspace workspace;
  reference::SampleStream stream(1, 0);
  const reference::RadianceEstimate miss = tracer.incoming_radiance({0, 1, 0}, {0.1, 1, 0}, 64, stream, workspace);
  CHECK(miss.value == glm::dvec3(2.0, 3.0, 4.0));
  const reference::RadianceEstimate back = tracer.incoming_radiance({0.1, -1, 0.2}, {0, 1, 0}, 64, stream, workspace);
  CHECK(back.value == glm::dvec3(0.0));
  const reference::RadianceEstimate front = tracer.incoming_radiance({0.1, 1, 0.2}, {0.2, -1, 0.1}, 1024, stream, workspace);
  for (int c = 0; c < 3; ++c) CHECK(front.value[c] == Approx(0.5 * (c + 2.0)).margin(5.0 * front.standard_error[c] + 1e-9));
  CHECK(front.standard_error.x > 0.0);
}

TEST_CASE("reference output is bit-identical for any thread count", "[reference]") {
  const mesh::Mesh torus = test::torus(1.0f, 0.45f, 24, 12);
  const reference::EnvironmentSampler sampler(disc_and_sky());
  reference::ReferenceOptions o;
  o.samples = 32;
  o.bounces = 4;
  o.seed = 9;
  std::vector<std::vector<glm::vec3>> results;
  for (int threads : {1, 2, 3}) {
    o.threads = threads;
    results.push_back(reference::vertex_radiance(torus, sampler, o));
  }
  for (std::size_t r = 1; r < results.size(); ++r)
    for (std::size_t v = 0; v < results[0].size(); ++v) REQUIRE(results[r][v] == results[0][v]);
  o.seed = 10;
  CHECK(reference::vertex_radiance(torus, sampler, o) != results[0]);
}
