// The reference path tracer against answers known in closed form (no baker involved): unoccluded
// planes under constant, sky-only and sun + sky environments, the floor centre of an open box (view
// factor of a square opening), the white furnace on a torus, and a signed band-limited environment on a
// sphere (Funk-Hecke). Tolerances come from the measured spread of the estimates (stated per test).
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
using prt::test::ground_grid;

namespace {


std::vector<glm::vec3> run(const mesh::Mesh& mesh, const light::Environment& env, int samples, int bounces,
                           glm::vec3 albedo, std::vector<glm::vec3>* standard_error = nullptr,
                           std::uint32_t seed = 1) {
  const reference::EnvironmentSampler sampler(env);
  reference::ReferenceOptions options;
  options.samples = samples;
  options.bounces = bounces;
  options.albedo = albedo;
  options.seed = seed;
  options.threads = 2;
  return reference::vertex_radiance(mesh, sampler, options, nullptr, standard_error);
}

// Checks that the vertices (all with the same expected value `exact` per channel) agree with it: the
// mean within 4 standard errors of the mean (measured spread / sqrt(count)) plus `allowance` (a
// stated discretisation bound, relative), and every vertex within 10 measured standard deviations (a
// check for gross outliers only: randomised quasi-Monte Carlo errors are not Gaussian-tailed).
void check_all_equal(const std::vector<glm::vec3>& values, const glm::dvec3& exact, double allowance) {
  for (int c = 0; c < 3; ++c) {
    const test::Spread s = test::spread(values, c);
    INFO("channel " << c << ": mean " << s.mean << " exact " << exact[c] << " stddev " << s.stddev << " over "
                    << s.count);
    CHECK(std::abs(s.mean - exact[c]) <= 4.0 * s.stddev / std::sqrt(double(s.count)) + allowance * std::abs(exact[c]) + 1e-7);
    for (const glm::vec3& v : values) REQUIRE(std::abs(v[c] - exact[c]) <= 10.0 * s.stddev + allowance * std::abs(exact[c]) + 1e-7);
    // The estimates are not trivially exact-by-construction: noise is present but small.
    CHECK(s.stddev < 0.05 * std::abs(exact[c]));
  }
}

}  // namespace

TEST_CASE("environment sampler: densities integrate to one and match the samples", "[reference]") {
  // A map with a bright texel, a dim sky and a black lower half.
  const light::Environment env = equirect_environment(64, 32, [](int x, int y) {
    if (x == 40 && y == 9) return glm::dvec3(1000.0, 500.0, 100.0);
    return y < 16 ? glm::dvec3(0.5, 0.7, 1.0) : glm::dvec3(0.0);
  });
  const reference::EnvironmentSampler sampler(env);
  REQUIRE(sampler.has_distribution());
  // Integral of the density over the sphere, 4 x 4 points per cell uniform in (phi, cos theta): 1, and
  // pdf() finds each point's own cell.
  double integral = 0.0;
  for (int y = 0; y < 32; ++y) {
    const double z0 = std::cos(kPi * y / 32), z1 = std::cos(kPi * (y + 1) / 32);
    for (int x = 0; x < 64; ++x)
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
          const double z = z0 + (z1 - z0) * (i + 0.5) / 4, phi = 2 * kPi * ((x + (j + 0.5) / 4) / 64 - 0.5);
          const double s = std::sqrt(1.0 - z * z);
          integral += sampler.pdf({s * std::cos(phi), z, s * std::sin(phi)}) *
                      light::equirect_texel_solid_angle(y, 64, 32) / 16.0;
        }
  }
  CHECK(integral == Approx(1.0).epsilon(1e-9));
  // sample() reports the density pdf() gives for its direction, and never lands where the map is black
  // beyond the bilinear footprint (rows >= 17).
  sh::Rng rng(7, 0);
  int in_bright = 0;
  const int count = 20000;
  for (int k = 0; k < count; ++k) {
    const glm::dvec2 u(rng.next_double(), rng.next_double());
    const reference::EnvironmentSampler::Sample s = sampler.sample(u);
    REQUIRE(glm::length(s.direction) == Approx(1.0).epsilon(1e-12));
    REQUIRE(s.pdf > 0.0);
    double eu = 0, ev = 0;
    light::equirect_uv(s.direction, eu, ev);
    REQUIRE(ev * 32 < 17.0 + 1e-9);
    const double inner_u = eu * 64 - std::floor(eu * 64), inner_v = ev * 32 - std::floor(ev * 32);
    if (inner_u > 1e-6 && inner_u < 1 - 1e-6 && inner_v > 1e-6 && inner_v < 1 - 1e-6)
      REQUIRE(sampler.pdf(s.direction) == Approx(s.pdf).epsilon(1e-12));
    if (int(eu * 64) == 40 && int(ev * 32) == 9) ++in_bright;
  }
  // The density is normalised over the cells, and the bright cell is drawn with its probability.
  double total = 0.0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) total += sampler.pdf(light::equirect_direction((x + 0.5) / 64, (y + 0.5) / 32)) *
                                         light::equirect_texel_solid_angle(y, 64, 32);
  CHECK(total == Approx(1.0).epsilon(1e-9));
  const double expected = sampler.pdf(light::equirect_direction(40.5 / 64, 9.5 / 32)) *
                          light::equirect_texel_solid_angle(9, 64, 32);
  CHECK(expected > 0.1);
  CHECK(double(in_bright) / count == Approx(expected).margin(4.0 * std::sqrt(expected / count)));
}

