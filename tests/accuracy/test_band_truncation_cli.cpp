// Run-time band truncation (`prt shade --bands N`; docs/conventions.md, "Run-time band truncation"):
// an 8-band unshadowed bake of a unit sphere with exact radial normals, shaded under a cone light with
// the lighting truncated to N bands, against the closed-form N-band irradiance. The closed form uses
// only std::legendre and the clamped-cosine factors written out here (Ramamoorthi & Hanrahan 2001),
// none of prt's SH code:
//   cap of half-angle a about d, radiance R: zonal z_l = 2 pi K_l (P_(l-1)(cos a) - P_(l+1)(cos a)) / (2l+1)
//   (P_(-1) := 1), so by Funk-Hecke the N-band irradiance at normal n is
//   E_N(n) = R sum_(l<N) A_l (P_(l-1)(cos a) - P_(l+1)(cos a)) / 2 P_l(n . d),
//   and the exit radiance of albedo rho is rho / pi E_N.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <string>

#include <glm/geometric.hpp>

#include "mesh/writers.h"
#include "support/run_prt.h"
#include "support/shapes.h"

namespace {

using prt::test::run_prt;

const std::string kData = std::string(PRT_SOURCE_DIR) + "/tests/data/";

// Clamped-cosine convolution factor A_l: pi, 2 pi / 3, 0 for odd l > 1, and for even l
// 2 pi (-1)^(l/2 - 1) / ((l+2)(l-1)) * l! / (2^l ((l/2)!)^2).
double clamped_cosine_factor(int l) {
  if (l == 0) return M_PI;
  if (l == 1) return 2.0 * M_PI / 3.0;
  if (l % 2 == 1) return 0.0;
  const double ratio = std::exp(std::lgamma(l + 1.0) - l * std::log(2.0) - 2.0 * std::lgamma(l / 2 + 1.0));
  return 2.0 * M_PI * ((l / 2 - 1) % 2 == 0 ? 1.0 : -1.0) / ((l + 2.0) * (l - 1.0)) * ratio;
}

double legendre(int l, double x) { return l < 0 ? 1.0 : std::legendre(static_cast<unsigned>(l), x); }

// Irradiance per unit radiance of the cap (half-angle `a`) band-limited to `bands`, at angle cos_gamma.
double cap_irradiance(int bands, double a, double cos_gamma) {
  double e = 0.0;
  for (int l = 0; l < bands; ++l)
    e += clamped_cosine_factor(l) * 0.5 * (legendre(l - 1, std::cos(a)) - legendre(l + 1, std::cos(a))) *
         legendre(l, cos_gamma);
  return e;
}

// The unit UV sphere as an ASCII PLY with its exact (radial) normals.
std::string write_sphere(const std::string& dir) {
  const prt::mesh::Mesh m = prt::test::uv_sphere(12, 24);
  const std::string path = dir + "/sphere.ply";
  std::ofstream f(path);
  f << "ply\nformat ascii 1.0\nelement vertex " << m.positions.size()
    << "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
    << "element face " << m.indices.size() / 3 << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const glm::vec3& p : m.positions) {
    const glm::vec3 n = glm::normalize(p);
    f << p.x << " " << p.y << " " << p.z << " " << n.x << " " << n.y << " " << n.z << "\n";
  }
  for (std::size_t t = 0; t < m.indices.size(); t += 3)
    f << "3 " << m.indices[t] << " " << m.indices[t + 1] << " " << m.indices[t + 2] << "\n";
  return path;
}

}  // namespace

TEST_CASE("shade --bands N truncates the lighting to N whole bands (closed-form cone irradiance)", "[accuracy][bands]") {
  const std::string dir = prt::test::fresh_temp_dir("band_truncation");
  const std::string mesh = write_sphere(dir);
  REQUIRE(run_prt("bake " + mesh + " --transfer unshadowed --bands 8 --albedo 0.8,0.8,0.8 -q -o " + dir + "/t.prt").exit_code == 0);
  // The cone's exact 8-band coefficients (light::cone_light), unsplit and unwindowed.
  REQUIRE(run_prt("light cone:0.3,0.8,0.5:40:2,1,0.5 --bands 8 --sun none --window none -o " + dir + "/cone.json").exit_code == 0);
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.3, 0.8, 0.5));
  const double half_angle = 40.0 * M_PI / 180.0;
  const glm::dvec3 radiance(2.0, 1.0, 0.5);
  const double albedo = 0.8;
  for (int bands : {1, 2, 3, 5, 7, 8}) {
    CAPTURE(bands);
    const std::string out = dir + "/s" + std::to_string(bands) + ".ply";
    const auto run = run_prt("shade " + mesh + " " + dir + "/t.prt --light " + dir + "/cone.json --sun none --window none --bands " +
                             std::to_string(bands) + " -q -o " + out);
    REQUIRE(run.exit_code == 0);
    const prt::mesh::ColourPly ply = prt::mesh::read_ply_colours(out);
    double worst = 0.0, dropped_top = 0.0;
    for (std::size_t v = 0; v < ply.positions.size(); ++v) {
      const double c = glm::dot(glm::normalize(glm::dvec3(ply.positions[v])), d);
      for (int ch = 0; ch < 3; ++ch) {
        const double truth = albedo / M_PI * radiance[ch] * cap_irradiance(bands, half_angle, c);
        worst = std::max(worst, std::abs(ply.colours[v][ch] - truth) / radiance[ch]);
        dropped_top = std::max(dropped_top, std::abs(albedo / M_PI * radiance[ch] * cap_irradiance(bands - 1, half_angle, c) - truth) / radiance[ch]);
      }
    }
    CHECK(worst < 2e-5);
    // The wrong rule (the top kept band's lighting dropped) is far outside that tolerance wherever that
    // band reaches diffuse shading (A_l = 0 for odd l > 1: dropping band 7 of 8 changes nothing).
    if (clamped_cosine_factor(bands - 1) != 0.0) CHECK(dropped_top > 50 * 2e-5);
  }
}

TEST_CASE("shade --bands outside 1..the transfer's bands fails in one line", "[accuracy][bands]") {
  const std::string dir = prt::test::fresh_temp_dir("band_truncation_bad");
  const std::string mesh = write_sphere(dir);
  REQUIRE(run_prt("bake " + mesh + " --transfer unshadowed --bands 3 -q -o " + dir + "/t.prt").exit_code == 0);
  for (const char* bad : {"4", "-1"}) {
    const auto run = run_prt("shade " + mesh + " " + dir + "/t.prt --env " + kData + "hdri/courtyard.exr --bands " + bad + " -o " + dir + "/s.ply");
    CHECK(prt::test::fails_in_one_line(run, "--bands"));
    CHECK(prt::test::entries_in(dir) == 2);  // no partial output
  }
}
