// Analytic lights as `prt light` inputs (cli/analytic_light_spec.h) through the real binary, against
// coefficients computed here from the first nine basis functions' closed forms (docs/conventions.md)
// and by quadrature of the cap indicator: exact light, summed terms, one-line errors, no output left.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>

#include "light/light_file.h"
#include "support/run_prt.h"

using namespace prt;

namespace {

// Y_0..Y_8 of a unit direction (conventions.md's table, Condon-Shortley phase).
std::array<double, 9> basis9(const glm::dvec3& d) {
  return {0.2820947918, -0.4886025119 * d.y, 0.4886025119 * d.z, -0.4886025119 * d.x, 1.0925484306 * d.x * d.y,
          -1.0925484306 * d.y * d.z, 0.3153915653 * (3 * d.z * d.z - 1), -1.0925484306 * d.x * d.z,
          0.5462742153 * (d.x * d.x - d.y * d.y)};
}

sh::RgbCoefficients light_of(const std::string& dir, const std::string& spec, int bands) {
  const std::string out = dir + "/l.json";
  const test::RunResult r = test::run_prt("light '" + spec + "' --bands " + std::to_string(bands) + " -o " + out);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return light::read_light_file(out);
}

}  // namespace

TEST_CASE("prt light takes directional, cone, hemisphere and constant lights", "[light][cli]") {
  const std::string dir = test::fresh_temp_dir("cli_analytic");
  // Directional, 3 bands: Y_i(d) colour 16 pi / 17 (an albedo-1 Lambert surface facing it shows colour).
  const glm::dvec3 d = glm::dvec3(1, 2, -2) / 3.0;
  const sh::RgbCoefficients dl = light_of(dir, "directional:1,2,-2:2,1,0.5", 3);
  const std::array<double, 9> y = basis9(d);
  for (int i = 0; i < 9; ++i) {
    CHECK(dl.values[i].r == Approx(y[i] * 2.0 * 16 * M_PI / 17).epsilon(1e-8).margin(1e-9));
    CHECK(dl.values[i].b == Approx(y[i] * 0.5 * 16 * M_PI / 17).epsilon(1e-8).margin(1e-9));
  }
  // Cone about +z, half-angle 30 degrees, 4 bands: c_l0 = 2 pi sqrt((2l+1)/4pi) integral_{cos a}^1 P_l,
  // by Simpson's rule on P_0..P_3; every m != 0 coefficient is zero.
  const sh::RgbCoefficients cone = light_of(dir, "cone:0,0,1:30:1,1,1", 4);
  auto legendre = [](int l, double t) { return l == 0 ? 1.0 : l == 1 ? t : l == 2 ? 1.5 * t * t - 0.5 : 2.5 * t * t * t - 1.5 * t; };
  for (int l = 0; l < 4; ++l) {
    const int n = 2000;
    const double a = std::cos(M_PI / 6), h = (1.0 - a) / n;
    double integral = 0.0;
    for (int k = 0; k <= n; ++k) integral += (k == 0 || k == n ? 1 : (k % 2 ? 4 : 2)) * legendre(l, a + k * h);
    integral *= h / 3;
    for (int m = -l; m <= l; ++m) {
      const double want = m == 0 ? 2 * M_PI * std::sqrt((2 * l + 1) / (4 * M_PI)) * integral : 0.0;
      CHECK(cone.values[l * (l + 1) + m].g == Approx(want).margin(1e-9));
    }
  }
  // Hemisphere sky 2 above +y, ground 0.5 below; plus a constant 0.25: c_0 = Y_0 (2 pi 2 + 2 pi 0.5) + 2 sqrt(pi) 0.25,
  // c_(1,-1) = -K_1 integral y L = -K_1 pi (2 - 0.5).
  const sh::RgbCoefficients hemi = light_of(dir, "hemisphere:0,3,0:2,2,2:0.5,0.5,0.5+constant:0.25,0.25,0.25", 2);
  CHECK(hemi.values[0].r == Approx(0.2820947918 * 2 * M_PI * 2.5 + 2 * std::sqrt(M_PI) * 0.25).epsilon(1e-9));
  CHECK(hemi.values[1].r == Approx(-0.4886025119 * M_PI * 1.5).epsilon(1e-9));
  CHECK(hemi.values[2].r == Approx(0.0).margin(1e-12));
  CHECK(hemi.values[3].r == Approx(0.0).margin(1e-12));
}

TEST_CASE("prt light: a bad analytic light is a one-line error and leaves no file", "[light][cli]") {
  const std::string dir = test::fresh_temp_dir("cli_analytic_bad");
  for (const auto& [spec, problem] : {std::pair<std::string, std::string>{"directional:0,0,0:1,1,1", "direction must be finite and non-zero"},
                                      {"cone:0,0,1:200:1,1,1", "half-angle in degrees in (0, 180]"},
                                      {"constant:1,2", "expected a radiance R,G,B"},
                                      {"directional:0,1,0", "expected directional:DX,DY,DZ:R,G,B"},
                                      {"constant:1,1,1+spot:0,1,0:1,1,1", "unknown analytic light 'spot'"}}) {
    const test::RunResult r = test::run_prt("light '" + spec + "' -o " + dir + "/l.json");
    INFO(spec << " -> " << r.output);
    CHECK(r.exit_code == 1);
    CHECK(r.output.rfind("prt: ", 0) == 0);
    CHECK(r.output.find(problem) != std::string::npos);
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
    CHECK(test::entries_in(dir) == 0);
  }
}
