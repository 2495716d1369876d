// Windows against ringing: the documented formulas and defaults, w_0 = 1 and monotone weights, and
// that each default actually reduces ringing of the band-limited clamped cosine and of a directional
// light (a delta), measured on a dense grid of angles.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "sh/basis.h"
#include "sh/window.h"
#include "sh/zonal.h"
#include "support/random_draws.h"

namespace {

using prt::sh::Window;

// Minimum over 20001 angles of the zonal function sum_l w_l zonal_l Y_l0, and its maximum.
void zonal_range(int bands, const std::vector<double>& zonal, const std::vector<double>& w, double& lo,
                 double& hi) {
  std::vector<double> windowed(static_cast<std::size_t>(bands));
  for (int l = 0; l < bands; ++l) windowed[l] = w[l] * zonal[l];
  lo = INFINITY;
  hi = -INFINITY;
  for (int i = 0; i <= 20000; ++i) {
    const double v = prt::sh::zonal_value(bands, windowed.data(), std::cos(M_PI * i / 20000.0));
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
}

std::vector<double> clamped_cosine(int bands) {
  std::vector<double> z(static_cast<std::size_t>(bands));
  for (int l = 0; l < bands; ++l) z[l] = prt::sh::clamped_cosine_zonal(l);
  return z;
}

// Zonal coefficients of a delta at +z: Y_l0(+z) = sqrt((2l+1)/(4 pi)).
std::vector<double> delta(int bands) {
  std::vector<double> z(static_cast<std::size_t>(bands));
  for (int l = 0; l < bands; ++l) z[l] = std::sqrt((2.0 * l + 1.0) / (4.0 * M_PI));
  return z;
}

using prt::test::random_direction;

}  // namespace

TEST_CASE("window names round-trip and bad names are reported", "[sh][window]") {
  for (Window w : {Window::none, Window::hanning, Window::lanczos, Window::laplacian})
    REQUIRE(prt::sh::parse_window(prt::sh::window_name(w)) == w);
  try {
    prt::sh::parse_window("gaussian");
    FAIL("expected prt::Error");
  } catch (const prt::Error& e) {
    CHECK(std::string(e.what()).find("'gaussian'") != std::string::npos);
  }
}

TEST_CASE("window weights start at 1, never increase and stay in [0, 1]", "[sh][window]") {
  for (Window w : {Window::none, Window::hanning, Window::lanczos, Window::laplacian}) {
    for (int bands = 1; bands <= prt::sh::kMaxBands; ++bands) {
      for (double param : {0.0, 1.5, 3.0, 7.0, 0.01, 1e-5}) {
        const std::vector<double> weights = prt::sh::window_weights(w, bands, param);
        REQUIRE(weights.size() == static_cast<std::size_t>(bands));
        REQUIRE(weights[0] == 1.0);
        for (int l = 1; l < bands; ++l) {
          REQUIRE(weights[l] <= weights[l - 1]);
          REQUIRE(weights[l] >= 0.0);
        }
      }
    }
  }
}

TEST_CASE("window weights follow the documented formulas and defaults", "[sh][window]") {
  using prt::sh::window_weights;
  // Defaults at 3 bands: W = 4 for Hanning and Lanczos, lambda = 1/144 for the Laplacian.
  CHECK(prt::sh::default_window_param(Window::hanning, 3) == 4.0);
  CHECK(prt::sh::default_window_param(Window::lanczos, 3) == 4.0);
  CHECK(prt::sh::default_window_param(Window::laplacian, 3) == Approx(1.0 / 144.0).epsilon(1e-15));
  auto han = window_weights(Window::hanning, 3);
  CHECK(han[1] == Approx(0.85355339059327373).epsilon(1e-14));  // (1 + cos(pi/4)) / 2
  CHECK(han[2] == Approx(0.5).epsilon(1e-14));
  auto lan = window_weights(Window::lanczos, 3);
  CHECK(lan[1] == Approx(0.90031631615710606).epsilon(1e-14));  // sin(pi/4) / (pi/4)
  CHECK(lan[2] == Approx(0.63661977236758134).epsilon(1e-14));  // 2 / pi
  auto lap = window_weights(Window::laplacian, 3);
  CHECK(lap[1] == Approx(36.0 / 37.0).epsilon(1e-14));
  CHECK(lap[2] == Approx(0.8).epsilon(1e-14));
  // The default Laplacian halves the first dropped band at every band count.
  for (int bands = 1; bands < 32; ++bands) {
    const double lambda = prt::sh::default_window_param(Window::laplacian, bands);
    REQUIRE(window_weights(Window::laplacian, bands + 1, lambda)[bands] == Approx(0.5).epsilon(1e-14));
  }

  // Explicit parameters, including the cut-off to zero at l >= W.
  han = window_weights(Window::hanning, 5, 2.0);
  CHECK(han[1] == Approx(0.5).epsilon(1e-14));
  CHECK(han[2] == 0.0);
  CHECK(han[4] == 0.0);
  lan = window_weights(Window::lanczos, 5, 2.5);
  CHECK(lan[1] == Approx(std::sin(M_PI / 2.5) / (M_PI / 2.5)).epsilon(1e-14));
  CHECK(lan[2] == Approx(std::sin(2.0 * M_PI / 2.5) / (2.0 * M_PI / 2.5)).epsilon(1e-14));
  CHECK(lan[3] == 0.0);
  lap = window_weights(Window::laplacian, 4, 0.01);
  CHECK(lap[1] == Approx(1.0 / 1.04).epsilon(1e-14));
  CHECK(lap[2] == Approx(1.0 / 1.36).epsilon(1e-14));
  CHECK(lap[3] == Approx(1.0 / 2.44).epsilon(1e-14));
  for (double w : window_weights(Window::none, 6, 3.0)) CHECK(w == 1.0);
}

TEST_CASE("apply_window scales every coefficient of band l by w_l", "[sh][window]") {
  const std::vector<double> w = {1.0, 0.5, 0.25};
  prt::sh::RgbCoefficients c(3);
  for (int i = 0; i < 9; ++i) c.values[i] = glm::dvec3(i + 1.0, -(i + 1.0), 2.0);
  prt::sh::apply_window(w, c);
  std::vector<double> s(9, 4.0);
  prt::sh::apply_window(w, 3, s.data());
  for (int i = 0; i < 9; ++i) {
    const double wl = w[prt::sh::band_of(i)];
    REQUIRE(c.values[i].x == (i + 1.0) * wl);
    REQUIRE(c.values[i].y == -(i + 1.0) * wl);
    REQUIRE(c.values[i].z == 2.0 * wl);
    REQUIRE(s[i] == 4.0 * wl);
  }
}

TEST_CASE("default windows reduce ringing of the clamped cosine and of a directional light", "[sh][window]") {
  for (int bands = 2; bands <= prt::sh::kMaxBands; ++bands) {
    const std::vector<double> none(static_cast<std::size_t>(bands), 1.0);
    double cc_lo0, cc_hi0, d_lo0, d_hi0;
    zonal_range(bands, clamped_cosine(bands), none, cc_lo0, cc_hi0);
    zonal_range(bands, delta(bands), none, d_lo0, d_hi0);
    REQUIRE(cc_lo0 < 0.0);  // the truncated clamped cosine rings below zero
    for (Window w : {Window::hanning, Window::lanczos, Window::laplacian}) {
      const std::vector<double> weights = prt::sh::window_weights(w, bands);
      double cc_lo, cc_hi, d_lo, d_hi;
      zonal_range(bands, clamped_cosine(bands), weights, cc_lo, cc_hi);
      zonal_range(bands, delta(bands), weights, d_lo, d_hi);
      INFO("bands = " << bands << ", window " << prt::sh::window_name(w));
      REQUIRE(std::abs(cc_lo) < std::abs(cc_lo0));
      // The delta's negative lobe relative to its peak.
      REQUIRE(std::abs(d_lo / d_hi) < std::abs(d_lo0 / d_hi0));
    }
  }
  // At 3 bands the unwindowed clamped cosine dips to -0.0396; the documented windowed minima.
  double lo, hi;
  zonal_range(3, clamped_cosine(3), std::vector<double>(3, 1.0), lo, hi);
  CHECK(lo == Approx(-0.0396).margin(1e-4));
  zonal_range(3, clamped_cosine(3), prt::sh::window_weights(Window::hanning, 3), lo, hi);
  CHECK(lo == Approx(-0.0224).margin(1e-4));
  zonal_range(3, clamped_cosine(3), prt::sh::window_weights(Window::lanczos, 3), lo, hi);
  CHECK(lo == Approx(-0.0192).margin(1e-4));
  zonal_range(3, clamped_cosine(3), prt::sh::window_weights(Window::laplacian, 3), lo, hi);
  CHECK(lo == Approx(-0.0328).margin(1e-4));
}

TEST_CASE("the smallest Laplacian lambda making the windowed clamped cosine non-negative", "[sh][window]") {
  // 2 bands: 1/4 + w_1 t / 2 >= 0 needs w_1 <= 1/2, i.e. lambda = 1/4 exactly.
  std::vector<double> z2 = clamped_cosine(2);
  CHECK(prt::sh::nonnegative_laplacian_lambda_zonal(2, z2.data()) == Approx(0.25).epsilon(1e-8));
  for (int bands : {3, 5, 9, 16}) {
    const std::vector<double> z = clamped_cosine(bands);
    const double lambda = prt::sh::nonnegative_laplacian_lambda_zonal(bands, z.data());
    INFO("bands = " << bands << ", lambda = " << lambda);
    REQUIRE(lambda > 0.17);
    REQUIRE(lambda < 0.19);
    double lo, hi;
    zonal_range(bands, z, prt::sh::window_weights(Window::laplacian, bands, lambda), lo, hi);
    REQUIRE(lo >= -1e-7);
    zonal_range(bands, z, prt::sh::window_weights(Window::laplacian, bands, 0.99 * lambda), lo, hi);
    REQUIRE(lo < 0.0);  // the smallest such lambda
  }
  // A non-negative zonal function needs no window.
  std::vector<double> z = {1.0, 0.5};
  CHECK(prt::sh::nonnegative_laplacian_lambda_zonal(2, z.data()) == 0.0);
}

TEST_CASE("the smallest Laplacian lambda making a directional light non-negative", "[sh][window]") {
  std::mt19937_64 rng(4);
  for (int bands : {3, 6}) {
    // A delta along a random axis, by its zonal coefficients; the full-sphere search must agree with
    // the zonal one to the resolution of its grid.
    const std::vector<double> zd = delta(bands);
    const glm::dvec3 a = random_direction(rng);
    std::vector<double> c(static_cast<std::size_t>(bands * bands));
    prt::sh::zonal_to_sh(bands, zd.data(), a, c.data());
    const double lambda_zonal = prt::sh::nonnegative_laplacian_lambda_zonal(bands, zd.data());
    const double lambda = prt::sh::nonnegative_laplacian_lambda(bands, c.data());
    INFO("bands = " << bands);
    REQUIRE(lambda == Approx(lambda_zonal).epsilon(0.02));
    // The windowed light, checked at many random directions.
    std::vector<double> windowed = c;
    prt::sh::apply_window(prt::sh::window_weights(Window::laplacian, bands, lambda), bands, windowed.data());
    double y[prt::sh::kMaxBands * prt::sh::kMaxBands];
    double lo = INFINITY;
    for (int k = 0; k < 20000; ++k) {
      prt::sh::eval(bands, random_direction(rng), y);
      double v = 0.0;
      for (int i = 0; i < bands * bands; ++i) v += windowed[i] * y[i];
      lo = std::min(lo, v);
    }
    REQUIRE(lo >= -1e-3 * windowed[0]);

    // RGB: the largest channel lambda (a weaker light in green needs the same lambda: it scales).
    prt::sh::RgbCoefficients rgb(bands);
    for (int i = 0; i < bands * bands; ++i) rgb.values[i] = glm::dvec3(c[i], 0.1 * c[i], 0.0);
    rgb.values[0].z = 1.0;  // a constant blue channel needs none
    REQUIRE(prt::sh::nonnegative_laplacian_lambda(rgb) == Approx(lambda).epsilon(1e-6));
  }
  // 3 bands: the delta kernel 1 + 3 w_1 t + 5 w_2 P_2(t) needs lambda = 1/4 (w_1 = 1/2, w_2 = 1/10).
  const std::vector<double> d3 = delta(3);
  CHECK(prt::sh::nonnegative_laplacian_lambda_zonal(3, d3.data()) == Approx(0.25).epsilon(1e-6));
}

TEST_CASE("no Laplacian lambda helps a function whose mean is not positive", "[sh][window]") {
  std::vector<double> c = {0.0, 1.0, 0.0, 0.0};
  CHECK_THROWS_AS(prt::sh::nonnegative_laplacian_lambda(2, c.data()), prt::Error);
  std::vector<double> z = {-0.1, 1.0};
  CHECK_THROWS_AS(prt::sh::nonnegative_laplacian_lambda_zonal(2, z.data()), prt::Error);
}
