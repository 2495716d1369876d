// `prt render` of a lightmap against `prt reference --image`, next to a per-vertex bake of the same mesh:
// a box standing on a floor of two triangles, lit by a band-limited sky with a bright lobe (no discs:
// the sky alone carries the shadow, through the transfer). The floor's four vertices lie far from the
// box, so the per-vertex transfer cannot show the box's shadow; the lightmap must. Runs the real prt
// binary end to end (bake, render, reference, compare).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <glm/geometric.hpp>

#include "camera/camera.h"
#include "image/image.h"
#include "lightmap/lightmap_scenes.h"  // tests/lightmap
#include "mesh/mesh.h"
#include "support/run_prt.h"

using namespace prt;

namespace {

constexpr int kWidth = 160, kHeight = 120;
const char* const kCamera = "215,50,auto";  // from the shadow side (-X, -Z)
// The sky's lobe comes from +X, +Y, +Z (toward the light): the box's shadow falls toward -X, -Z.
const glm::dvec3 kLight = glm::normalize(glm::dvec3(0.6, 0.55, 0.45));

double luminance_at(const image::Image& image, const mesh::Mesh& mesh, const glm::dvec3& p) {
  camera::Camera cam = camera::parse_camera(kCamera);
  const camera::ViewMatrices view = camera::orbit_view(cam, mesh::bounds(mesh), kWidth, kHeight);
  const glm::dvec4 clip = view.projection * view.view * view.model * glm::dvec4(p, 1.0);
  const double x = (clip.x / clip.w + 1.0) * 0.5 * kWidth - 0.5, y = (1.0 - clip.y / clip.w) * 0.5 * kHeight - 0.5;
  double sum = 0.0;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) {
      const int px = int(std::lround(x)) + dx, py = int(std::lround(y)) + dy;
      REQUIRE((px >= 0 && py >= 0 && px < kWidth && py < kHeight));
      sum += 0.2126 * image.at(px, py, 0) + 0.7152 * image.at(px, py, 1) + 0.0722 * image.at(px, py, 2);
    }
  return sum / 25.0;
}

}  // namespace

