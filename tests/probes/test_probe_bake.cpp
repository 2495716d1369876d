// Probe baking against the independent Monte Carlo path tracer (probe_reference.h) in a scene with
// occluders, interreflection, a sun and an emitter; validity; determinism; transfer and relighting.
#include <catch2/catch.hpp>

#include <cmath>

#include <glm/geometric.hpp>

#include "light/projection.h"
#include "probes/baker.h"
#include "probes/probe_reference.h"
#include "probes/probe_scene.h"
#include "sh/rotation.h"
#include "sh/zonal.h"

using namespace prt;

namespace {

struct Comparison {
  double rel_rms = 0.0;        ///< sqrt(sum (bake - ref)^2 / sum ref^2) over valid probes, coefficients, channels
  double reference_noise = 0;  ///< the same ratio for the reference's own standard errors
};

Comparison compare(const probes::ProbeSet& baked, const std::vector<test::ReferenceProbe>& reference) {
  double diff2 = 0, ref2 = 0, noise2 = 0;
  for (std::size_t p = 0; p < baked.count(); ++p) {
    if (!baked.valid[p]) continue;
    const sh::RgbCoefficients b = baked.probe(p);
    for (std::size_t i = 0; i < b.values.size(); ++i) {
      const glm::dvec3 d = b.values[i] - reference[p].coefficients.values[i];
      diff2 += glm::dot(d, d);
      ref2 += glm::dot(reference[p].coefficients.values[i], reference[p].coefficients.values[i]);
      noise2 += glm::dot(reference[p].standard_error.values[i], reference[p].standard_error.values[i]);
    }
  }
  return {std::sqrt(diff2 / ref2), std::sqrt(noise2 / ref2)};
}

probes::ProbeSet points_layout() {
  probes::ProbeSet layout;
  layout.layout = probes::ProbeSet::Layout::points;
  return layout;
}

}  // namespace

TEST_CASE("probe radiance matches a brute-force path tracer (sky, sun, emitter, 2 bounces)", "[probes][bake]") {
  const test::ProbeScene scene = test::make_probe_scene(true);
  const light::Environment sky = test::make_sky();
  probes::SceneLight light;
  light.environment = &sky;
  light.sun = probes::parse_sun("0.5,0.8,0.3,3,2");
  light.emission = scene.emission;
  probes::ProbeBakeOptions options;
  options.bounces = 2;
  probes::ProbeBakeReport report;
  const probes::ProbeSet baked = probes::bake_probes(scene.mesh, light, scene.probes, points_layout(), options, &report);
  const std::vector<test::ReferenceProbe> reference = test::reference_probes(
      scene.mesh, scene.mesh.albedo, scene.emission, &sky, light.sun, scene.probes, options.bands, options.bounces, 1 << 18, 99);

  // Probe 0 is inside the closed box: every ray meets a back face.
  CHECK(baked.valid[0] == 0);
  CHECK(baked.backface_fraction[0] == Approx(1.0));
  CHECK(reference[0].backface_fraction == Approx(1.0));
  for (std::size_t p = 1; p < baked.count(); ++p) {
    CHECK(baked.valid[p] == 1);
    CHECK(baked.backface_fraction[p] == Approx(reference[p].backface_fraction).margin(0.02));
  }
  CHECK(report.invalid == 1);
  const Comparison c = compare(baked, reference);
  INFO("rel_rms " << c.rel_rms << ", reference noise " << c.reference_noise);
  CHECK(c.reference_noise < 0.006);
  CHECK(c.rel_rms <= 0.02);
  // Per probe, the irradiance a surface at the probe would receive, at the 6 axis normals.
  for (std::size_t p = 1; p < baked.count(); ++p)
    for (const glm::dvec3& n : {glm::dvec3(1, 0, 0), glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, -1, 0),
                                glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1)}) {
      const glm::dvec3 e_bake = sh::irradiance(baked.probe(p), n), e_ref = sh::irradiance(reference[p].coefficients, n);
      INFO("probe " << p << " normal " << n.x << "," << n.y << "," << n.z << ": " << e_bake.x << " vs " << e_ref.x);
      CHECK(std::abs(e_bake.x - e_ref.x) <= 0.03 * std::max(e_ref.x, 0.2 * glm::length(sh::irradiance(reference[p].coefficients, {0, 1, 0}))));
    }
}