TEST_CASE("unoccluded plane under a constant environment: L_o = albedo * c", "[reference]") {
  const mesh::Mesh ground = ground_grid(16);
  const glm::vec3 albedo(0.8f, 0.5f, 0.3f);
  const glm::dvec3 c(1.0, 2.0, 3.0);
  for (int bounces : {0, 2}) {
    INFO("bounces " << bounces);
    check_all_equal(run(ground, constant_environment(c), 256, bounces, albedo), glm::dvec3(albedo) * c, 0.0);
  }
}

TEST_CASE("unoccluded plane under a sky-only hemisphere: L_o = albedo * c", "[reference]") {
  // c above the horizon (rows 0..H/2-1), 0 below. Bilinear smearing across the horizon changes the
  // integral by about (pi/H)^2 / 12 = 1.3e-5 relative at H = 256: allowance 1e-4.
  const glm::dvec3 c(2.0, 1.0, 0.5);
  const light::Environment sky = equirect_environment(512, 256, [&](int, int y) { return y < 128 ? c : glm::dvec3(0.0); });
  const glm::vec3 albedo(0.8f);
  check_all_equal(run(ground_grid(16), sky, 256, 0, albedo), glm::dvec3(albedo) * c, 1e-4);
}

TEST_CASE("sun and sky on an unoccluded plane: MIS estimate matches the analytic irradiance", "[reference]") {
  // Sky radiance 1 above the horizon; a "sun" of 4 x 4 texels of radiance 5000 (about 1.7e-3 sr at 45
  // degrees elevation), giving about 2/3 of the irradiance. For normal +Y the irradiance of a block of
  // texels, rows theta0..theta1 and width dphi, is dphi (sin^2 theta1 - sin^2 theta0) / 2 per unit
  // radiance. Allowance 1e-4 for the bilinear smearing at the block's and horizon's edges (second order).
  const int w = 512, h = 256, x0 = 100, y0 = 62;
  const double sun = 5000.0;
  const light::Environment env = equirect_environment(w, h, [&](int x, int y) {
    if (x >= x0 && x < x0 + 4 && y >= y0 && y < y0 + 4) return glm::dvec3(sun, 0.9 * sun, 0.8 * sun);
    return y < h / 2 ? glm::dvec3(1.0) : glm::dvec3(0.0);
  });
  const double theta0 = kPi * y0 / h, theta1 = kPi * (y0 + 4) / h, dphi = 2 * kPi * 4 / w;
  const double block = dphi * (std::pow(std::sin(theta1), 2) - std::pow(std::sin(theta0), 2)) / 2.0;
  const glm::dvec3 sun_rgb(sun, 0.9 * sun, 0.8 * sun);
  const glm::vec3 albedo(0.7f);
  const glm::dvec3 exact = glm::dvec3(albedo) / kPi * (kPi * glm::dvec3(1.0) + (sun_rgb - glm::dvec3(1.0)) * block);
  REQUIRE(block * sun > 0.5 * kPi);  // the sun dominates
  check_all_equal(run(ground_grid(16), env, 256, 0, albedo), exact, 1e-4);
}

TEST_CASE("floor centre of an open box: view factor of the square opening", "[reference]") {
  // Floor [-1,1]^2, walls of height 1, open top, constant sky c. The floor centre sees the sky through
  // the square opening only: L_o = albedo * c * F, with F the view factor from a point to a parallel
  // square centred above it, four times that of a corner rectangle:
  //   F_corner(A, B) = (1/2pi) [A/sqrt(1+A^2) atan(B/sqrt(1+A^2)) + B/sqrt(1+B^2) atan(A/sqrt(1+B^2))],
  // A = B = half width / height above the ray origin (height - ray offset).
  const mesh::Mesh box = test::open_box(1.0f, 8);
  std::size_t centre = 0;
  for (std::size_t v = 0; v < box.positions.size(); ++v)
    if (glm::length(box.positions[v]) < 1e-6f && box.normals[v].y > 0.5f) centre = v;
  REQUIRE(glm::length(box.positions[centre]) < 1e-6f);
  const double height = 1.0 - trace::ray_offset_for(box.positions);
  const double a = 1.0 / height;
  const double f_corner = (a / std::sqrt(1 + a * a) * std::atan(a / std::sqrt(1 + a * a))) * 2.0 / (2.0 * kPi);
  const double view_factor = 4.0 * f_corner;
  const glm::dvec3 c(1.0, 2.0, 0.5);
  const glm::vec3 albedo(0.6f);
  // One vertex, several independent seeds: their spread gives the standard error.
  std::vector<glm::vec3> estimates;
  mesh::Mesh single = box;  // estimate all vertices, keep the centre
  for (std::uint32_t seed = 1; seed <= 24; ++seed) estimates.push_back(run(single, constant_environment(c), 64, 0, albedo, nullptr, seed)[centre]);
  check_all_equal(estimates, glm::dvec3(albedo) * c * view_factor, 0.0);
  CHECK(view_factor == Approx(0.55413).epsilon(1e-3));
}
