// SH rotation against independent truth: the rotated expansion evaluated by the reference basis at
// d equals the original expansion at R^-1 d (the definition of an active rotation); group identities
// (composition, inverse, orthogonality); band 1 written out by hand; the yaw/pitch/roll convention on
// explicit vectors; the float fast paths against the double Ivanic-Ruedenberg blocks; and the
// generated X(+90) table against the double recursion.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "core/error.h"
#include "sh/basis.h"
#include "sh/rotation.h"
#include "sh/rotation_float.h"
#include "sh/rotation_x90_table.h"
#include "support/random_draws.h"

namespace {

using prt::sh::index;
using prt::sh::Rotation;

constexpr double kFloatEps = 5.9604644775390625e-08;  // 2^-24

using prt::test::random_direction;
using prt::test::random_rotation;

std::vector<double> random_coefficients(std::mt19937_64& rng, int bands) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> c(static_cast<std::size_t>(bands * bands));
  for (double& v : c) v = u(rng);
  return c;
}

// Right-handed rotations about the world axes by an angle in radians (column-vector convention).
glm::dmat3 rot_x(double a) { return glm::mat3_cast(glm::angleAxis(a, glm::dvec3(1, 0, 0))); }
glm::dmat3 rot_y(double a) { return glm::mat3_cast(glm::angleAxis(a, glm::dvec3(0, 1, 0))); }
glm::dmat3 rot_z(double a) { return glm::mat3_cast(glm::angleAxis(a, glm::dvec3(0, 0, 1))); }
glm::dmat3 rot_axis(double a, glm::dvec3 axis) { return glm::mat3_cast(glm::angleAxis(a, glm::normalize(axis))); }

// sum_i c_i Y_i(d) with the slow reference basis.
double expansion(const std::vector<double>& c, int bands, const glm::dvec3& d) {
  double sum = 0;
  for (int l = 0; l < bands; ++l)
    for (int m = -l; m <= l; ++m) sum += c[index(l, m)] * prt::sh::eval_reference(l, m, d);
  return sum;
}

double norm2(const std::vector<double>& c) {
  double s = 0;
  for (double v : c) s += v * v;
  return std::sqrt(s);
}

// The special rotations every path must handle: identity, half turns, near gimbal lock of the ZYZ
// decomposition (beta near 0 and pi) and exact gimbal lock.
std::vector<glm::dmat3> special_rotations() {
  std::vector<glm::dmat3> r = {glm::dmat3(1.0), rot_x(M_PI), rot_y(M_PI), rot_z(M_PI),
                               rot_axis(M_PI, {1, 1, 0}), rot_axis(M_PI, {0.3, -0.5, 0.8}), rot_x(M_PI / 2),
                               rot_y(-M_PI / 2)};
  for (double beta : {0.0, 1e-9, 1e-6, 1e-4, 1e-2, M_PI - 1e-2, M_PI - 1e-4, M_PI - 1e-6, M_PI - 1e-9, M_PI})
    r.push_back(rot_z(0.7) * rot_y(beta) * rot_z(-2.1));
  r.push_back(rot_z(1.3));  // beta = 0 exactly, alpha + gamma = 1.3
  r.push_back(rot_z(-0.4) * rot_x(M_PI));  // beta = pi exactly
  return r;
}

}  // namespace

TEST_CASE("band 1 is R conjugated by the signed permutation (x, y, z) -> (-c_1,1, -c_1,-1, c_1,0)",
          "[sh][rotation]") {
  // Y_1,-1 = -k y, Y_1,0 = k z, Y_1,1 = -k x: the band-1 part of f is k (a . d) with
  // a = (-c_1,1, -c_1,-1, c_1,0), and f(R^-1 d) = k ((R a) . d). Written out, with R_ij = row i, col j:
  std::mt19937_64 rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    const glm::dmat3 r = random_rotation(rng);
    auto R = [&](int i, int j) { return r[j][i]; };
    const int x = 0, y = 1, z = 2;
    const double expected[3][3] = {{R(y, y), -R(y, z), R(y, x)},
                                   {-R(z, y), R(z, z), -R(z, x)},
                                   {R(x, y), -R(x, z), R(x, x)}};
    const Rotation rotation(2, r);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) REQUIRE(std::abs(rotation.block(1)[i * 3 + j] - expected[i][j]) <= 1e-15);
    CHECK(rotation.block(0)[0] == 1.0);
  }
}