TEST_CASE("probe radiance without sun or emission, 0 and 3 bounces, matches the path tracer", "[probes][bake]") {
  const test::ProbeScene scene = test::make_probe_scene(false);
  const light::Environment sky = test::make_sky();
  probes::SceneLight light;
  light.environment = &sky;
  for (int bounces : {0, 3}) {
    probes::ProbeBakeOptions options;
    options.bounces = bounces;
    const probes::ProbeSet baked = probes::bake_probes(scene.mesh, light, scene.probes, points_layout(), options);
    const auto reference = test::reference_probes(scene.mesh, scene.mesh.albedo, {}, &sky, std::nullopt, scene.probes,
                                                  options.bands, bounces, 1 << 18, 5);
    const Comparison c = compare(baked, reference);
    INFO("bounces " << bounces << ": rel_rms " << c.rel_rms << ", reference noise " << c.reference_noise);
    CHECK(c.rel_rms <= 0.02);
  }
}

TEST_CASE("probe bakes are identical for any thread count", "[probes][bake]") {
  const test::ProbeScene scene = test::make_probe_scene(true);
  const light::Environment sky = test::make_sky();
  probes::SceneLight light;
  light.environment = &sky;
  light.sun = probes::parse_sun("0.5,0.8,0.3,3,2");
  light.emission = scene.emission;
  probes::ProbeBakeOptions options;
  options.rays = 256;
  options.surface_samples = 64;
  options.transfer_bands = 3;
  options.threads = 1;
  const probes::ProbeSet one = probes::bake_probes(scene.mesh, light, scene.probes, points_layout(), options);
  options.threads = 2;
  const probes::ProbeSet two = probes::bake_probes(scene.mesh, light, scene.probes, points_layout(), options);
  CHECK(one.coefficients == two.coefficients);
  CHECK(one.transfer == two.transfer);
  CHECK(one.transfer_bias == two.transfer_bias);
}

TEST_CASE("transfer: M L + b reproduces the bake, and relighting a rotated sky matches a rebake", "[probes][bake][transfer]") {
  const test::ProbeScene scene = test::make_probe_scene(true);
  // Band-limited skies, so that the transfer's 3-band view of the environment is the whole truth.
  const light::Environment sky = test::make_band_limited_sky(3);
  probes::SceneLight light;
  light.environment = &sky;
  light.sun = probes::parse_sun("0.5,0.8,0.3,3,2");
  light.emission = scene.emission;
  probes::ProbeBakeOptions options;
  options.transfer_bands = 3;
  options.surface_samples = 512;
  const probes::ProbeSet baked = probes::bake_probes(scene.mesh, light, scene.probes, points_layout(), options);
  REQUIRE(baked.transfer_bands == 3);
  REQUIRE(baked.transfer_channels == 3);  // coloured albedo

  auto rel_rms = [](const probes::ProbeSet& a, const probes::ProbeSet& b) {
    double d2 = 0, r2 = 0;
    for (std::size_t k = 0; k < a.coefficients.size(); ++k) {
      if (!a.valid[k / a.coefficient_count()]) continue;
      const glm::dvec3 d = glm::dvec3(a.coefficients[k]) - glm::dvec3(b.coefficients[k]);
      d2 += glm::dot(d, d);
      r2 += glm::dot(glm::dvec3(b.coefficients[k]), glm::dvec3(b.coefficients[k]));
    }
    return std::sqrt(d2 / r2);
  };

  probes::ProbeSet same = baked;
  probes::relight(same, baked.transfer_environment);
  INFO("same sky: " << rel_rms(same, baked));
  CHECK(rel_rms(same, baked) < 0.01);
  CHECK(same.sky.values[0].x == Approx(baked.sky.values[0].x).epsilon(1e-9));

  // Rotate the sky by 120 degrees about +Y: relight the transfer, and rebake with the rotated sky.
  const glm::dmat3 r = sh::rotation_from_yaw_pitch_roll(120.0, 0.0, 0.0);
  const sh::RgbCoefficients rotated = sh::Rotation(3, r).apply(baked.transfer_environment);
  light::Environment rotated_sky;
  rotated_sky.layout = light::Environment::Layout::equirect;
  rotated_sky.equirect = light::render_equirect(rotated, 512, 256);
  probes::SceneLight rotated_light = light;
  rotated_light.environment = &rotated_sky;
  probes::ProbeBakeOptions rebake_options = options;
  rebake_options.transfer_bands = 0;
  const probes::ProbeSet rebaked = probes::bake_probes(scene.mesh, rotated_light, scene.probes, points_layout(), rebake_options);
  probes::ProbeSet relit = baked;
  probes::relight(relit, rotated);
  INFO("rotated sky: relit vs rebaked " << rel_rms(relit, rebaked) << "; unrelit vs rebaked " << rel_rms(baked, rebaked));
  CHECK(rel_rms(relit, rebaked) < 0.02);
  CHECK(rel_rms(baked, rebaked) > 0.05);  // the rotation really changes the probes
}