TEST_CASE("prt render of a lightmap shows the box's shadow on a two-triangle floor that a per-vertex bake cannot",
          "[render][gl][lightmap][cli][slow]") {
  const std::string dir = test::fresh_temp_dir("render_lightmap_image");
  const std::string scene = dir + "/scene.obj", sky = dir + "/sky.exr";
  const mesh::Mesh mesh = test::floor_and_box(true, 0.0f);
  test::write_obj_with_uv(scene, mesh);
  char spec[160];
  std::snprintf(spec, sizeof spec, "cone:%.4f,%.4f,%.4f:30:6,5.5,5+constant:0.25,0.3,0.4", kLight.x, kLight.y, kLight.z);
  auto run = [](const std::string& arguments) {
    const test::RunResult r = test::run_prt(arguments);
    INFO("prt " << arguments << "\n" << r.output);
    REQUIRE(r.exit_code == 0);
  };
  run("light '" + std::string(spec) + "' --bands 5 -o " + dir + "/sky.json --preview " + sky + " --preview-width 256");
  run("bake " + scene + " --transfer shadowed --bands 5 --samples 256 --lightmap 128x128 -q -o " + dir + "/lightmap.prt");
  run("bake " + scene + " --transfer shadowed --bands 5 --samples 256 --footprint vertex -q -o " + dir + "/vertex.prt");
  const std::string view = std::string(" --env ") + sky + " --sun none --window none --background black --camera " + kCamera +
                           " --size " + std::to_string(kWidth) + "x" + std::to_string(kHeight) + " -q -o ";
  run("render " + scene + " " + dir + "/lightmap.prt" + view + dir + "/lightmap.exr");
  run("render " + scene + " " + dir + "/vertex.prt" + view + dir + "/vertex.exr");
  run("reference " + scene + " --image --env " + sky + " --band-limit 5 --bounces 0 --spp 256 --background black --camera " +
      kCamera + " --size " + std::to_string(kWidth) + "x" + std::to_string(kHeight) + " -q -o " + dir + "/reference.exr");

  const double lightmap_error = test::compare_rel_rms(dir + "/lightmap.exr", dir + "/reference.exr");
  const double vertex_error = test::compare_rel_rms(dir + "/vertex.exr", dir + "/reference.exr");
  std::printf("box on a two-triangle floor, 160x120, 5 bands, shadowed: rel_rms against prt reference --image: lightmap %.4f, "
              "per-vertex %.4f\n", lightmap_error, vertex_error);

  // On the floor just beside the box, away from the lobe (in its shadow), and out in the open toward it.
  const glm::dvec3 away = -glm::normalize(glm::dvec3(kLight.x, 0.0, kLight.z));
  const glm::dvec3 shadow = 0.42 * away, open = -0.75 * away;
  const image::Image reference = image::read_rgb(dir + "/reference.exr");
  const image::Image lightmap = image::read_rgb(dir + "/lightmap.exr");
  const image::Image vertex = image::read_rgb(dir + "/vertex.exr");
  const double ref_shadow = luminance_at(reference, mesh, shadow), lightmap_shadow = luminance_at(lightmap, mesh, shadow);
  const double ref_ratio = ref_shadow / luminance_at(reference, mesh, open);
  const double lightmap_ratio = lightmap_shadow / luminance_at(lightmap, mesh, open);
  const double vertex_ratio = luminance_at(vertex, mesh, shadow) / luminance_at(vertex, mesh, open);
  std::printf("shadow / open floor luminance: reference %.3f, lightmap %.3f, per-vertex %.3f\n", ref_ratio, lightmap_ratio, vertex_ratio);
  INFO("shadow / open floor luminance: reference " << ref_ratio << ", lightmap " << lightmap_ratio << ", per-vertex " << vertex_ratio);
  CHECK(ref_ratio < 0.5);                                          // the truth has a deep shadow there
  CHECK(std::abs(lightmap_ratio - ref_ratio) < 0.1);               // the lightmap shows it, about as deep
  CHECK(std::abs(lightmap_shadow - ref_shadow) < 0.15 * ref_shadow);
  // The four floor vertices cannot: their interpolation keeps the spot lit (the floor's light only
  // grades from corner to corner).
  CHECK(vertex_ratio > 0.6);
  CHECK(vertex_ratio > 3.0 * ref_ratio);
  INFO("rel_rms lightmap " << lightmap_error << ", per-vertex " << vertex_error);
  CHECK(lightmap_error < 0.5 * vertex_error);
}

TEST_CASE("prt render refuses a lightmap with a mesh whose lightmap UVs differ, in one line, writing nothing",
          "[render][gl][lightmap][cli]") {
  const std::string dir = test::fresh_temp_dir("render_lightmap_bad");
  mesh::Mesh mesh = test::floor_and_box(false);
  test::write_obj_with_uv(dir + "/floor.obj", mesh);
  const test::RunResult bake = test::run_prt("bake " + dir + "/floor.obj --transfer unshadowed --bands 2 --lightmap 16x16 -q -o " +
                                             dir + "/floor.prt");
  INFO(bake.output);
  REQUIRE(bake.exit_code == 0);
  REQUIRE(test::run_prt("light 'constant:1,1,1' --bands 2 -o " + dir + "/white.json").exit_code == 0);
  for (glm::vec2& uv : mesh.lightmap_uv) uv = glm::vec2(0.5f) + 0.5f * (uv - glm::vec2(0.5f));  // same positions, other UVs
  test::write_obj_with_uv(dir + "/moved.obj", mesh);
  const test::RunResult r = test::run_prt("render " + dir + "/moved.obj " + dir + "/floor.prt --env " + dir +
                                          "/white.json --size 32x32 -o " + dir + "/out.png");
  INFO(r.output);
  CHECK(test::fails_in_one_line(r, "different lightmap UVs"));
  CHECK_FALSE(std::filesystem::exists(dir + "/out.png"));
  const test::RunResult ok = test::run_prt("render " + dir + "/floor.obj " + dir + "/floor.prt --env " + dir +
                                           "/white.json --size 32x32 -q -o " + dir + "/out.png");
  INFO(ok.output);
  CHECK(ok.exit_code == 0);
  CHECK(std::filesystem::exists(dir + "/out.png"));
}
