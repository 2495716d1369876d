// SH projection of environment images: closed forms, band-limited round trips, the slow per-texel
// reference, rotation against image shifts, cube maps against equirect maps.
#include <catch2/catch.hpp>

#include <cmath>

#include <glm/geometric.hpp>

#include "core/constants.h"
#include "light/environment.h"
#include "light/projection.h"
#include "light_test_util.h"
#include "sh/basis.h"
#include "sh/rotation.h"

using namespace prt;

namespace {


image::Image constant_equirect(int width, int height, glm::dvec3 v) {
  image::Image im(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) im.at(x, y, c) = static_cast<float>(v[c]);
  return im;
}

image::Image random_image(int width, int height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 10.0f);
  image::Image im(width, height, 3);
  for (float& p : im.pixels) p = u(rng);
  return im;
}

}  // namespace

TEST_CASE("texel solid angles sum to the sphere", "[projection]") {
  for (int h : {1, 3, 64, 255}) {
    double total = 0.0;
    for (int row = 0; row < h; ++row) total += 2 * h * light::equirect_texel_solid_angle(row, 2 * h, h);
    CHECK(total == Approx(4 * kPi).epsilon(1e-13));
  }
  for (int n : {1, 2, 7, 64}) {
    double total = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) total += light::cube_texel_solid_angle(i, j, n);
    CHECK(total == Approx(4 * kPi / 6).epsilon(1e-13));
  }
  // A single-texel face is the whole face: 4 pi / 6; the centre texel of a large face is nearly flat.
  CHECK(light::cube_texel_solid_angle(0, 0, 1) == Approx(4 * kPi / 6).epsilon(1e-14));
  CHECK(light::cube_texel_solid_angle(50, 50, 101) == Approx(4.0 / (101.0 * 101.0)).epsilon(1e-3));
}

TEST_CASE("a constant map projects to c_0 = 2 sqrt(pi) v and nothing else", "[projection]") {
  const glm::dvec3 v(1.0, 0.25, 3.5);
  // c_0 is exact at every size: the row weights integrate sin(theta) exactly and the phi sum of a
  // constant is exact.
  for (int h : {1, 2, 3, 17, 256, 1024}) {
    const auto c = light::project_equirect(constant_equirect(2 * h, h, v), 9, 2);
    for (int k = 0; k < 3; ++k) CHECK(c.values[0][k] == Approx(2 * std::sqrt(kPi) * v[k]).margin(1e-5 * v[k]));
    if (h == 1024) {
      // Every other coefficient vanishes up to the theta midpoint error, ~ (pi/h)^2/12 (see the
      // band-limited test below): below 1e-5 v from 2048x1024 on.
      for (int i = 1; i < 81; ++i)
        for (int k = 0; k < 3; ++k) CHECK(std::fabs(c.values[i][k]) < 1e-5 * v[k]);
    }
    if (h == 256) {
      // At 512x256 that error is ~6e-5 v.
      for (int i = 1; i < 81; ++i)
        for (int k = 0; k < 3; ++k) CHECK(std::fabs(c.values[i][k]) < 1e-4 * v[k]);
    }
  }
}

// An image synthesised from known band-limited coefficients (point samples at texel centres)
// projects back to them to 1e-4 at 512x256. Why texel-area weighting makes this accurate:
// - in phi, the sum over the W equally spaced columns of exp(i k phi) is exact for |k| < W, and the
//   product of the image with Y_lm holds |k| <= 2 (bands - 1) only: no error at all in phi;
// - in theta, each row is weighted by the exact integral of sin(theta) over the row. The product,
//   restricted to one Fourier mode, is a polynomial in cos(theta), i.e. a cosine series sum_v a_v
//   cos(v theta). For v = 0 the exact weights make the sum exact (the mean, c_0 of a constant map);
//   for odd v both sides vanish by symmetry; for even v >= 2 the weighted midpoint sum equals the
//   integral plus (h^2 / 12) v^2 / (v^2 - 1) a_v + O(h^4), h = pi / height: an absolute error of at
//   most h^2/9 = 1.7e-5 per unit amplitude at 256 rows, independent of the frequency (plain
//   sin(theta_centre) h weights would also break the v = 0 term, i.e. the mean and c_0).
// With c_0 = 4 and other coefficients up to 1 the measured worst error is ~8e-5 for 3 to 9 bands.
TEST_CASE("band-limited equirect maps project back to their coefficients", "[projection]") {
  for (int bands : {1, 2, 3, 5, 9}) {
    const auto truth = test::random_coefficients(bands, 100 + bands);
    const auto image = test::synthesise_equirect(truth, 512, 256);
    const auto c = light::project_equirect(image, bands, 2);
    INFO("bands " << bands);
    CHECK(test::max_difference(c, truth) < 1e-4);
  }
  // The error shrinks as h^2: 4x fewer at twice the resolution.
  const auto truth = test::random_coefficients(5, 7);
  const double coarse = test::max_difference(light::project_equirect(test::synthesise_equirect(truth, 256, 128), 5), truth);
  const double fine = test::max_difference(light::project_equirect(test::synthesise_equirect(truth, 512, 256), 5), truth);
  CHECK(coarse / fine == Approx(4.0).epsilon(0.05));
}

