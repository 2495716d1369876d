// Analytic lights against brute-force projection of the function each one defines, by quadratures
// laid out around the light's own axis so that the integrands are polynomials on each piece (exact),
// and the directional light's normalisation (exit radiance 1 facing it).
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "light/analytic.h"
#include "sh/basis.h"
#include "sh/quadrature.h"
#include "sh/zonal.h"
#include "support/random_draws.h"

namespace {

using prt::test::random_direction;

// Calls f(w, weight) for a rule over the cap 1 - width <= axis . w <= 1 (width in (0, 2]): Gauss-Legendre
// in axis . w times uniform phi about the axis, exact for polynomials of degree < 2 * 24 in w. The
// width is passed (not cos) so that tiny caps keep their relative accuracy.
template <typename F>
void cap_rule(const glm::dvec3& axis, double width, F f) {
  glm::dvec3 t = std::abs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  t = glm::normalize(t - glm::dot(t, axis) * axis);
  const glm::dvec3 b = glm::cross(axis, t);
  std::vector<double> x, w;
  prt::sh::gauss_legendre(24, x, w);
  const int phi_count = 48;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double c = 1.0 - width * 0.5 * (1.0 - x[i]);
    const double s = std::sqrt(std::max(0.0, (1.0 - c) * (1.0 + c)));
    for (int j = 0; j < phi_count; ++j) {
      const double phi = 2.0 * M_PI * (j + 0.5) / phi_count;
      f(s * std::cos(phi) * t + s * std::sin(phi) * b + c * axis, w[i] * 0.5 * width * 2.0 * M_PI / phi_count);
    }
  }
}

// Brute-force projection of colour times the indicator of the cap 1 - width <= axis . w <= 1.
std::vector<glm::dvec3> project_cap(int bands, const glm::dvec3& axis, double width, const glm::dvec3& colour) {
  std::vector<glm::dvec3> c(static_cast<std::size_t>(bands * bands), glm::dvec3(0.0));
  std::vector<double> y(static_cast<std::size_t>(bands * bands));
  cap_rule(axis, width, [&](const glm::dvec3& w, double weight) {
    prt::sh::eval(bands, w, y.data());
    for (int i = 0; i < bands * bands; ++i) c[i] += weight * y[i] * colour;
  });
  return c;
}

void require_close(const prt::sh::RgbCoefficients& got, const std::vector<glm::dvec3>& want, double tolerance) {
  REQUIRE(got.values.size() == want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    INFO("coefficient " << i);
    for (int k = 0; k < 3; ++k) REQUIRE(std::abs(got.values[i][k] - want[i][k]) <= tolerance);
  }
}

}  // namespace

TEST_CASE("constant light has only c_0 = 2 sqrt(pi) v, as its projection", "[light][analytic]") {
  const glm::dvec3 v(0.5, 1.0, 2.5);
  for (int bands : {1, 3, 9, 32}) {
    const prt::sh::RgbCoefficients c = prt::light::constant_light(bands, v);
    REQUIRE(c.bands == bands);
    REQUIRE(c.values[0].x == Approx(2.0 * std::sqrt(M_PI) * 0.5).epsilon(1e-15));
    REQUIRE(c.values[0].z == Approx(2.0 * std::sqrt(M_PI) * 2.5).epsilon(1e-15));
    for (int i = 1; i < bands * bands; ++i) REQUIRE(c.values[i] == glm::dvec3(0.0));
    if (bands <= 9) require_close(c, project_cap(bands, {0, 0, 1}, 2.0, v), 1e-13);
  }
}

TEST_CASE("cone light matches brute-force projection of the cap", "[light][analytic]") {
  std::mt19937_64 rng(21);
  const glm::dvec3 radiance(3.0, 1.0, 0.25);
  for (int bands : {1, 2, 3, 6, 9, 16}) {
    for (double angle : {0.05, 0.3, 1.0, M_PI / 2.0, 2.5, M_PI}) {
      const glm::dvec3 axis = random_direction(rng);
      const double width = 2.0 * std::sin(angle / 2.0) * std::sin(angle / 2.0);  // 1 - cos a
      INFO("bands " << bands << ", half angle " << angle);
      require_close(prt::light::cone_light(bands, axis, angle, radiance),
                    project_cap(bands, axis, width, radiance), 1e-12);
    }
  }
}

