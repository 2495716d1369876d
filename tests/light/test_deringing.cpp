// --window auto (light/deringing.h): no window at all (the shading clamps instead), while the explicit
// Laplacian window with sh::nonnegative_laplacian_lambda's lambda makes ringing lighting non-negative,
// checked on an independent dense direction set (a Fibonacci lattice, not the search grid).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "core/constants.h"
#include "light/deringing.h"
#include "light/disc.h"
#include "light_test_util.h"
#include "sh/window.h"

using namespace prt;

namespace {


// Clamped-cosine factors A_l written out (Ramamoorthi and Hanrahan 2001): pi, 2pi/3, pi/4, 0, -pi/24.
const double kA[5] = {kPi, 2.0 * kPi / 3.0, kPi / 4.0, 0.0, -kPi / 24.0};

// Minimum over 20,000 Fibonacci directions and the three channels of the radiance and irradiance.
void minima(const sh::RgbCoefficients& c, double& radiance, double& irradiance) {
  sh::RgbCoefficients e = c;
  for (int l = 0; l < c.bands; ++l)
    for (int m = -l; m <= l; ++m) e.values[l * (l + 1) + m] *= kA[l];
  radiance = irradiance = 1e300;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt(1.0 - z * z), phi = i * kPi * (3.0 - std::sqrt(5.0));
    const glm::dvec3 d(r * std::cos(phi), r * std::sin(phi), z);
    const glm::dvec3 a = test::evaluate(c, d), b = test::evaluate(e, d);
    radiance = std::min({radiance, a.x, a.y, a.z});
    irradiance = std::min({irradiance, b.x, b.y, b.z});
  }
}

}  // namespace

TEST_CASE("auto window leaves non-negative lighting alone", "[light][window]") {
  sh::RgbCoefficients c(5);
  c.values[0] = {3.0, 3.0, 3.0};
  c.values[2] = {0.5, 0.4, 0.3};  // a gentle gradient along +z: far from negative
  sh::RgbCoefficients windowed = c;
  const light::WindowChoice choice = light::apply_window_request(light::WindowRequest{}, windowed);
  CHECK(choice.window == sh::Window::none);
  CHECK(choice.description == "none");
  CHECK(windowed.values == c.values);
}

TEST_CASE("auto window leaves ringing lighting alone - the Laplacian window of the non-negative lambda removes the ringing", "[light][window]") {
  light::WindowRequest glossy;
  glossy.radiance = true;
  // A small bright disc plus a dim sky, 5 bands: its band-limited radiance rings far below zero.
  light::Disc sun;
  sun.direction = glm::normalize(glm::dvec3(0.3, 0.8, -0.5));
  sun.irradiance = {6.0, 5.0, 4.0};
  sun.angular_radius = 0.5 * kPi / 180.0;
  sh::RgbCoefficients c = light::disc_coefficients(5, sun);
  c.values[0] += glm::dvec3(0.5);
  double before_l, before_e;
  minima(c, before_l, before_e);
  REQUIRE(before_l < -0.1);

  sh::RgbCoefficients unwindowed = c;
  CHECK(light::apply_window_request(glossy, unwindowed).window == sh::Window::none);
  CHECK(unwindowed.values == c.values);

  sh::RgbCoefficients irradiance = c;
  for (int l = 0; l < c.bands; ++l)
    for (int m = -l; m <= l; ++m) irradiance.values[l * (l + 1) + m] *= kA[l];
  const double lambda = std::max(sh::nonnegative_laplacian_lambda(c), sh::nonnegative_laplacian_lambda(irradiance));
  sh::RgbCoefficients windowed = c;
  const light::WindowChoice choice = light::apply_window_request(light::parse_window_request("laplacian", lambda), windowed);
  REQUIRE(choice.window == sh::Window::laplacian);
  double after_l, after_e;
  minima(windowed, after_l, after_e);
  const double mean = c.values[0].z * 0.28209479177387814;
  CHECK(after_l >= -1e-3 * mean);
  CHECK(after_e >= -1e-3 * kPi * mean);

  // Least: 80% of that lambda leaves a clearly negative lobe.
  sh::RgbCoefficients weaker = c;
  sh::apply_window(sh::window_weights(sh::Window::laplacian, 5, 0.8 * choice.param), weaker);
  double weak_l, weak_e;
  minima(weaker, weak_l, weak_e);
  CHECK(std::min(weak_l, weak_e / kPi) < -2e-3 * mean);
}

TEST_CASE("window requests parse and reject bad names", "[light][window]") {
  CHECK(light::parse_window_request("auto").automatic);
  CHECK(light::parse_window_request("hanning", 4.0).window == sh::Window::hanning);
  CHECK_THROWS_WITH(light::parse_window_request("gauss"), Catch::Contains("window: unknown window 'gauss'"));
}