TEST_CASE("rotated coefficients give f(R^-1 d) to 1e-12 for every band count up to 16", "[sh][rotation]") {
  std::mt19937_64 rng(2);
  for (int bands = 1; bands <= 16; ++bands) {
    std::vector<glm::dmat3> rotations = {random_rotation(rng), random_rotation(rng), random_rotation(rng)};
    for (const glm::dmat3& r : special_rotations()) rotations.push_back(r);
    for (const glm::dmat3& r : rotations) {
      const std::vector<double> c = random_coefficients(rng, bands);
      std::vector<double> rotated(c.size());
      Rotation(bands, r).apply(c.data(), rotated.data());
      for (int k = 0; k < 4; ++k) {
        const glm::dvec3 d = random_direction(rng);
        INFO("bands " << bands);
        REQUIRE(std::abs(expansion(rotated, bands, d) - expansion(c, bands, glm::transpose(r) * d)) <= 1e-12);
      }
    }
  }
}

TEST_CASE("rotation spot checks up to 32 bands", "[sh][rotation]") {
  // Tolerance: |sum_i e_i Y_i(d)| <= |e|_2 |Y(d)|_2 with |Y(d)|_2 = bands / sqrt(4 pi) (addition
  // theorem) and |e|_2 <= max_l ||B~_l - B_l|| |c|_2. The blocks are orthogonal to 3e-14 at l = 31
  // (next test), so ||B~_l - B_l|| = 1e-13 bounds the error with margin (observed: ~1e-13 absolute,
  // 100x below the bound).
  std::mt19937_64 rng(3);
  for (int bands : {17, 20, 24, 28, 32}) {
    for (int trial = 0; trial < 2; ++trial) {
      const glm::dmat3 r = random_rotation(rng);
      const std::vector<double> c = random_coefficients(rng, bands);
      std::vector<double> rotated(c.size());
      Rotation(bands, r).apply(c.data(), rotated.data());
      const double tolerance = 1e-13 * norm2(c) * bands / std::sqrt(4 * M_PI);
      for (int k = 0; k < 3; ++k) {
        const glm::dvec3 d = random_direction(rng);
        INFO("bands " << bands);
        REQUIRE(std::abs(expansion(rotated, bands, d) - expansion(c, bands, glm::transpose(r) * d)) <= tolerance);
      }
    }
  }
}

TEST_CASE("every block is orthogonal to 1e-13, for random and special rotations", "[sh][rotation]") {
  std::mt19937_64 rng(4);
  std::vector<glm::dmat3> rotations = special_rotations();
  for (int i = 0; i < 4; ++i) rotations.push_back(random_rotation(rng));
  for (const glm::dmat3& r : rotations) {
    const Rotation rotation(prt::sh::kMaxBands, r);
    double worst = 0;
    for (int l = 0; l < rotation.bands(); ++l) {
      const int size = 2 * l + 1;
      const double* b = rotation.block(l);
      for (int i = 0; i < size; ++i)
        for (int j = 0; j < size; ++j) {
          double dot = 0;
          for (int k = 0; k < size; ++k) dot += b[i * size + k] * b[j * size + k];
          worst = std::fmax(worst, std::abs(dot - (i == j ? 1.0 : 0.0)));
        }
    }
    REQUIRE(worst <= 1e-13);
  }
}