TEST_CASE("cap zonal coefficients: the Legendre identity, tiny caps, the full sphere", "[light][analytic]") {
  // integral_{cos a}^1 P_l = (P_(l-1)(cos a) - P_(l+1)(cos a)) / (2l+1), used directly for moderate a.
  for (double angle : {0.4, 1.2, 2.0, 3.0}) {
    double zonal[prt::sh::kMaxBands];
    prt::light::cap_zonal(prt::sh::kMaxBands, angle, zonal);
    const double c = std::cos(angle);
    for (int l = 1; l < prt::sh::kMaxBands; ++l) {
      const double identity = 2.0 * M_PI * std::sqrt((2.0 * l + 1.0) / (4.0 * M_PI)) *
                              (prt::sh::legendre(l - 1, c) - prt::sh::legendre(l + 1, c)) / (2.0 * l + 1.0);
      REQUIRE(zonal[l] == Approx(identity).margin(1e-13));
    }
  }
  // A tiny cap of solid angle 2 pi (1 - cos a) ~ pi a^2: z_l -> K_l * solid angle, to relative 1e-9
  // even where P_(l-1) - P_(l+1) would cancel to a few digits.
  const double a = 1e-5;
  double zonal[prt::sh::kMaxBands];
  prt::light::cap_zonal(prt::sh::kMaxBands, a, zonal);
  const double solid_angle = 4.0 * M_PI * std::sin(a / 2.0) * std::sin(a / 2.0);
  for (int l = 0; l < prt::sh::kMaxBands; ++l) {
    // integral_c^1 P_l = (1 - c) (1 - l (l+1) (1 - c) / 4 + O((1 - c)^2)).
    const double expected = std::sqrt((2.0 * l + 1.0) / (4.0 * M_PI)) * solid_angle *
                            (1.0 - l * (l + 1.0) * (solid_angle / (2.0 * M_PI)) / 4.0);
    REQUIRE(zonal[l] == Approx(expected).epsilon(1e-12));
  }
  // The whole sphere: only the constant term.
  prt::light::cap_zonal(8, M_PI, zonal);
  CHECK(zonal[0] == Approx(2.0 * std::sqrt(M_PI)).epsilon(1e-15));
  for (int l = 1; l < 8; ++l) CHECK(std::abs(zonal[l]) <= 1e-15);
}

TEST_CASE("hemisphere light matches brute-force projection of sky and ground", "[light][analytic]") {
  std::mt19937_64 rng(8);
  const glm::dvec3 sky(0.4, 0.6, 1.0), ground(0.3, 0.2, 0.1);
  for (int bands : {1, 2, 3, 5, 9, 16}) {
    for (int trial = 0; trial < 3; ++trial) {
      const glm::dvec3 up = trial == 0 ? glm::dvec3(0, 1, 0) : random_direction(rng);
      std::vector<glm::dvec3> want = project_cap(bands, up, 1.0, sky);
      const std::vector<glm::dvec3> lower = project_cap(bands, -up, 1.0, ground);
      for (std::size_t i = 0; i < want.size(); ++i) want[i] += lower[i];
      INFO("bands " << bands);
      require_close(prt::light::hemisphere_light(bands, up, sky, ground), want, 1e-13);
    }
  }
  // Equal sky and ground is a constant light.
  const prt::sh::RgbCoefficients same = prt::light::hemisphere_light(4, {0, 1, 0}, sky, sky);
  const prt::sh::RgbCoefficients constant = prt::light::constant_light(4, sky);
  for (int i = 0; i < 16; ++i)
    for (int k = 0; k < 3; ++k) REQUIRE(std::abs(same.values[i][k] - constant.values[i][k]) <= 1e-15);
}

