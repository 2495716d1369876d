// The exact disc term of `prt shade --sun DISC` (shade/disc_direct.h) against the independent path
// tracer: the same disc rasterised into an otherwise black environment map, traced by `prt reference`
// (environment importance sampling). A sphere over a floor puts a penumbra on the floor. Diffuse
// (shadowed transfer, no bounce) and glossy (glossy-shadowed, Phong, toward an eye point).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "core/constants.h"
#include "image/image.h"
#include "support/run_prt.h"

using namespace prt;

namespace {

const std::string kMesh = std::string(PRT_SOURCE_DIR) + "/tests/data/sphere_on_floor.ply";

// Equirect convention of docs/conventions.md, written out.
glm::dvec3 direction_at(double u, double v) {
  const double phi = 2.0 * kPi * (u - 0.5), theta = kPi * v;
  return {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
}

// A black 1024 x 512 map holding a uniform disc (16 x 16 sub-samples per texel); returns its exact
// irradiance at normal incidence, sum L coverage Omega (d . w).
double write_disc_map(const std::string& path, const glm::dvec3& d, double radius, double radiance) {
  const int w = 1024, h = 512;
  image::Image im(w, h, 3);
  double energy = 0.0;
  for (int y = 0; y < h; ++y) {
    const double omega = (std::cos(kPi * y / h) - std::cos(kPi * (y + 1) / h)) * 2.0 * kPi / w;
    for (int x = 0; x < w; ++x) {
      const glm::dvec3 centre = direction_at((x + 0.5) / w, (y + 0.5) / h);
      if (glm::dot(centre, d) < std::cos(radius + 0.02)) continue;
      int inside = 0;
      for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i) inside += glm::dot(direction_at((x + (i + 0.5) / 16) / w, (y + (j + 0.5) / 16) / h), d) >= std::cos(radius);
      const double value = radiance * inside / 256.0;
      for (int c = 0; c < 3; ++c) im.at(x, y, c) = static_cast<float>(value);
      energy += value * omega * glm::dot(centre, d);
    }
  }
  image::write(path, im);
  return energy;
}

double rel_rms(const std::string& a, const std::string& b) {
  const test::RunResult r = test::run_prt("compare " + a + " " + b);
  REQUIRE(r.exit_code == 0);
  WARN(r.output);
  return std::stod(r.output.substr(r.output.find("rel_rms=") + 8));
}

}  // namespace

TEST_CASE("prt shade's exact disc term matches the path tracer on a penumbra, diffuse and glossy", "[sun][reference][slow]") {
  const std::string dir = test::fresh_temp_dir("sun_disc");
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.5, 0.8, 0.3));
  const double radius = 3.0 * kPi / 180.0;
  const double energy = write_disc_map(dir + "/disc.exr", d, radius, 2000.0);
  char sun[200];
  std::snprintf(sun, sizeof sun, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,3", d.x, d.y, d.z, energy, energy, energy);
  const std::string black = dir + "/black.exr";
  {
    image::Image zero(64, 32, 3);
    image::write(black, zero);
  }

  REQUIRE(test::run_prt("bake " + kMesh + " --transfer shadowed --bands 3 --samples 64 --footprint vertex -q -o " + dir + "/s.prt").exit_code == 0);
  REQUIRE(test::run_prt("shade " + kMesh + " " + dir + "/s.prt --env " + black + " --sun " + sun + " --sun-samples 256 -q -o " +
                        dir + "/shade.ply").exit_code == 0);
  REQUIRE(test::run_prt("reference " + kMesh + " --env " + dir + "/disc.exr --bounces 0 --samples 4096 --footprint vertex -q -o " + dir + "/ref.ply").exit_code == 0);
  CHECK(rel_rms(dir + "/shade.ply", dir + "/ref.ply") < 0.02);

  const std::string brdf = "phong:exponent=8,ks=0.6,kd=0.3";
  const std::string eye = "2.5,1.5,1.0";
  REQUIRE(test::run_prt("bake " + kMesh + " --transfer glossy-shadowed --brdf " + brdf + " --bands 3 --samples 64 --footprint vertex -q -o " + dir + "/g.prt").exit_code == 0);
  REQUIRE(test::run_prt("shade " + kMesh + " " + dir + "/g.prt --env " + black + " --sun " + sun + " --sun-samples 256 --eye " + eye +
                        " -q -o " + dir + "/gshade.ply").exit_code == 0);
  REQUIRE(test::run_prt("reference " + kMesh + " --env " + dir + "/disc.exr --bounces 0 --samples 4096 --brdf " + brdf + " --eye " + eye +
                        " --footprint vertex -q -o " + dir + "/gref.ply").exit_code == 0);
  CHECK(rel_rms(dir + "/gshade.ply", dir + "/gref.ply") < 0.03);
}
