// Gauss-Legendre and the Gauss x uniform-phi product rule, against closed-form integrals.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "sh/basis.h"
#include "sh/quadrature.h"

namespace {

// Integral over the unit sphere of x^a y^b z^c: 0 if any exponent is odd, else
// 2 Gamma((a+1)/2) Gamma((b+1)/2) Gamma((c+1)/2) / Gamma((a+b+c+3)/2).
double monomial_integral(int a, int b, int c) {
  if (a % 2 || b % 2 || c % 2) return 0.0;
  return 2.0 * std::exp(std::lgamma((a + 1) / 2.0) + std::lgamma((b + 1) / 2.0) + std::lgamma((c + 1) / 2.0) -
                        std::lgamma((a + b + c + 3) / 2.0));
}

double product_rule_monomial(const prt::sh::SphereQuadrature& q, int a, int b, int c) {
  double sum = 0.0;
  for (std::size_t k = 0; k < q.directions.size(); ++k) {
    const glm::dvec3& d = q.directions[k];
    sum += q.weights[k] * std::pow(d.x, a) * std::pow(d.y, b) * std::pow(d.z, c);
  }
  return sum;
}

}  // namespace

TEST_CASE("Gauss-Legendre matches the textbook rules for n = 1, 2, 3", "[sh][quadrature]") {
  std::vector<double> x, w;
  prt::sh::gauss_legendre(1, x, w);
  REQUIRE(x.size() == 1);
  CHECK(x[0] == 0.0);
  CHECK(w[0] == Approx(2.0).epsilon(1e-15));
  prt::sh::gauss_legendre(2, x, w);
  CHECK(x[0] == Approx(-1.0 / std::sqrt(3.0)).epsilon(1e-15));
  CHECK(x[1] == Approx(1.0 / std::sqrt(3.0)).epsilon(1e-15));
  CHECK(w[0] == Approx(1.0).epsilon(1e-15));
  prt::sh::gauss_legendre(3, x, w);
  CHECK(x[0] == Approx(-std::sqrt(0.6)).epsilon(1e-15));
  CHECK(x[1] == 0.0);
  CHECK(w[0] == Approx(5.0 / 9.0).epsilon(1e-15));
  CHECK(w[1] == Approx(8.0 / 9.0).epsilon(1e-15));
}

TEST_CASE("Gauss-Legendre with n points integrates x^k exactly for k <= 2n - 1", "[sh][quadrature]") {
  std::vector<double> x, w;
  for (int n = 1; n <= 64; ++n) {
    prt::sh::gauss_legendre(n, x, w);
    double weight_sum = 0.0;
    for (int i = 0; i < n; ++i) {
      weight_sum += w[i];
      if (i > 0) REQUIRE(x[i] > x[i - 1]);
      REQUIRE(x[i] == -x[n - 1 - i]);
      REQUIRE(w[i] > 0.0);
    }
    INFO("n = " << n);
    REQUIRE(weight_sum == Approx(2.0).epsilon(1e-14));
    for (int k = 0; k <= 2 * n - 1; ++k) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i) sum += w[i] * std::pow(x[i], k);
      const double exact = k % 2 ? 0.0 : 2.0 / (k + 1.0);
      REQUIRE(std::abs(sum - exact) <= 1e-14);
    }
    // ... and not for degree 2n: the error of x^(2n) is the textbook remainder
    // 2^(2n+1) (n!)^4 / ((2n+1) ((2n)!)^2) (checked while it is well above rounding).
    if (n <= 14) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i) sum += w[i] * std::pow(x[i], 2 * n);
      const double remainder = std::exp((2 * n + 1) * std::log(2.0) + 4.0 * std::lgamma(n + 1.0) -
                                        std::log(2.0 * n + 1.0) - 2.0 * std::lgamma(2.0 * n + 1.0));
      REQUIRE(2.0 / (2.0 * n + 1.0) - sum == Approx(remainder).epsilon(1e-5));
    }
  }
  // Large n: still converged roots.
  prt::sh::gauss_legendre(500, x, w);
  double weight_sum = 0.0;
  for (double wi : w) weight_sum += wi;
  CHECK(weight_sum == Approx(2.0).epsilon(1e-13));
}

