// The SH basis against its definition: the closed-form table of the first 9 functions
// (docs/conventions.md), the reference evaluation, and the fast paths.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "sh/basis.h"
#include "support/random_draws.h"

namespace {
using prt::test::random_direction;

// Closed forms of the first 9 real SH with the Condon-Shortley phase.
double closed_form(int i, const glm::dvec3& d) {
  const double x = d.x, y = d.y, z = d.z;
  switch (i) {
    case 0: return 0.5 * std::sqrt(1.0 / M_PI);
    case 1: return -std::sqrt(3.0 / (4.0 * M_PI)) * y;
    case 2: return std::sqrt(3.0 / (4.0 * M_PI)) * z;
    case 3: return -std::sqrt(3.0 / (4.0 * M_PI)) * x;
    case 4: return 0.5 * std::sqrt(15.0 / M_PI) * x * y;
    case 5: return -0.5 * std::sqrt(15.0 / M_PI) * y * z;
    case 6: return 0.25 * std::sqrt(5.0 / M_PI) * (3.0 * z * z - 1.0);
    case 7: return -0.5 * std::sqrt(15.0 / M_PI) * x * z;
    case 8: return 0.25 * std::sqrt(15.0 / M_PI) * (x * x - y * y);
  }
  return NAN;
}
}  // namespace

TEST_CASE("index and band_of are inverse", "[sh]") {
  for (int l = 0; l < prt::sh::kMaxBands; ++l)
    for (int m = -l; m <= l; ++m) REQUIRE(prt::sh::band_of(prt::sh::index(l, m)) == l);
  CHECK(prt::sh::index(2, -2) == 4);
  CHECK(prt::sh::coefficient_count(5) == 25);
}

TEST_CASE("the first 9 basis functions match their closed forms to 1e-14", "[sh]") {
  std::mt19937_64 rng(1);
  CHECK(closed_form(1, {0, 1, 0}) == Approx(-0.4886025119).epsilon(1e-9));
  for (int trial = 0; trial < 200; ++trial) {
    glm::dvec3 d = random_direction(rng);
    double fast[9];
    prt::sh::eval(3, d, fast);
    for (int i = 0; i < 9; ++i) {
      int l = prt::sh::band_of(i), m = i - l * (l + 1);
      REQUIRE(std::abs(prt::sh::eval_reference(l, m, d) - closed_form(i, d)) <= 1e-14);
      REQUIRE(std::abs(fast[i] - closed_form(i, d)) <= 1e-14);
    }
  }
}

TEST_CASE("recurrence evaluation matches the reference for every band up to kMaxBands", "[sh]") {
  std::mt19937_64 rng(2);
  const int bands = prt::sh::kMaxBands;
  std::vector<double> out(bands * bands);
  for (int trial = 0; trial < 50; ++trial) {
    glm::dvec3 d = random_direction(rng);
    prt::sh::eval(bands, d, out.data());
    for (int l = 0; l < bands; ++l)
      for (int m = -l; m <= l; ++m) {
        double ref = prt::sh::eval_reference(l, m, d);
        // Relative to the band's size: |Y_lm| <= sqrt((2l+1)/(4pi)).
        double scale = std::sqrt((2.0 * l + 1.0) / (4.0 * M_PI));
        REQUIRE(std::abs(out[prt::sh::index(l, m)] - ref) <= 1e-12 * scale);
      }
  }
}

TEST_CASE("float single-direction evaluation matches double to float precision", "[sh]") {
  std::mt19937_64 rng(3);
  for (int bands : {1, 2, 3, 5, 9, 16}) {
    std::vector<double> ref(bands * bands);
    std::vector<float> out(bands * bands);
    for (int trial = 0; trial < 50; ++trial) {
      glm::dvec3 d = random_direction(rng);
      prt::sh::eval(bands, d, ref.data());
      prt::sh::eval(bands, glm::vec3(d), out.data());
      for (int i = 0; i < bands * bands; ++i) REQUIRE(out[i] == Approx(ref[i]).margin(2e-6 * bands));
    }
  }
}