TEST_CASE("composition and inverse: Rot(A) Rot(B) = Rot(AB), Rot(R)^-1 = Rot(R^T)", "[sh][rotation]") {
  std::mt19937_64 rng(5);
  const int bands = prt::sh::kMaxBands;
  for (int trial = 0; trial < 3; ++trial) {
    const glm::dmat3 a = random_rotation(rng), b = random_rotation(rng);
    const Rotation ra(bands, a), rb(bands, b), rab(bands, a * b);
    const Rotation inverse = ra.inverse(), transposed(bands, glm::transpose(a));
    double worst_product = 0, worst_inverse = 0;
    for (int l = 0; l < bands; ++l) {
      const int size = 2 * l + 1;
      for (int i = 0; i < size; ++i)
        for (int j = 0; j < size; ++j) {
          double product = 0;
          for (int k = 0; k < size; ++k) product += ra.block(l)[i * size + k] * rb.block(l)[k * size + j];
          worst_product = std::fmax(worst_product, std::abs(product - rab.block(l)[i * size + j]));
          worst_inverse = std::fmax(worst_inverse, std::abs(inverse.block(l)[i * size + j] - transposed.block(l)[i * size + j]));
        }
    }
    REQUIRE(worst_product <= 1e-13);
    REQUIRE(worst_inverse <= 1e-13);
    // Applying a rotation and then its inverse returns the coefficients.
    const std::vector<double> c = random_coefficients(rng, bands);
    std::vector<double> there(c.size()), back(c.size());
    ra.apply(c.data(), there.data());
    inverse.apply(there.data(), back.data());
    for (std::size_t i = 0; i < c.size(); ++i) REQUIRE(std::abs(back[i] - c[i]) <= 1e-13);
  }
}

TEST_CASE("the identity rotation is exact in every path", "[sh][rotation]") {
  std::mt19937_64 rng(6);
  for (int bands = 1; bands <= prt::sh::kMaxBands; ++bands) {
    const Rotation rotation(bands, glm::dmat3(1.0));
    for (int l = 0; l < bands; ++l)
      for (int i = 0; i < 2 * l + 1; ++i)
        for (int j = 0; j < 2 * l + 1; ++j) REQUIRE(rotation.block(l)[i * (2 * l + 1) + j] == (i == j ? 1.0 : 0.0));
    const std::vector<double> c = random_coefficients(rng, bands);
    std::vector<double> out(c.size());
    rotation.apply(c.data(), out.data());
    REQUIRE(out == c);
    std::vector<float> cf(c.begin(), c.end()), of(c.size());
    prt::sh::rotate(bands, glm::mat3(1.0f), cf.data(), of.data());
    REQUIRE(of == cf);
    std::vector<glm::vec3> rgb(c.size()), rgb_out(c.size());
    for (std::size_t i = 0; i < c.size(); ++i) rgb[i] = glm::vec3(cf[i], -cf[i], 2 * cf[i]);
    prt::sh::rotate_rgb(bands, glm::mat3(1.0f), rgb.data(), rgb_out.data());
    REQUIRE(rgb_out == rgb);
  }
}

