// Dominant-light extraction (light/sun_extraction.h) on synthetic maps whose discs are known exactly:
// direction, energy (irradiance at normal incidence, E = L pi sin^2 a for a uniform cap), the residual
// sky, maps without a sun, and rotation.
#include <catch2/catch.hpp>

#include <cmath>

#include <glm/geometric.hpp>

#include "core/constants.h"
#include "light/environment.h"
#include "light/projection.h"
#include "light/scene_lighting.h"
#include "light/sun_extraction.h"
#include "light_test_util.h"

using namespace prt;

namespace {


// The equirect convention of docs/conventions.md, written out here (not light::equirect_direction).
glm::dvec3 direction_at(double u, double v) {
  const double phi = 2.0 * kPi * (u - 0.5), theta = kPi * v;
  return {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
}

glm::dvec3 sky(const glm::dvec3& w) {
  if (w.y < 0.0) return {0.10, 0.08, 0.05};
  return glm::dvec3(0.3, 0.4, 0.6) + glm::dvec3(0.5, 0.4, 0.2) * (1.0 - w.y) * (1.0 - w.y);
}

struct SyntheticDisc {
  glm::dvec3 direction;
  double radius;       // radians
  glm::dvec3 radiance;
};

// Sky plus discs, each texel the disc's radiance times its covered fraction (16 x 16 sub-samples).
image::Image synthetic_map(int width, int height, const std::vector<SyntheticDisc>& discs) {
  image::Image im(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glm::dvec3 centre = direction_at((x + 0.5) / width, (y + 0.5) / height);
      glm::dvec3 value = sky(centre);
      for (const SyntheticDisc& d : discs) {
        if (glm::dot(centre, d.direction) < std::cos(d.radius + 4.0 * kPi / height)) continue;
        int inside = 0;
        for (int j = 0; j < 16; ++j)
          for (int i = 0; i < 16; ++i)
            inside += glm::dot(direction_at((x + (i + 0.5) / 16) / width, (y + (j + 0.5) / 16) / height), d.direction) >= std::cos(d.radius);
        value += d.radiance * (inside / 256.0);
      }
      for (int c = 0; c < 3; ++c) im.at(x, y, c) = static_cast<float>(value[c]);
    }
  return im;
}

light::Environment as_environment(image::Image im) {
  light::Environment env;
  env.layout = light::Environment::Layout::equirect;
  env.equirect = std::move(im);
  env.source = "synthetic";
  return env;
}

double angle_degrees(const glm::dvec3& a, const glm::dvec3& b) {
  return std::acos(std::min(1.0, glm::dot(glm::normalize(a), glm::normalize(b)))) * 180.0 / kPi;
}

double relative_error(const glm::dvec3& got, const glm::dvec3& want) {
  return glm::length(got - want) / glm::length(want);
}

}  // namespace

TEST_CASE("a disc on a smooth sky is found with its direction, energy and radius", "[light][sun]") {
  const SyntheticDisc sun{glm::normalize(glm::dvec3(0.5, 0.6, -0.62)), 1.0 * kPi / 180.0, {30000.0, 27000.0, 21000.0}};
  const light::Environment env = as_environment(synthetic_map(2048, 1024, {sun}));
  const light::ExtractionResult found = light::extract_discs(env);
  REQUIRE(found.discs.size() == 1);
  const light::Disc& disc = found.discs[0];
  const glm::dvec3 energy = sun.radiance * (kPi * std::sin(sun.radius) * std::sin(sun.radius));
  CHECK(angle_degrees(disc.direction, sun.direction) < 0.5);
  CHECK(relative_error(disc.irradiance, energy) < 0.02);
  CHECK(disc.angular_radius * 180.0 / kPi == Approx(1.0).margin(0.25));

  // Away from the disc the residual is the sky (within 1%); where the disc was, the fill is sky-like.
  const image::Image& residual = found.residual.equirect;
  double worst_away = 0.0, worst_inside = 0.0;
  for (int y = 0; y < residual.height; y += 3)
    for (int x = 0; x < residual.width; x += 3) {
      const glm::dvec3 w = direction_at((x + 0.5) / residual.width, (y + 0.5) / residual.height);
      const glm::dvec3 got(residual.at(x, y, 0), residual.at(x, y, 1), residual.at(x, y, 2));
      const double e = relative_error(got, sky(w));
      if (angle_degrees(w, sun.direction) > 2.0) worst_away = std::max(worst_away, e);
      else worst_inside = std::max(worst_inside, e);
    }
  CHECK(worst_away < 0.01);
  CHECK(worst_inside < 0.05);

  // The residual projects like the sky alone: the spike is gone from every band.
  light::Environment sky_only = as_environment(synthetic_map(2048, 1024, {}));
  const sh::RgbCoefficients a = light::project(found.residual, 5), b = light::project(sky_only, 5);
  CHECK(test::max_difference(a, b) < 0.01 * b.values[0].x);
}

TEST_CASE("two compact sources give two discs, brightest first", "[light][sun]") {
  const SyntheticDisc sun{glm::normalize(glm::dvec3(-0.3, 0.8, 0.4)), 0.5 * kPi / 180.0, {80000.0, 76000.0, 70000.0}};
  const SyntheticDisc lamp{glm::normalize(glm::dvec3(0.7, 0.1, -0.7)), 1.2 * kPi / 180.0, {4000.0, 3000.0, 1500.0}};
  const light::ExtractionResult found = light::extract_discs(as_environment(synthetic_map(2048, 1024, {lamp, sun})));
  REQUIRE(found.discs.size() == 2);
  CHECK(angle_degrees(found.discs[0].direction, sun.direction) < 0.5);
  CHECK(angle_degrees(found.discs[1].direction, lamp.direction) < 0.5);
  CHECK(relative_error(found.discs[1].irradiance, lamp.radiance * (kPi * std::pow(std::sin(lamp.radius), 2))) < 0.02);
  CHECK(light::extract_discs(as_environment(synthetic_map(2048, 1024, {lamp, sun})), 0, 1).discs.size() == 1);
}

TEST_CASE("a sky without a compact source yields no disc and an unchanged map", "[light][sun]") {
  const image::Image plain = synthetic_map(1024, 512, {});
  const light::ExtractionResult none = light::extract_discs(as_environment(plain));
  CHECK(none.discs.empty());
  CHECK(none.residual.equirect.pixels.empty());  // no copy: the input stands unchanged

  // A broad bright patch: 400 x the sky level over 25 degrees (a bright overcast region, a large window).
  const SyntheticDisc broad{glm::normalize(glm::dvec3(0.2, 0.5, 0.8)), 25.0 * kPi / 180.0, {200.0, 200.0, 200.0}};
  CHECK(light::extract_discs(as_environment(synthetic_map(1024, 512, {broad}))).discs.empty());
  // A pin-point that carries almost nothing (a distant street lamp): below the power fraction.
  const SyntheticDisc speck{glm::normalize(glm::dvec3(-0.6, 0.2, 0.3)), 0.3 * kPi / 180.0, {800.0, 800.0, 800.0}};
  CHECK(light::extract_discs(as_environment(synthetic_map(1024, 512, {speck}))).discs.empty());
}

TEST_CASE("a studio soft box of a few degrees is a compact source: one disc with its energy", "[light][sun]") {
  const SyntheticDisc softbox{glm::normalize(glm::dvec3(0.2, 0.5, 0.8)), 6.0 * kPi / 180.0, {600.0, 600.0, 600.0}};
  const light::ExtractionResult found = light::extract_discs(as_environment(synthetic_map(1024, 512, {softbox})));
  REQUIRE(found.discs.size() == 1);
  CHECK(angle_degrees(found.discs[0].direction, softbox.direction) < 0.5);
  CHECK(relative_error(found.discs[0].irradiance, softbox.radiance * (kPi * std::pow(std::sin(softbox.radius), 2))) < 0.02);
  CHECK(found.discs[0].angular_radius * 180.0 / kPi == Approx(6.0).margin(0.6));
}

TEST_CASE("rotating the lighting rotates its discs as rotating the map does", "[light][sun]") {
  const SyntheticDisc sun{glm::normalize(glm::dvec3(0.6, 0.5, 0.3)), 0.8 * kPi / 180.0, {50000.0, 45000.0, 40000.0}};
  const image::Image map = synthetic_map(1024, 512, {sun});
  // An active yaw of 90 degrees about +Y is a shift of the columns by a quarter turn (phi' = phi - 90).
  image::Image turned = map;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x)
      for (int c = 0; c < 3; ++c) turned.at(x, y, c) = map.at((x + map.width / 4) % map.width, y, c);
  const light::SunRequest sun_auto;
  const light::WindowRequest no_window = light::parse_window_request("none");
  const light::SceneLighting rotated = light::split_environment(as_environment(map), 3, {90.0, 0.0, 0.0}, sun_auto, no_window);
  const light::SceneLighting reference = light::split_environment(as_environment(turned), 3, {0.0, 0.0, 0.0}, sun_auto, no_window);
  REQUIRE(rotated.discs.size() == 1);
  REQUIRE(reference.discs.size() == 1);
  CHECK(angle_degrees(rotated.discs[0].direction, reference.discs[0].direction) < 0.05);
  CHECK(test::max_difference(rotated.sky, reference.sky) < 1e-3 * reference.sky.values[0].x);
}

