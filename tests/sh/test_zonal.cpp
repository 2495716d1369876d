// Zonal harmonics, Funk-Hecke convolution, the clamped cosine and irradiance, each against a closed
// form or a brute-force quadrature that does not use the identity under test.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "sh/basis.h"
#include "sh/coefficients.h"
#include "sh/quadrature.h"
#include "sh/zonal.h"
#include "support/random_draws.h"

namespace {

using prt::sh::index;

using prt::test::random_direction;

// Y_l0 at a direction whose z is t, by the slow reference evaluation (not by sh::legendre).
double y_l0(int l, double t) { return prt::sh::eval_reference(l, 0, {std::sqrt(std::max(0.0, 1.0 - t * t)), 0.0, t}); }

// Gauss-Legendre nodes and weights mapped to [a, b].
void gauss_interval(int n, double a, double b, std::vector<double>& x, std::vector<double>& w) {
  prt::sh::gauss_legendre(n, x, w);
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = a + (b - a) * 0.5 * (x[i] + 1.0);
    w[i] *= 0.5 * (b - a);
  }
}

// Integral over the hemisphere about unit n of f(w), by GL in cos(theta) in [0, 1] times uniform phi
// in a frame about n: exact for polynomials of degree < 2 * 24 in w.
template <typename F>
double hemisphere_integral(const glm::dvec3& n, F f) {
  glm::dvec3 t = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  t = glm::normalize(t - glm::dot(t, n) * n);
  const glm::dvec3 b = glm::cross(n, t);
  std::vector<double> u, wu;
  gauss_interval(24, 0.0, 1.0, u, wu);
  const int phi_count = 48;
  double sum = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    const double r = std::sqrt(1.0 - u[i] * u[i]);
    for (int j = 0; j < phi_count; ++j) {
      const double phi = 2.0 * M_PI * (j + 0.5) / phi_count;
      const glm::dvec3 w = r * std::cos(phi) * t + r * std::sin(phi) * b + u[i] * n;
      sum += wu[i] * (2.0 * M_PI / phi_count) * f(w);
    }
  }
  return sum;
}

double sh_value(int bands, const double* c, const glm::dvec3& d) {
  double y[prt::sh::kMaxBands * prt::sh::kMaxBands];
  prt::sh::eval(bands, d, y);
  double s = 0.0;
  for (int i = 0; i < bands * bands; ++i) s += c[i] * y[i];
  return s;
}

}  // namespace

TEST_CASE("clamped cosine factors match the quoted values", "[sh][zonal]") {
  using prt::sh::clamped_cosine_factor;
  CHECK(clamped_cosine_factor(0) == Approx(M_PI).epsilon(1e-15));
  CHECK(clamped_cosine_factor(1) == Approx(2.0 * M_PI / 3.0).epsilon(1e-15));
  CHECK(clamped_cosine_factor(2) == Approx(M_PI / 4.0).epsilon(1e-15));
  CHECK(clamped_cosine_factor(3) == 0.0);
  CHECK(clamped_cosine_factor(4) == Approx(-M_PI / 24.0).epsilon(1e-15));
  CHECK(clamped_cosine_factor(5) == 0.0);
  CHECK(clamped_cosine_factor(6) == Approx(M_PI / 64.0).epsilon(1e-15));
  CHECK(clamped_cosine_factor(8) == Approx(-M_PI / 128.0).epsilon(1e-15));
  for (int l = 3; l < 200; l += 2) REQUIRE(clamped_cosine_factor(l) == 0.0);
  // Ramamoorthi-Hanrahan's constant c4 = 0.886227 is A_0 Y_00.
  CHECK(clamped_cosine_factor(0) * 0.28209479177387814 == Approx(0.886227).epsilon(1e-6));
}

TEST_CASE("clamped cosine zonal coefficients match brute-force quadrature up to l = 63", "[sh][zonal]") {
  // z_l = integral of max(cos theta, 0) Y_l0 = 2 pi integral_0^1 t Y_l0(t) dt; 40 GL nodes are exact for
  // degree 79 >= l + 1.
  std::vector<double> t, w;
  gauss_interval(40, 0.0, 1.0, t, w);
  for (int l = 0; l < 64; ++l) {
    double brute = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) brute += w[i] * 2.0 * M_PI * t[i] * y_l0(l, t[i]);
    INFO("l = " << l);
    REQUIRE(std::abs(prt::sh::clamped_cosine_zonal(l) - brute) <= 1e-14 + 1e-11 * std::abs(brute));
    // The Funk-Hecke factor is sqrt(4 pi / (2l+1)) times the zonal coefficient.
    REQUIRE(std::abs(prt::sh::clamped_cosine_factor(l) - std::sqrt(4.0 * M_PI / (2.0 * l + 1.0)) * brute) <=
            1e-14 + 1e-11 * std::abs(brute));
  }
}