namespace {

// A floor much larger than the probes' height (so it covers the lower hemisphere to within 0.06 degrees),
// black (albedo 0), under an environment that is 1 only well below the horizon (direction y < -0.2)
// and 0 elsewhere, bilinear neighbours included. Every probe above the floor then sees nothing:
// its exact coefficients are all 0.
struct DarkFloor {
  mesh::Mesh mesh;
  light::Environment environment;
};

DarkFloor dark_floor() {
  DarkFloor scene;
  const float r = 1000.0f;
  scene.mesh.positions = {{-r, 0, -r}, {r, 0, -r}, {r, 0, r}, {-r, 0, r}};
  scene.mesh.positions.reserve(5);
  scene.mesh.normals.assign(4, glm::vec3(0, 1, 0));
  scene.mesh.albedo.assign(4, glm::vec3(0.0f));
  scene.mesh.indices = {0, 2, 1, 0, 3, 2};  // counter-clockwise seen from +Y
  light::Environment& env = scene.environment;
  env.layout = light::Environment::Layout::equirect;
  env.equirect = image::Image(128, 64, 3);
  for (int y = 0; y < 64; ++y) {
    const double up = std::cos(M_PI * (y + 0.5) / 64.0);  // docs/conventions.md: the top row is +Y
    for (int x = 0; x < 128; ++x)
      for (int c = 0; c < 3; ++c) env.equirect.at(x, y, c) = up < -0.2 ? 1.0f : 0.0f;
  }
  return scene;
}

}  // namespace

TEST_CASE("probe estimates are unbiased when the control variate is chosen per probe", "[probes][bake]") {
  // With few rays per probe, the number of hits varies from probe to probe. Choosing the control
  // variate or the plain estimator from those same rays' hit count would make the choice correlate with
  // the control variate's quadrature error, whose mean over probes is then not 0 (it was positive here:
  // the control variate was taken exactly when fewer rays than usual met the bright floor region).
  const DarkFloor scene = dark_floor();
  probes::SceneLight light;
  light.environment = &scene.environment;
  probes::ProbeBakeOptions options;
  options.bands = 1;
  options.rays = 16;
  options.bounces = 0;
  options.surface_samples = 16;
  std::vector<glm::dvec3> positions;
  for (int i = 0; i < 16000; ++i) positions.emplace_back(0.01 * (i % 128), 1.0, 0.01 * (i / 128));
  const probes::ProbeSet baked = probes::bake_probes(scene.mesh, light, positions, points_layout(), options);
  double sum = 0.0, sum_sq = 0.0;
  for (std::size_t p = 0; p < baked.count(); ++p) {
    const double c0 = baked.coefficients[p].x;
    sum += c0;
    sum_sq += c0 * c0;
  }
  const double n = static_cast<double>(baked.count());
  const double mean = sum / n, standard_error = std::sqrt((sum_sq / n - mean * mean) / (n - 1.0));
  INFO("mean c_0 " << mean << " +- " << standard_error << " (exact: 0)");
  CHECK(standard_error > 0.0);  // the estimates do vary: the test has power
  CHECK(std::abs(mean) < 4.0 * standard_error);
}