TEST_CASE("the separable projection equals the slow per-texel reference", "[projection]") {
  // Sizes with width % 4 == 0 use the quarter fold; 6x3, 2x1 and 130x65 the half fold.
  struct Case {
    int width, height, bands;
  };
  for (const Case& k : {Case{2, 1, 3}, Case{4, 2, 5}, Case{6, 3, 4}, Case{130, 65, 9}, Case{256, 128, 16},
                        Case{64, 32, 32}, Case{200, 100, 1}}) {
    const auto image = random_image(k.width, k.height, 17u + k.width);
    const auto fast = light::project_equirect(image, k.bands, 2);
    const auto slow = light::project_equirect_reference(image, k.bands);
    INFO(k.width << "x" << k.height << ", bands " << k.bands);
    CHECK(test::max_difference(fast, slow) < 1e-11 * std::fabs(slow.values[0].x));
  }
}

TEST_CASE("projection is deterministic for any thread count", "[projection]") {
  const auto image = random_image(512, 256, 3);
  const auto one = light::project_equirect(image, 9, 1);
  for (int threads : {2, 3, 8}) {
    const auto many = light::project_equirect(image, 9, threads);
    for (std::size_t i = 0; i < one.values.size(); ++i) CHECK(many.values[i] == one.values[i]);
  }
  std::array<image::Image, 6> faces;
  for (int f = 0; f < 6; ++f) faces[f] = random_image(40, 40, 50u + f);
  const auto cube_one = light::project_cube(faces, 5, 1);
  const auto cube_many = light::project_cube(faces, 5, 3);
  for (std::size_t i = 0; i < cube_one.values.size(); ++i) CHECK(cube_many.values[i] == cube_one.values[i]);
}

TEST_CASE("a yaw of 90 degrees equals shifting the image by a quarter of its width", "[projection]") {
  // Convention check first: R = Ry(90) takes +X to -Z, and the equirect map looks along +X at
  // u = 1/2 and along -Z at u = 1/4. Rotating the environment by R (active: f'(d) = f(R^-1 d)) moves
  // what was seen at +X (u = 1/2) to -Z (u = 1/4): the content moves LEFT by width/4, i.e. the new
  // column x shows the old column x + width/4 (mod width).
  const glm::dmat3 r = sh::rotation_from_yaw_pitch_roll(90.0, 0.0, 0.0);
  const glm::dvec3 moved = r * glm::dvec3(1.0, 0.0, 0.0);
  CHECK(moved.x == Approx(0.0).margin(1e-12));
  CHECK(moved.z == Approx(-1.0).margin(1e-12));
  const glm::dvec3 minus_z = light::equirect_direction(0.25, 0.5);
  CHECK(minus_z.z == Approx(-1.0).margin(1e-12));

  const int width = 256, height = 128, bands = 6;
  const auto image = random_image(width, height, 11);
  image::Image shifted_left(width, height, 3), shifted_right(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) {
        shifted_left.at(x, y, c) = image.at((x + width / 4) % width, y, c);
        shifted_right.at(x, y, c) = image.at((x + 3 * width / 4) % width, y, c);
      }
  const auto rotated = sh::Rotation(bands, r).apply(light::project_equirect(image, bands));
  const auto left = light::project_equirect(shifted_left, bands);
  const auto right = light::project_equirect(shifted_right, bands);
  // Both grids coincide, so the only difference is rounding.
  CHECK(test::max_difference(rotated, left) < 1e-9 * left.values[0].x);
  // The opposite shift is a yaw of -90 degrees: clearly different (guards the test's sensitivity).
  CHECK(test::max_difference(rotated, right) > 1e-2);
}