TEST_CASE("split_environment hands back the sky without its discs: the map's own sky where the sun was", "[light][sun]") {
  const SyntheticDisc sun{glm::normalize(glm::dvec3(-0.4, 0.6, 0.5)), 0.6 * kPi / 180.0, {40000.0, 38000.0, 30000.0}};
  const light::Environment map = as_environment(synthetic_map(512, 256, {sun}));
  const light::WindowRequest no_window = light::parse_window_request("none");
  light::Environment sky_map;
  const light::SceneLighting split = light::split_environment(map, 3, {0.0, 0.0, 0.0}, light::SunRequest{}, no_window, 0, &sky_map);
  REQUIRE(split.discs.size() == 1);
  REQUIRE(sky_map.equirect.width == 512);
  REQUIRE(sky_map.equirect.height == 256);
  double worst = 0.0;  // against the analytic sky, relative
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 512; ++x) {
      const glm::dvec3 expected = sky(direction_at((x + 0.5) / 512, (y + 0.5) / 256));
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(sky_map.equirect.at(x, y, c) - expected[c]) / expected[c]);
    }
  INFO("largest relative difference from the sky without the sun: " << worst);
  CHECK(worst < 0.02);  // the refilled texels interpolate the sky around them; the sun is 1e5 x the sky

  // No disc found (sun none): nothing is handed back.
  light::Environment untouched;
  light::SunRequest none;
  none.mode = light::SunRequest::Mode::none;
  light::split_environment(map, 3, {0.0, 0.0, 0.0}, none, no_window, 0, &untouched);
  CHECK(untouched.equirect.pixels.empty());
}