TEST_CASE("a directional light gives exit radiance 1 on an albedo-1 Lambert surface facing it", "[light][analytic]") {
  std::mt19937_64 rng(2);
  CHECK(prt::light::directional_light_scale(1) == Approx(4.0 * M_PI).epsilon(1e-15));
  CHECK(prt::light::directional_light_scale(2) == Approx(4.0 * M_PI / 3.0).epsilon(1e-15));
  CHECK(prt::light::directional_light_scale(3) == Approx(16.0 * M_PI / 17.0).epsilon(1e-15));
  CHECK(prt::light::directional_light_scale(4) == Approx(16.0 * M_PI / 17.0).epsilon(1e-15));
  CHECK(prt::light::directional_light_scale(5) == Approx(32.0 * M_PI / 31.0).epsilon(1e-15));
  CHECK(prt::light::directional_light_scale(6) == Approx(32.0 * M_PI / 31.0).epsilon(1e-15));
  const glm::dvec3 colour(1.0, 0.5, 2.0);
  for (int bands = 1; bands <= 9; ++bands) {
    for (int trial = 0; trial < 5; ++trial) {
      const glm::dvec3 d = random_direction(rng);
      const prt::sh::RgbCoefficients light = prt::light::directional_light(bands, 3.0 * d, colour);
      const glm::dvec3 exit = prt::sh::irradiance(light, d) / M_PI;
      INFO("bands " << bands);
      REQUIRE(exit.x == Approx(1.0).epsilon(1e-13));
      REQUIRE(exit.y == Approx(0.5).epsilon(1e-13));
      REQUIRE(exit.z == Approx(2.0).epsilon(1e-13));
    }
  }
}

TEST_CASE("directional light irradiance matches brute-force integration of max(n . w, 0) L(w)", "[light][analytic]") {
  std::mt19937_64 rng(13);
  for (int bands = 1; bands <= 9; ++bands) {
    const glm::dvec3 d = random_direction(rng);
    const prt::sh::RgbCoefficients light = prt::light::directional_light(bands, d, glm::dvec3(1.0));
    std::vector<double> y(static_cast<std::size_t>(bands * bands));
    for (int trial = 0; trial < 6; ++trial) {
      const glm::dvec3 n = trial == 0 ? d : random_direction(rng);
      // The band-limited light times the cosine over the hemisphere about n (a polynomial there).
      double brute = 0.0;
      cap_rule(n, 1.0, [&](const glm::dvec3& w, double weight) {
        prt::sh::eval(bands, w, y.data());
        double radiance = 0.0;
        for (int i = 0; i < bands * bands; ++i) radiance += light.values[i].x * y[i];
        brute += weight * glm::dot(n, w) * radiance;
      });
      INFO("bands " << bands << ", trial " << trial);
      REQUIRE(prt::sh::irradiance(light, n).x == Approx(brute).epsilon(1e-12).margin(1e-12));
    }
  }
}

TEST_CASE("analytic lights reject bad input with prt::Error", "[light][analytic]") {
  using prt::light::cone_light;
  CHECK_THROWS_AS(prt::light::directional_light(0, {0, 1, 0}, glm::dvec3(1.0)), prt::Error);
  CHECK_THROWS_AS(prt::light::directional_light(prt::sh::kMaxBands + 1, {0, 1, 0}, glm::dvec3(1.0)), prt::Error);
  CHECK_THROWS_AS(prt::light::directional_light(3, {0, 0, 0}, glm::dvec3(1.0)), prt::Error);
  CHECK_THROWS_AS(prt::light::directional_light(3, {NAN, 0, 1}, glm::dvec3(1.0)), prt::Error);
  CHECK_THROWS_AS(cone_light(3, {0, 1, 0}, 0.0, glm::dvec3(1.0)), prt::Error);
  CHECK_THROWS_AS(cone_light(3, {0, 1, 0}, 3.2, glm::dvec3(1.0)), prt::Error);
  CHECK_THROWS_AS(prt::light::hemisphere_light(3, {0, 0, 0}, glm::dvec3(1.0), glm::dvec3(0.0)), prt::Error);
  CHECK_THROWS_AS(prt::light::constant_light(0, glm::dvec3(1.0)), prt::Error);
  CHECK_NOTHROW(cone_light(3, {0, 1, 0}, M_PI, glm::dvec3(1.0)));
}
