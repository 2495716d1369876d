// Sample sets and the PCG32 generator: determinism, domains, stratification (the (0,k,2)-net property),
// the stated densities, and integration error that falls like a low-discrepancy set's.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>

#include "sh/sampling.h"

namespace {

// Relative error of (4 pi / N) sum f(d_i) for f(d) = exp(a . d), |a| = 1: the integral is 4 pi sinh(1).
double exp_integral_error(const std::vector<glm::dvec3>& directions) {
  const glm::dvec3 a = glm::normalize(glm::dvec3(0.3, 0.5, 0.8));
  double sum = 0.0;
  for (const glm::dvec3& d : directions) sum += std::exp(glm::dot(a, d));
  const double estimate = 4.0 * M_PI * sum / directions.size();
  const double exact = 4.0 * M_PI * std::sinh(1.0);
  return (estimate - exact) / exact;
}

std::vector<glm::dvec3> random_sphere_directions(std::size_t count, std::uint64_t stream) {
  prt::sh::Rng rng(2024, stream);
  std::vector<glm::dvec3> out;
  for (std::size_t i = 0; i < count; ++i) {
    const double u = rng.next_double();
    const double v = rng.next_double();
    out.push_back(prt::sh::square_to_sphere({u, v}));
  }
  return out;
}

}  // namespace

TEST_CASE("sobol_2d is deterministic, seed-dependent and strictly inside the unit square", "[sh][sampling]") {
  for (std::uint32_t i = 0; i < 4096; ++i) {
    const glm::dvec2 p = prt::sh::sobol_2d(i, 17);
    REQUIRE(p == prt::sh::sobol_2d(i, 17));
    REQUIRE(p.x > 0.0);
    REQUIRE(p.x < 1.0);
    REQUIRE(p.y > 0.0);
    REQUIRE(p.y < 1.0);
  }
  const auto a = prt::sh::sphere_directions(1024, 1), b = prt::sh::sphere_directions(1024, 1);
  const auto c = prt::sh::sphere_directions(1024, 2);
  REQUIRE(a == b);
  int same = 0;
  for (std::size_t i = 0; i < a.size(); ++i) same += a[i] == c[i];
  CHECK(same == 0);
  // Seeds 0 and 1 (adjacent integers) are as different as any others.
  int same01 = 0;
  for (std::uint32_t i = 0; i < 1024; ++i) same01 += prt::sh::sobol_2d(i, 0) == prt::sh::sobol_2d(i, 1);
  CHECK(same01 == 0);
}