TEST_CASE("clamped cosine factors stay accurate for large l (lgamma form)", "[sh][zonal]") {
  for (int l = 2; l <= 2000; l += 2) {
    const double log_central = std::lgamma(l + 1.0) - 2.0 * std::lgamma(l / 2 + 1.0) - l * std::log(2.0);
    const double sign = (l / 2 - 1) % 2 == 0 ? 1.0 : -1.0;
    const double expected = 2.0 * M_PI * sign / ((l + 2.0) * (l - 1.0)) * std::exp(log_central);
    INFO("l = " << l);
    // lgamma's own error grows like l * eps; the product form is the more accurate of the two.
    REQUIRE(prt::sh::clamped_cosine_factor(l) == Approx(expected).epsilon(1e-10));
  }
}

TEST_CASE("legendre and its derivative match the reference basis and finite differences", "[sh][zonal]") {
  for (int l = 0; l < 40; ++l) {
    const double k = std::sqrt((2.0 * l + 1.0) / (4.0 * M_PI));
    for (double x : {-1.0, -0.73, -0.2, 0.0, 0.31, 0.9, 1.0}) {
      REQUIRE(std::abs(prt::sh::legendre(l, x) - y_l0(l, x) / k) <= 1e-12);
    }
    REQUIRE(prt::sh::legendre_derivative(l, 1.0) == Approx(l * (l + 1.0) / 2.0).epsilon(1e-13));
    REQUIRE(prt::sh::legendre_derivative(l, -1.0) ==
            Approx((l % 2 == 0 ? -1.0 : 1.0) * l * (l + 1.0) / 2.0).epsilon(1e-13));
    for (double x : {-0.73, -0.2, 0.31, 0.9}) {
      const double closed = l == 0 ? 0.0 : l * (x * prt::sh::legendre(l, x) - prt::sh::legendre(l - 1, x)) / (x * x - 1.0);
      REQUIRE(std::abs(prt::sh::legendre_derivative(l, x) - closed) <= 1e-11 * (1.0 + l * l));
    }
  }
}

TEST_CASE("zonal_to_sh along +z reproduces the zonal coefficients", "[sh][zonal]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int bands : {1, 3, 8, 16, 32}) {
    std::vector<double> zonal(static_cast<std::size_t>(bands));
    for (double& z : zonal) z = u(rng);
    std::vector<double> out(static_cast<std::size_t>(bands * bands));
    prt::sh::zonal_to_sh(bands, zonal.data(), {0, 0, 1}, out.data());
    for (int l = 0; l < bands; ++l)
      for (int m = -l; m <= l; ++m) REQUIRE(std::abs(out[index(l, m)] - (m == 0 ? zonal[l] : 0.0)) <= 1e-13);
  }
}

TEST_CASE("zonal_to_sh in direction a gives g(d) = f(a . d) pointwise", "[sh][zonal]") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int bands : {2, 3, 5, 9, 16}) {
    std::vector<double> zonal(static_cast<std::size_t>(bands));
    for (double& z : zonal) z = u(rng);
    for (int trial = 0; trial < 10; ++trial) {
      const glm::dvec3 a = random_direction(rng);
      std::vector<double> g(static_cast<std::size_t>(bands * bands));
      prt::sh::zonal_to_sh(bands, zonal.data(), a, g.data());
      for (int k = 0; k < 10; ++k) {
        const glm::dvec3 d = random_direction(rng);
        const double t = glm::dot(a, d);
        double f = 0.0;  // f(t) = sum_l z_l Y_l0(t), by the reference basis
        for (int l = 0; l < bands; ++l) f += zonal[l] * y_l0(l, t);
        REQUIRE(std::abs(sh_value(bands, g.data(), d) - f) <= 1e-12);
        REQUIRE(std::abs(prt::sh::zonal_value(bands, zonal.data(), t) - f) <= 1e-12);
      }
    }
  }
}