TEST_CASE("yaw, pitch, roll: R = Ry(yaw) Rx(pitch) Rz(roll) in degrees, right-handed", "[sh][rotation]") {
  using prt::sh::rotation_from_yaw_pitch_roll;
  // Multiples of 90 degrees are exact.
  CHECK(rotation_from_yaw_pitch_roll(90, 0, 0) * glm::dvec3(1, 0, 0) == glm::dvec3(0, 0, -1));
  CHECK(rotation_from_yaw_pitch_roll(90, 0, 0) * glm::dvec3(0, 0, 1) == glm::dvec3(1, 0, 0));
  CHECK(rotation_from_yaw_pitch_roll(0, 90, 0) * glm::dvec3(0, 1, 0) == glm::dvec3(0, 0, 1));
  CHECK(rotation_from_yaw_pitch_roll(0, 0, 90) * glm::dvec3(1, 0, 0) == glm::dvec3(0, 1, 0));
  CHECK(rotation_from_yaw_pitch_roll(-270, 0, 0) * glm::dvec3(1, 0, 0) == glm::dvec3(0, 0, -1));
  CHECK(rotation_from_yaw_pitch_roll(180, 0, 0) * glm::dvec3(1, 0, 0) == glm::dvec3(-1, 0, 0));
  CHECK_THROWS_AS(rotation_from_yaw_pitch_roll(NAN, 0, 0), prt::Error);
  // Order: roll first, then pitch, then yaw. +Y -(pitch 90)-> +Z -(yaw 90)-> +X.
  CHECK(rotation_from_yaw_pitch_roll(90, 90, 0) * glm::dvec3(0, 1, 0) == glm::dvec3(1, 0, 0));
  // +X -(roll 90)-> +Y -(pitch 90)-> +Z -(yaw 90)-> +X.
  CHECK(rotation_from_yaw_pitch_roll(90, 90, 90) * glm::dvec3(1, 0, 0) == glm::dvec3(1, 0, 0));
  // General angles against the product of axis rotations.
  const glm::dmat3 r = rotation_from_yaw_pitch_roll(30, -50, 125);
  const glm::dmat3 expected = rot_y(30 * M_PI / 180) * rot_x(-50 * M_PI / 180) * rot_z(125 * M_PI / 180);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) CHECK(std::abs(r[i][j] - expected[i][j]) <= 1e-15);
  // Applied to the environment: a lobe seen along +X is seen along -Z after yaw 90.
  const Rotation rotation(2, rotation_from_yaw_pitch_roll(90, 0, 0));
  std::vector<double> lobe(4, 0.0), rotated(4);
  prt::sh::eval(2, glm::dvec3(1, 0, 0), lobe.data());
  rotation.apply(lobe.data(), rotated.data());
  std::vector<double> expected_lobe(4);
  prt::sh::eval(2, glm::dvec3(0, 0, -1), expected_lobe.data());
  for (int i = 0; i < 4; ++i) CHECK(std::abs(rotated[i] - expected_lobe[i]) <= 1e-15);
}

TEST_CASE("float fast paths match the double rotation to float precision for every band count",
          "[sh][rotation]") {
  // Error model: each band's error is at most 10 (l + 1) float epsilons relative to that band's
  // norm (zxzxz: cos/sin of m theta by complex products, error ~m eps; two X(+90) products of
  // ~l/2 terms; observed at most ~3.5 (l + 1) eps over random and near-gimbal rotations).
  std::mt19937_64 rng(7);
  for (int bands : {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 24, 32}) {
    std::vector<glm::dmat3> rotations = special_rotations();
    for (int i = 0; i < 12; ++i) rotations.push_back(random_rotation(rng));
    for (const glm::dmat3& r_double : rotations) {
      const glm::mat3 r(r_double);
      // The reference rotates the same float matrix, in double.
      const Rotation reference(bands, glm::dmat3(r));
      const std::vector<double> c0 = random_coefficients(rng, bands);
      const int count = bands * bands;
      std::vector<float> c(c0.begin(), c0.end()), out(count);
      std::vector<glm::vec3> rgb(count), rgb_out(count);
      prt::sh::RgbCoefficients rgb_double(bands);
      std::uniform_real_distribution<double> u(-1, 1);
      for (int i = 0; i < count; ++i) {
        const float green = static_cast<float>(u(rng)), blue = static_cast<float>(u(rng));
        rgb[i] = glm::vec3(c[i], green, blue);
        rgb_double.values[i] = glm::dvec3(rgb[i]);
      }
      std::vector<double> cd(c.begin(), c.end()), expected(count);
      reference.apply(cd.data(), expected.data());
      const prt::sh::RgbCoefficients expected_rgb = reference.apply(rgb_double);
      prt::sh::rotate(bands, r, c.data(), out.data());
      prt::sh::rotate_rgb(bands, r, rgb.data(), rgb_out.data());
      for (int l = 0; l < bands; ++l) {
        double error = 0, error_rgb = 0, norm = 0, norm_rgb = 0;
        for (int m = -l; m <= l; ++m) {
          const int i = index(l, m);
          error += (out[i] - expected[i]) * (out[i] - expected[i]);
          norm += cd[i] * cd[i];
          const glm::dvec3 e = glm::dvec3(rgb_out[i]) - expected_rgb.values[i];
          error_rgb += glm::dot(e, e);
          norm_rgb += glm::dot(rgb_double.values[i], rgb_double.values[i]);
        }
        INFO("bands " << bands << " l " << l);
        REQUIRE(std::sqrt(error) <= 10 * (l + 1) * kFloatEps * std::sqrt(norm));
        REQUIRE(std::sqrt(error_rgb) <= 10 * (l + 1) * kFloatEps * std::sqrt(norm_rgb));
      }
    }
  }
}