namespace {

// True if points first .. first + 2^k - 1 of sobol_2d(., seed) put exactly one point in every cell of
// size 2^-i x 2^-(k-i), for every i in 0..k: a (0,k,2)-net, counted by brute force.
bool is_net(std::uint32_t first, int k, std::uint32_t seed) {
  const std::uint32_t n = 1u << k;
  for (int i = 0; i <= k; ++i) {
    std::vector<int> cells(n, 0);
    for (std::uint32_t p = first; p < first + n; ++p) {
      const glm::dvec2 u = prt::sh::sobol_2d(p, seed);
      ++cells[static_cast<std::uint32_t>(u.x * (1u << i)) * (1u << (k - i)) + static_cast<std::uint32_t>(u.y * (1u << (k - i)))];
    }
    for (int count : cells)
      if (count != 1) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("every prefix of length 2^k is a (0,k,2)-net", "[sh][sampling]") {
  for (std::uint32_t seed : {0u, 1u, 12345u})
    for (int k = 0; k <= 10; ++k) {
      INFO("seed " << seed << ", k = " << k);
      REQUIRE(is_net(0, k, seed));
    }
}

// The interleaved sample sets (bake/vertex_samples.h) take aligned blocks of the sequence, not prefixes;
// a block that is not aligned is in general no net (the check can fail).
TEST_CASE("every aligned block [m 2^k, (m + 1) 2^k) is a (0,k,2)-net", "[sh][sampling]") {
  for (std::uint32_t seed : {1u, 777u})
    for (int k = 2; k <= 7; ++k)
      for (std::uint32_t m : {1u, 2u, 3u, 5u, 15u, 1000u}) {
        INFO("seed " << seed << ", k = " << k << ", m = " << m);
        REQUIRE(is_net(m << k, k, seed));
      }
  int misaligned_nets = 0;
  for (std::uint32_t seed : {1u, 777u}) misaligned_nets += is_net((3u << 6) + 32u, 6, seed);
  CHECK(misaligned_nets < 2);
}

TEST_CASE("directions lie in their domains", "[sh][sampling]") {
  for (const glm::dvec3& d : prt::sh::sphere_directions(4096, 3)) REQUIRE(std::abs(glm::length(d) - 1.0) <= 1e-14);
  for (const glm::dvec3& d : prt::sh::hemisphere_directions_uniform(4096, 3)) {
    REQUIRE(std::abs(glm::length(d) - 1.0) <= 1e-14);
    REQUIRE(d.z > 0.0);
  }
  for (const glm::dvec3& d : prt::sh::hemisphere_directions_cosine(4096, 3)) {
    REQUIRE(std::abs(glm::length(d) - 1.0) <= 1e-14);
    REQUIRE(d.z > 0.0);
  }
  // The corners and centre of the square map to the poles and the rim as documented.
  CHECK(prt::sh::square_to_sphere({0.0, 0.3}).z == 1.0);
  CHECK(prt::sh::square_to_hemisphere_uniform({0.0, 0.3}).z == 1.0);
  CHECK(prt::sh::square_to_hemisphere_cosine({0.5, 0.5}).z == 1.0);
}

TEST_CASE("samples follow the stated densities", "[sh][sampling]") {
  const std::size_t n = 4096;
  const auto sphere = prt::sh::sphere_directions(n, 5);
  const auto uniform = prt::sh::hemisphere_directions_uniform(n, 5);
  const auto cosine = prt::sh::hemisphere_directions_cosine(n, 5);
  // P(z > c): (1 - c) / 2 on the sphere, 1 - c uniform on the hemisphere, 1 - c^2 cosine-weighted;
  // P(0 <= phi < pi/2) = 1/4 for all three.
  auto fraction = [](const std::vector<glm::dvec3>& ds, auto inside) {
    double k = 0;
    for (const glm::dvec3& d : ds) k += inside(d) ? 1.0 : 0.0;
    return k / ds.size();
  };
  for (double c : {-0.6, 0.0, 0.25, 0.7, 0.95}) {
    auto above = [c](const glm::dvec3& d) { return d.z > c; };
    INFO("c = " << c);
    REQUIRE(fraction(sphere, above) == Approx((1.0 - c) / 2.0).margin(2e-3));
    if (c >= 0.0) {
      REQUIRE(fraction(uniform, above) == Approx(1.0 - c).margin(2e-3));
      REQUIRE(fraction(cosine, above) == Approx(1.0 - c * c).margin(4e-3));
    }
  }
  auto quadrant = [](const glm::dvec3& d) { return d.x > 0.0 && d.y >= 0.0; };
  CHECK(fraction(sphere, quadrant) == Approx(0.25).margin(2e-3));
  CHECK(fraction(uniform, quadrant) == Approx(0.25).margin(2e-3));
  CHECK(fraction(cosine, quadrant) == Approx(0.25).margin(4e-3));

  // Unbiased estimates with the stated pdfs: integral over the hemisphere of z^2 + x z = 2 pi / 3.
  double su = 0.0, sc = 0.0;
  for (const glm::dvec3& d : uniform) su += (d.z * d.z + d.x * d.z) / prt::sh::kHemisphereUniformPdf;
  for (const glm::dvec3& d : cosine) sc += (d.z * d.z + d.x * d.z) / prt::sh::hemisphere_cosine_pdf(d);
  CHECK(su / n == Approx(2.0 * M_PI / 3.0).epsilon(1e-3));
  CHECK(sc / n == Approx(2.0 * M_PI / 3.0).epsilon(1e-3));
  double ss = 0.0;
  for (const glm::dvec3& d : sphere) ss += d.z * d.z / prt::sh::kSpherePdf;
  CHECK(ss / n == Approx(4.0 * M_PI / 3.0).epsilon(1e-4));
  // The pdfs integrate to 1: 4 pi kSpherePdf, 2 pi kHemisphereUniformPdf, and
  // integral_0^{2pi} integral_0^1 z / pi dz dphi (z^2/2 by hand, here as a midpoint sum in z).
  CHECK(4.0 * M_PI * prt::sh::kSpherePdf == Approx(1.0).epsilon(1e-15));
  CHECK(2.0 * M_PI * prt::sh::kHemisphereUniformPdf == Approx(1.0).epsilon(1e-15));
  double cosine_mass = 0.0;
  for (int i = 0; i < 1000; ++i)
    cosine_mass += 2.0 * M_PI * 0.001 * prt::sh::hemisphere_cosine_pdf({0.0, 0.0, (i + 0.5) / 1000.0});
  CHECK(cosine_mass == Approx(1.0).epsilon(1e-12));
  CHECK(prt::sh::hemisphere_cosine_pdf({1.0, 0.0, 0.0}) == 0.0);
}

TEST_CASE("integration error falls like a low-discrepancy set's, far below plain Monte Carlo", "[sh][sampling]") {
  const int seeds = 16;
  double sobol_256 = 0.0, sobol_4096 = 0.0, random_4096 = 0.0;
  for (int s = 0; s < seeds; ++s) {
    const double e256 = exp_integral_error(prt::sh::sphere_directions(256, static_cast<std::uint32_t>(s)));
    const double e4096 = exp_integral_error(prt::sh::sphere_directions(4096, static_cast<std::uint32_t>(s)));
    const double emc = exp_integral_error(random_sphere_directions(4096, static_cast<std::uint64_t>(s)));
    sobol_256 += e256 * e256;
    sobol_4096 += e4096 * e4096;
    random_4096 += emc * emc;
  }
  sobol_256 = std::sqrt(sobol_256 / seeds);
  sobol_4096 = std::sqrt(sobol_4096 / seeds);
  random_4096 = std::sqrt(random_4096 / seeds);
  INFO("RMS relative error: scrambled Sobol 256 " << sobol_256 << ", 4096 " << sobol_4096 << "; plain MC 4096 "
                                                   << random_4096);
  // Plain MC: relative standard deviation of exp(a . d) is 0.56, so 0.0087 at 4096 points.
  CHECK(random_4096 == Approx(0.56 / 64.0).epsilon(0.5));
  CHECK(sobol_4096 < random_4096 / 20.0);
  // 16x the points: MC gains 4x, an Owen-scrambled net on a smooth integrand ~64x (N^-3/2).
  CHECK(sobol_4096 < sobol_256 / 16.0);
}

TEST_CASE("PCG32 reproduces the reference generator's output", "[sh][sampling]") {
  // pcg32-demo (pcg-c-basic) seeded with pcg32_srandom_r(&rng, 42u, 54u).
  prt::sh::Rng rng(42u, 54u);
  const std::uint32_t expected[] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u, 0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
  for (std::uint32_t e : expected) CHECK(rng.next_u32() == e);
  // Doubles in [0, 1) with mean 1/2 and variance 1/12; streams differ.
  prt::sh::Rng a(7, 0), b(7, 1);
  double sum = 0.0, sum2 = 0.0;
  int same = 0;
  for (int i = 0; i < 100000; ++i) {
    const double u = a.next_double();
    REQUIRE(u >= 0.0);
    REQUIRE(u < 1.0);
    sum += u;
    sum2 += u * u;
    same += u == b.next_double();
  }
  CHECK(sum / 100000 == Approx(0.5).margin(0.005));
  CHECK(sum2 / 100000 - 0.25 == Approx(1.0 / 12.0).margin(0.005));  // E[u^2] - E[u]^2
  CHECK(same == 0);
}