TEST_CASE("Funk-Hecke convolution matches brute-force integration over the sphere", "[sh][zonal]") {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  const int bands = 8;
  std::vector<double> f(bands * bands);
  for (double& c : f) c = normal(rng);

  // Kernel h(t) = exp(2 t), not band-limited; its zonal coefficients by 1D quadrature.
  std::vector<double> t, w;
  gauss_interval(60, -1.0, 1.0, t, w);
  std::vector<double> h(bands, 0.0);
  for (int l = 0; l < bands; ++l)
    for (std::size_t i = 0; i < t.size(); ++i) h[l] += w[i] * 2.0 * M_PI * std::exp(2.0 * t[i]) * y_l0(l, t[i]);

  std::vector<double> convolved = f;
  prt::sh::convolve_zonal(bands, h.data(), convolved.data());

  // Brute force: (h * f)(a) = integral of h(a . d) f(d) dd over a fine product rule (the integrand
  // is smooth, so degree 80 converges to rounding).
  const prt::sh::SphereQuadrature q = prt::sh::gauss_product_quadrature(80);
  std::vector<double> f_at(q.directions.size());
  for (std::size_t k = 0; k < q.directions.size(); ++k) f_at[k] = sh_value(bands, f.data(), q.directions[k]);
  for (int trial = 0; trial < 6; ++trial) {
    const glm::dvec3 a = random_direction(rng);
    double brute = 0.0;
    for (std::size_t k = 0; k < q.directions.size(); ++k)
      brute += q.weights[k] * std::exp(2.0 * glm::dot(a, q.directions[k])) * f_at[k];
    REQUIRE(sh_value(bands, convolved.data(), a) == Approx(brute).epsilon(1e-11).margin(1e-11));
  }

  // The RGB form scales every channel the same way.
  prt::sh::RgbCoefficients rgb(bands);
  for (int i = 0; i < bands * bands; ++i) rgb.values[i] = glm::dvec3(f[i], 2.0 * f[i], -f[i]);
  prt::sh::convolve_zonal(h.data(), rgb);
  for (int i = 0; i < bands * bands; ++i) {
    REQUIRE(rgb.values[i].x == convolved[i]);
    REQUIRE(rgb.values[i].y == 2.0 * convolved[i]);
    REQUIRE(rgb.values[i].z == -convolved[i]);
  }
}

TEST_CASE("irradiance of a constant environment is pi times the radiance", "[sh][zonal]") {
  std::mt19937_64 rng(5);
  for (int bands : {1, 2, 3, 4, 9, 16, 32}) {
    prt::sh::RgbCoefficients radiance(bands);
    const glm::dvec3 l(0.7, 1.3, 2.0);
    radiance.values[0] = 2.0 * std::sqrt(M_PI) * l;
    for (int trial = 0; trial < 5; ++trial) {
      const glm::dvec3 e = prt::sh::irradiance(radiance, random_direction(rng));
      REQUIRE(e.x == Approx(M_PI * l.x).epsilon(1e-14));
      REQUIRE(e.y == Approx(M_PI * l.y).epsilon(1e-14));
      REQUIRE(e.z == Approx(M_PI * l.z).epsilon(1e-14));
    }
  }
}

TEST_CASE("irradiance matches brute-force integration of max(n . w, 0) L(w)", "[sh][zonal]") {
  std::mt19937_64 rng(9);
  std::normal_distribution<double> normal;
  for (int bands = 1; bands <= 12; ++bands) {
    std::vector<double> radiance(bands * bands);
    for (double& c : radiance) c = normal(rng);
    prt::sh::RgbCoefficients rgb(bands);
    for (int i = 0; i < bands * bands; ++i) rgb.values[i] = glm::dvec3(radiance[i], -3.0 * radiance[i], 0.5);
    for (int trial = 0; trial < 8; ++trial) {
      const glm::dvec3 n = random_direction(rng);
      const double brute = hemisphere_integral(n, [&](const glm::dvec3& w) {
        return glm::dot(n, w) * sh_value(bands, radiance.data(), w);
      });
      INFO("bands = " << bands);
      REQUIRE(prt::sh::irradiance(bands, radiance.data(), n) == Approx(brute).epsilon(1e-12).margin(1e-12));
      REQUIRE(prt::sh::irradiance(rgb, n).x == Approx(brute).epsilon(1e-12).margin(1e-12));
      REQUIRE(prt::sh::irradiance(rgb, n).y == Approx(-3.0 * brute).epsilon(1e-12).margin(1e-12));
    }
  }
}