TEST_CASE("cube maps and equirect maps of the same lighting agree", "[projection]") {
  const int bands = 5;
  const auto truth = test::random_coefficients(bands, 21);
  const auto from_equirect = light::project_equirect(test::synthesise_equirect(truth, 1024, 512), bands);
  const auto faces = test::synthesise_cube(truth, 256);
  const auto from_cube = light::project_cube(faces, bands);
  // Both rules are midpoint rules with exact texel solid angles: O(texel^2) errors, a few 1e-5 here.
  CHECK(test::max_difference(from_cube, truth) < 1e-4);
  CHECK(test::max_difference(from_equirect, from_cube) < 1e-4);

  // The same through crosses (both layouts) and through Environment dispatch.
  for (auto layout : {light::CrossLayout::horizontal, light::CrossLayout::vertical}) {
    light::Environment env;
    env.layout = light::Environment::Layout::cube;
    env.faces = light::faces_from_cross(light::cross_from_faces(faces, layout), "cross");
    const auto c = light::project(env, bands);
    for (std::size_t i = 0; i < c.values.size(); ++i) CHECK(c.values[i] == from_cube.values[i]);
  }
}

namespace {

// The direction through (s, t) of cube face f, written out from docs/conventions.md (GL 4.5 table 8.19)
// rather than taken from light::cube_direction, which project_cube itself uses.
glm::dvec3 gl_cube_direction(int face, double s, double t) {
  const double sc = 2.0 * s - 1.0, tc = 2.0 * t - 1.0;
  const glm::dvec3 d[6] = {{1, -tc, -sc}, {-1, -tc, sc}, {sc, 1, tc}, {sc, -1, -tc}, {sc, -tc, 1}, {-sc, -tc, -1}};
  return glm::normalize(d[face]);
}

}  // namespace

TEST_CASE("a real environment gives the same SH from its equirect map and from a cube resampling", "[projection]") {
  const auto env = light::load_environment(std::string(PRT_SOURCE_DIR) + "/assets/env/sunrise.exr");
  // Cube texels smaller than the map's (n = 512: at most 1.5e-5 sr against 3.8e-5 sr at the equator),
  // so that bilinear resampling keeps the energy of the small, very bright sun.
  const int n = 512;
  std::array<image::Image, 6> faces;
  for (int f = 0; f < 6; ++f) {
    faces[f] = image::Image(n, n, 3);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const glm::dvec3 l = env.radiance(gl_cube_direction(f, (i + 0.5) / n, (j + 0.5) / n));
        for (int c = 0; c < 3; ++c) faces[f].at(i, j, c) = static_cast<float>(l[c]);
      }
  }
  const auto a = light::project(env, 3);
  const auto b = light::project_cube(faces, 3);
  // Bilinear resampling of a map with a tiny, very bright sun changes the sun's energy slightly: 2%
  // of c_0 is a loose but meaningful bound (a wrong face orientation changes band 1 by far more).
  CHECK(test::max_difference(a, b) < 0.02 * a.values[0].y);
}

TEST_CASE("render_equirect evaluates the SH at pixel centres", "[projection]") {
  const auto c = test::random_coefficients(4, 5);
  const auto image = light::render_equirect(c, 64, 32, 2);
  REQUIRE(image.width == 64);
  REQUIRE(image.height == 32);
  for (int y : {0, 7, 31})
    for (int x : {0, 16, 63}) {
      const glm::dvec3 d = light::equirect_direction((x + 0.5) / 64, (y + 0.5) / 32);
      glm::dvec3 expected(0.0);
      for (int l = 0; l < 4; ++l)
        for (int m = -l; m <= l; ++m) expected += c.values[sh::index(l, m)] * sh::eval_reference(l, m, d);
      for (int k = 0; k < 3; ++k) CHECK(image.at(x, y, k) == Approx(expected[k]).margin(1e-5));
    }
  // Projecting the rendering returns the coefficients (render and project are inverse on band-limited data).
  const auto back = light::project_equirect(light::render_equirect(c, 512, 256), 4);
  CHECK(test::max_difference(back, c) < 1e-4);
}

TEST_CASE("projection rejects bad arguments", "[projection]") {
  const auto image = random_image(8, 4, 1);
  CHECK_THROWS_WITH(light::project_equirect(image, 0), Catch::Contains("out of range"));
  CHECK_THROWS_WITH(light::project_equirect(image, sh::kMaxBands + 1), Catch::Contains("out of range"));
  CHECK_THROWS_WITH(light::project_equirect(random_image(9, 4, 1), 3), Catch::Contains("not 2:1"));
  std::array<image::Image, 6> faces;
  for (int f = 0; f < 6; ++f) faces[f] = random_image(4, f == 3 ? 5 : 4, 1);
  CHECK_THROWS_WITH(light::project_cube(faces, 3), Catch::Contains("square"));
}
