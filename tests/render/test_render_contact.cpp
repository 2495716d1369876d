// Contact that stays lit: a wall standing on a floor, baked with `prt bake`'s default options, rendered
// by `prt render` and compared with `prt reference --image`, against the same scene with the wall lifted
// 1 mm off the floor (nothing touches there, so its error is what per-vertex transfer costs anyway).
// Runs the real prt binary end to end (light, bake, render, reference, compare).
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "support/run_prt.h"

namespace {

constexpr int kFloorQuads = 16;  // per side of the 2 x 2 floor
const char* const kView = " --camera 215,30,auto --size 160x120 --background black";

/// A 2 x 2 floor (y = 0, kFloorQuads^2 quads, normal +Y) and a wall [-0.6, 0.6] x [lift, lift + 0.8] x
/// [0.1, 0.2] of five quads (no bottom face), each face its own vertices and normal, as OBJ.
void write_scene(const std::string& path, double lift) {
  std::ofstream obj(path);
  obj << "vn 0 1 0\nvn 0 0 1\nvn 0 0 -1\nvn 1 0 0\nvn -1 0 0\n";
  const int n = kFloorQuads;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) obj << "v " << -1.0 + 2.0 * i / n << " 0 " << -1.0 + 2.0 * j / n << "\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i + 1;
      obj << "f " << a << "//1 " << a + n + 1 << "//1 " << a + n + 2 << "//1 " << a + 1 << "//1\n";
    }
  const double x0 = -0.6, x1 = 0.6, z0 = 0.1, z1 = 0.2, y0 = lift, y1 = lift + 0.8;
  struct Quad {
    double corners[4][3];
    int normal;  // 1-based vn
  };
  const std::vector<Quad> wall = {{{{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}}, 2},
                                  {{{x1, y0, z0}, {x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}}, 3},
                                  {{{x1, y0, z1}, {x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}}, 4},
                                  {{{x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}}, 5},
                                  {{{x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}, {x0, y1, z0}}, 1}};
  int next = (n + 1) * (n + 1) + 1;
  for (const Quad& q : wall) {
    for (const auto& p : q.corners) obj << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
    obj << "f";
    for (int k = 0; k < 4; ++k) obj << " " << next + k << "//" << q.normal;
    obj << "\n";
    next += 4;
  }
}

void run(const std::string& arguments) {
  const prt::test::RunResult r = prt::test::run_prt(arguments);
  INFO("prt " << arguments << "\n" << r.output);
  REQUIRE(r.exit_code == 0);
}

double rel_rms(const std::string& image, const std::string& reference) {
  const prt::test::RunResult r = prt::test::run_prt("compare " + image + " " + reference);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::size_t at = r.output.find("rel_rms=");
  REQUIRE(at != std::string::npos);
  return std::stod(r.output.substr(at + 8));
}

/// The image error of `prt bake <scene> <bake_options>` rendered against the path-traced image.
double image_error(const std::string& dir, const std::string& name, double lift, const std::string& bake_options) {
  const std::string scene = dir + "/" + name + ".obj", sky = dir + "/sky.exr";
  write_scene(scene, lift);
  run("bake " + scene + " --bands 5" + bake_options + " -q -o " + dir + "/" + name + ".prt");
  run("render " + scene + " " + dir + "/" + name + ".prt --env " + sky + " --sun none --window none" + kView + " -q -o " +
      dir + "/" + name + ".exr");
  run("reference " + scene + " --image --env " + sky + " --band-limit 5 --bounces 0 --spp 256" + kView + " -q -o " + dir +
      "/" + name + "_reference.exr");
  return rel_rms(dir + "/" + name + ".exr", dir + "/" + name + "_reference.exr");
}

}  // namespace

TEST_CASE("a wall standing on a floor, default bake options: image error within 1.2x of the wall lifted 1 mm",
          "[render][gl][cli][footprint][slow]") {
  const std::string dir = prt::test::fresh_temp_dir("render_contact");
  // A sky with a lobe from +X, +Y, +Z and a constant, band-limited to the bake's 5 bands (no discs: the
  // sky alone lights the scene, through the transfer). `prt bake`'s defaults: shadowed, 1024 rays.
  run("light 'cone:0.6,0.55,0.45:30:6,5.5,5+constant:0.25,0.3,0.4' --bands 5 -o " + dir + "/sky.json --preview " + dir +
      "/sky.exr --preview-width 256");
  const double standing = image_error(dir, "standing", 0.0, "");
  const double lifted = image_error(dir, "lifted", 0.001, "");
  std::printf("wall on a floor, default bake, 160x120 rel_rms against prt reference --image: standing %.4f, lifted 1 mm %.4f "
              "(ratio %.2f)\n", standing, lifted, standing / lifted);
  INFO("standing " << standing << ", lifted " << lifted);
  CHECK(standing <= 1.2 * lifted);
  CHECK(lifted < 0.05);  // the lifted wall itself is rendered close to the truth
}