TEST_CASE("the product rule integrates every monomial of degree <= max_degree exactly", "[sh][quadrature]") {
  for (int degree = 0; degree <= 16; ++degree) {
    const prt::sh::SphereQuadrature q = prt::sh::gauss_product_quadrature(degree);
    REQUIRE(q.directions.size() == static_cast<std::size_t>((degree / 2 + 1) * (degree + 1)));
    double weight_sum = 0.0;
    for (std::size_t k = 0; k < q.directions.size(); ++k) {
      weight_sum += q.weights[k];
      REQUIRE(std::abs(glm::length(q.directions[k]) - 1.0) <= 1e-15);
    }
    REQUIRE(weight_sum == Approx(4.0 * M_PI).epsilon(1e-14));
    for (int a = 0; a <= degree; ++a)
      for (int b = 0; a + b <= degree; ++b)
        for (int c = 0; a + b + c <= degree; ++c) {
          INFO("degree " << degree << ": x^" << a << " y^" << b << " z^" << c);
          REQUIRE(std::abs(product_rule_monomial(q, a, b, c) - monomial_integral(a, b, c)) <= 1e-13);
        }
    // Degree + 1 is beyond it for some monomial: z^(d+2) for even d (GL) and x^(d+1) (phi) for odd d.
    const double miss = degree % 2 == 0 ? product_rule_monomial(q, 0, 0, degree + 2) - monomial_integral(0, 0, degree + 2)
                                        : product_rule_monomial(q, degree + 1, 0, 0) - monomial_integral(degree + 1, 0, 0);
    REQUIRE(std::abs(miss) > 1e-10);
  }
}

TEST_CASE("the product rule integrates Y_i Y_j to delta_ij up to 16 bands", "[sh][quadrature]") {
  const int bands = 16, count = bands * bands;
  const prt::sh::SphereQuadrature q = prt::sh::gauss_product_quadrature_for_bands(bands, bands);
  REQUIRE(q.directions.size() == 16 * 31);
  std::vector<double> basis(q.directions.size() * count);
  for (std::size_t k = 0; k < q.directions.size(); ++k) prt::sh::eval(bands, q.directions[k], &basis[k * count]);
  double worst = 0.0;
  for (int i = 0; i < count; ++i)
    for (int j = 0; j <= i; ++j) {
      double sum = 0.0;
      for (std::size_t k = 0; k < q.directions.size(); ++k) sum += q.weights[k] * basis[k * count + i] * basis[k * count + j];
      worst = std::max(worst, std::abs(sum - (i == j ? 1.0 : 0.0)));
    }
  CHECK(worst <= 1e-12);
}

TEST_CASE("the product rule keeps every band orthonormal up to kMaxBands (diagonal and neighbours)", "[sh][quadrature]") {
  const int bands = prt::sh::kMaxBands, count = bands * bands;
  const prt::sh::SphereQuadrature q = prt::sh::gauss_product_quadrature_for_bands(bands, bands);
  std::vector<double> gram_diagonal(count, 0.0), gram_next(count, 0.0);
  std::vector<double> y(count);
  for (std::size_t k = 0; k < q.directions.size(); ++k) {
    prt::sh::eval(bands, q.directions[k], y.data());
    for (int i = 0; i < count; ++i) {
      gram_diagonal[i] += q.weights[k] * y[i] * y[i];
      if (i + 1 < count) gram_next[i] += q.weights[k] * y[i] * y[i + 1];
    }
  }
  for (int i = 0; i < count; ++i) {
    REQUIRE(std::abs(gram_diagonal[i] - 1.0) <= 1e-11);
    REQUIRE(std::abs(gram_next[i]) <= 1e-11);
  }
}