TEST_CASE("the generated X(+90) table is the double recursion's Rx(90) rounded to float", "[sh][rotation]") {
  using prt::sh::detail::kX90Bands;
  using prt::sh::detail::kX90SubBlocks;
  using prt::sh::detail::kX90Values;
  const Rotation x90(kX90Bands, rot_x(M_PI / 2));
  for (int l = 0; l < kX90Bands; ++l) {
    const int size = 2 * l + 1;
    std::vector<int> covered(static_cast<std::size_t>(size * size), 0);
    for (const auto& b : kX90SubBlocks[l])
      for (int i = 0; i < b.rows; ++i)
        for (int k = 0; k < b.cols; ++k) {
          const int m = b.row_start + i * b.row_step, n = b.col_start + k * b.col_step;
          const double exact = x90.block(l)[(m + l) * size + (n + l)];
          REQUIRE(std::abs(kX90Values[b.offset + i * b.cols + k] - exact) <= kFloatEps * std::abs(exact) + 1e-15);
          ++covered[(m + l) * size + (n + l)];
        }
    for (int e = 0; e < size * size; ++e) {
      REQUIRE(covered[e] <= 1);
      if (!covered[e]) REQUIRE(std::abs(x90.block(l)[e]) <= 1e-14);
    }
  }
}

TEST_CASE("RGB sets rotate channel by channel", "[sh][rotation]") {
  std::mt19937_64 rng(8);
  const int bands = 6;
  const glm::dmat3 r = random_rotation(rng);
  const Rotation rotation(bands, r);
  prt::sh::RgbCoefficients rgb(bands);
  std::vector<double> channel[3];
  for (auto& ch : channel) ch = random_coefficients(rng, bands);
  for (int i = 0; i < bands * bands; ++i) rgb.values[i] = glm::dvec3(channel[0][i], channel[1][i], channel[2][i]);
  const prt::sh::RgbCoefficients rotated = rotation.apply(rgb);
  REQUIRE(rotated.bands == bands);
  for (int ch = 0; ch < 3; ++ch) {
    std::vector<double> out(channel[ch].size());
    rotation.apply(channel[ch].data(), out.data());
    for (int i = 0; i < bands * bands; ++i) REQUIRE(rotated.values[i][ch] == Approx(out[i]).margin(1e-15));
  }
  CHECK_THROWS_AS(rotation.apply(prt::sh::RgbCoefficients(bands + 1)), prt::Error);
}

TEST_CASE("invalid input is reported, small drift from orthonormality is tolerated", "[sh][rotation]") {
  CHECK_THROWS_AS(Rotation(0, glm::dmat3(1.0)), prt::Error);
  CHECK_THROWS_AS(Rotation(prt::sh::kMaxBands + 1, glm::dmat3(1.0)), prt::Error);
  CHECK_THROWS_AS(Rotation(3, glm::dmat3(2.0)), prt::Error);                                // scaling
  CHECK_THROWS_AS(Rotation(3, glm::dmat3(glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1))),
                  prt::Error);                                                               // reflection
  // A rotation perturbed by 1e-7 still gives orthogonal blocks (it is re-orthonormalised).
  std::mt19937_64 rng(9);
  glm::dmat3 r = random_rotation(rng);
  r[0][1] += 1e-7;
  r[2][0] -= 1e-7;
  const Rotation rotation(8, r);
  const double* b = rotation.block(7);
  for (int i = 0; i < 15; ++i) {
    double dot = 0;
    for (int k = 0; k < 15; ++k) dot += b[i * 15 + k] * b[i * 15 + k];
    REQUIRE(std::abs(dot - 1) <= 1e-13);
  }
}

TEST_CASE("FloatRotation gives f(R^-1 d) to float precision and its RGB form rotates each channel", "[sh][rotation]") {
  std::mt19937_64 rng(9);
  for (int bands : {1, 2, 3, 4, 5, 6, 9, 16}) {
    for (int trial = 0; trial < 4; ++trial) {
      const glm::dmat3 r = random_rotation(rng);
      const std::vector<double> c = random_coefficients(rng, bands);
      std::vector<float> in(c.begin(), c.end()), out(c.size());
      const prt::sh::FloatRotation rotation{Rotation(bands, r)};
      REQUIRE(rotation.bands() == bands);
      rotation.apply(in.data(), out.data());
      const std::vector<double> rotated(out.begin(), out.end());
      for (int k = 0; k < 4; ++k) {
        const glm::dvec3 d = random_direction(rng);
        // (2l+1)-term float sums of coefficients in [-1, 1], |Y| <= sqrt((2l+1)/4pi) per term of f.
        INFO("bands " << bands);
        REQUIRE(std::abs(expansion(rotated, bands, d) - expansion(c, bands, glm::transpose(r) * d)) <=
                40.0 * kFloatEps * bands * bands * bands);
      }
      std::vector<glm::vec3> rgb(c.size()), rgb_out(c.size());
      for (std::size_t i = 0; i < c.size(); ++i) rgb[i] = glm::vec3(in[i], 2.0f * in[i], -in[i]);
      rotation.apply_rgb(rgb.data(), rgb_out.data());
      for (std::size_t i = 0; i < c.size(); ++i) {
        // Not bit-equal: the compiler may contract the RGB and the scalar sums differently (-O2 vs -O3).
        REQUIRE(rgb_out[i].x == Approx(out[i]).margin(1e-6));
        REQUIRE(rgb_out[i].y == Approx(2.0f * out[i]).margin(1e-6));
        REQUIRE(rgb_out[i].z == Approx(-out[i]).margin(1e-6));
      }
    }
  }
}

TEST_CASE("FloatRotation agrees with the double Rotation::apply to float rounding of each band", "[sh][rotation]") {
  // Each output is a (2l+1)-term float sum of float-rounded blocks times float inputs: the error is at
  // most about (2l+1) float roundings of the band's magnitude sum_k |block| |in| <= sqrt(2l+1) |band|.
  std::mt19937_64 rng(23);
  double worst_ratio = 0;
  for (int bands : {1, 2, 3, 5, 9, 16, 17, 32}) {
    for (int trial = 0; trial < 3; ++trial) {
      const glm::dmat3 r = random_rotation(rng);
      const std::vector<double> c = random_coefficients(rng, bands);
      const Rotation rotation(bands, r);
      std::vector<double> exact(c.size());
      rotation.apply(c.data(), exact.data());
      std::vector<float> in(c.begin(), c.end()), out(c.size());
      prt::sh::FloatRotation{rotation}.apply(in.data(), out.data());
      for (int l = 0; l < bands; ++l) {
        double norm = 0;
        for (int m = -l; m <= l; ++m) norm += c[prt::sh::index(l, m)] * c[prt::sh::index(l, m)];
        const double bound = 2.0 * kFloatEps * (2 * l + 2) * std::sqrt((2.0 * l + 1.0) * norm);
        for (int m = -l; m <= l; ++m) {
          const int k = prt::sh::index(l, m);
          INFO("bands " << bands << ", l " << l << ", m " << m);
          REQUIRE(std::abs(out[k] - exact[k]) <= bound);
          worst_ratio = std::max(worst_ratio, std::abs(out[k] - exact[k]) / bound);
        }
      }
    }
  }
  CHECK(worst_ratio >= 0.01);  // the bound is within two orders of magnitude of what happens
}
