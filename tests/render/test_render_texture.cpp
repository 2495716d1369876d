// Textures per pixel in `prt render` (the albedo split, docs/conventions.md "Albedo and textures"),
// through the real binary: a checker quad under constant light shows each square's own albedo (a closed
// form), also with a disc; a bake with --albedo shows no texture; real third-party textured glTF assets
// (BoxTextured, TextureTransformTest, BoxTexcoords; tests/data/README.md) against `prt reference --image`,
// textured and with each texture replaced by its mean colour.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "camera/camera.h"
#include "image/image.h"
#include "mesh/mesh.h"
#include "support/checker_quad.h"
#include "support/run_prt.h"

using namespace prt;

namespace {

constexpr int kSize = 96;

void run_ok(const std::string& arguments) {
  const test::RunResult r = test::run_prt(arguments);
  INFO("prt " << arguments << "\n" << r.output);
  REQUIRE(r.exit_code == 0);
}

// The pixel of point (x, y, 0) from camera "0,0,auto" (looking down -Z) in a width x height frame of a
// mesh whose bounds are [0, extent] x [0, 1] x {0}.
glm::ivec2 quad_pixel(double x, double y, double extent = 1.0, int width = kSize, int height = kSize) {
  mesh::Bounds bounds;
  bounds.lo = glm::vec3(0.0f);
  bounds.hi = glm::vec3(float(extent), 1.0f, 0.0f);
  const camera::ViewMatrices view = camera::orbit_view(camera::parse_camera("0,0,auto"), bounds, width, height);
  const glm::dvec4 clip = view.projection * view.view * view.model * glm::dvec4(x, y, 0.0, 1.0);
  return {int(std::floor((clip.x / clip.w + 1.0) * 0.5 * width)), int(std::floor((1.0 - clip.y / clip.w) * 0.5 * height))};
}

// Every pixel on a 5 x 5 grid over the middle half of each checker square has radiance scale x the
// square's albedo, within 1% per channel.
void check_squares(const image::Image& image, const glm::dvec3& a, const glm::dvec3& b, double scale) {
  for (int sx = 0; sx < 2; ++sx)
    for (int sy = 0; sy < 2; ++sy) {
      const glm::dvec3 albedo = sx != sy ? b : a;  // (sx, sy) = (0, 1) and (1, 0) show a
      for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) {
          const glm::ivec2 p = quad_pixel(0.5 * sx + 0.125 + 0.0625 * i, 0.5 * (1 - sy) + 0.125 + 0.0625 * j);
          REQUIRE((p.x >= 0 && p.y >= 0 && p.x < kSize && p.y < kSize));
          for (int c = 0; c < 3; ++c) {
            INFO("square (" << sx << ", " << sy << "), pixel (" << p.x << ", " << p.y << "), channel " << c);
            CHECK(double(image.at(p.x, p.y, c)) == Approx(scale * albedo[c]).epsilon(0.01));
          }
        }
    }
}

std::string render_args(const std::string& dir, const std::string& out) {
  return std::string(" --env ") + dir + "/white.json --window none --background black --camera 0,0,auto --size " +
         std::to_string(kSize) + "x" + std::to_string(kSize) + " -q -o " + dir + "/" + out;
}

}  // namespace

TEST_CASE("prt render of a checker quad under constant light shows each square's albedo per pixel",
          "[render][gl][texture][cli]") {
  const std::string dir = test::fresh_temp_dir("render_texture_checker");
  glm::dvec3 a, b;
  const std::string obj = test::write_checker_quad(dir, &a, &b);
  run_ok("bake " + obj + " --transfer unshadowed --bands 1 -q -o " + dir + "/t.prt");
  run_ok("render " + obj + " " + dir + "/t.prt --sun none" + render_args(dir, "plain.exr"));
  check_squares(image::read_rgb(dir + "/plain.exr"), a, b, 1.0);
  // A disc of irradiance 1 straight above adds E cos / pi = 1 / pi times the albedo (unshadowed).
  run_ok("render " + obj + " " + dir + "/t.prt --sun 0,0,1,1,1,1,0.5" + render_args(dir, "sun.exr"));
  check_squares(image::read_rgb(dir + "/sun.exr"), a, b, 1.0 + 1.0 / 3.14159265358979);
  // The compressed transfer's pass does the same.
  run_ok("bake " + obj + " --transfer unshadowed --bands 1 --compress 1,1 -q -o " + dir + "/t.cprt");
  run_ok("render " + obj + " " + dir + "/t.cprt --sun none" + render_args(dir, "cpca.exr"));
  check_squares(image::read_rgb(dir + "/cpca.exr"), a, b, 1.0);
}

TEST_CASE("prt render of a bake with --albedo shows no texture", "[render][gl][texture][cli]") {
  const std::string dir = test::fresh_temp_dir("render_texture_option");
  glm::dvec3 a, b;
  const std::string obj = test::write_checker_quad(dir, &a, &b);
  run_ok("bake " + obj + " --transfer unshadowed --bands 1 --albedo 0.5,0.25,1 -q -o " + dir + "/t.prt");
  run_ok("render " + obj + " " + dir + "/t.prt --sun none" + render_args(dir, "option.exr"));
  const glm::dvec3 grey(0.5, 0.25, 1.0);
  check_squares(image::read_rgb(dir + "/option.exr"), grey, grey, 1.0);
}

namespace {

// Two unit quads side by side in z = 0 ([0, 1] and [1, 2] in x), each with its own material and a
// uniform PNG of its own size and 8-bit sRGB codes; returns the OBJ and sets the linear colours.
std::string write_two_textures(const std::string& dir, glm::dvec3 colour[2]) {
  const int codes[2][3] = {{200, 60, 30}, {40, 120, 230}}, sizes[2][2] = {{8, 8}, {32, 16}};
  std::ofstream mtl(dir + "/two.mtl");
  for (int q = 0; q < 2; ++q) {
    image::Image png(sizes[q][0], sizes[q][1], 3);
    for (int c = 0; c < 3; ++c) {
      const double code = codes[q][c] / 255.0;
      colour[q][c] = code <= 0.04045 ? code / 12.92 : std::pow((code + 0.055) / 1.055, 2.4);
      for (int y = 0; y < sizes[q][1]; ++y)
        for (int x = 0; x < sizes[q][0]; ++x) png.at(x, y, c) = float(code);
    }
    image::write(dir + "/t" + std::to_string(q) + ".png", png);
    mtl << "newmtl m" << q << "\nKd 1 1 1\nmap_Kd t" << q << ".png\n";
  }
  std::ofstream(dir + "/two.obj") << "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
                                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nusemtl m0\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n"
                                     "usemtl m1\nf 2/1/1 5/2/1 6/3/1\nf 2/1/1 6/3/1 3/4/1\n";
  return dir + "/two.obj";
}

}  // namespace

TEST_CASE("prt render of two materials with textures of different sizes shows each its own", "[render][gl][texture][cli]") {
  const std::string dir = test::fresh_temp_dir("render_texture_two");
  glm::dvec3 a, b, colour[2];
  test::write_checker_quad(dir, &a, &b);  // for white.json
  const std::string obj = write_two_textures(dir, colour);
  run_ok("bake " + obj + " --transfer unshadowed --bands 1 -q -o " + dir + "/two.prt");
  run_ok("render " + obj + " " + dir + "/two.prt --sun none --env " + dir + "/white.json --window none --background black "
         "--camera 0,0,auto --size 96x48 -q -o " + dir + "/two.exr");
  const image::Image image = image::read_rgb(dir + "/two.exr");
  for (int q = 0; q < 2; ++q) {
    const glm::ivec2 p = quad_pixel(q + 0.5, 0.5, 2.0, 96, 48);  // the middle of quad q
    for (int c = 0; c < 3; ++c) {
      INFO("quad " << q << ", pixel (" << p.x << ", " << p.y << "), channel " << c);
      CHECK(double(image.at(p.x, p.y, c)) == Approx(colour[q][c]).epsilon(0.01));
    }
  }
}

namespace {

// A textured third-party glTF asset of tests/data (tests/data/README.md: source and licence of each).
struct Asset {
  const char* folder;  // under tests/data, every file copied
  const char* gltf;
  const char* camera;  // --camera
};

// The asset's files in `dir`, or with each image replaced by a 4 x 4 one of its mean linear colour
// (8-bit sRGB, as the originals); returns the glTF's path there.
std::string copy_asset(const Asset& asset, const std::string& dir, bool mean_colour) {
  const std::filesystem::path source = std::filesystem::path(PRT_SOURCE_DIR "/tests/data") / asset.folder;
  for (const auto& entry : std::filesystem::directory_iterator(source)) {
    const std::string target = dir + "/" + entry.path().filename().string();
    std::filesystem::copy_file(entry.path(), target);
    const std::string extension = entry.path().extension().string();
    if (!mean_colour || (extension != ".png" && extension != ".jpg")) continue;
    const image::Image texture = image::read_rgb(entry.path().string());
    glm::dvec3 mean(0.0);
    for (std::size_t i = 0; i < texture.pixels.size(); ++i) mean[int(i % 3)] += texture.pixels[i];
    mean /= double(texture.pixels.size() / 3);
    image::Image flat(4, 4, 3);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        for (int c = 0; c < 3; ++c) flat.at(x, y, c) = float(test::encode_srgb(mean[c]));
    std::filesystem::remove(target);
    image::write(target, flat);
  }
  return dir + "/" + asset.gltf;
}

// prt bake + prt render of the asset against prt reference --image (the same 5-band sky); returns rel_rms.
double asset_error(const Asset& asset, const std::string& dir, bool mean_colour) {
  const std::string gltf = copy_asset(asset, dir, mean_colour);
  const std::string env = std::string(PRT_SOURCE_DIR) + "/assets/env/studio.exr";
  const std::string view = std::string(" --camera ") + asset.camera + " --size 96x96 --background black -q -o " + dir + "/";
  run_ok("bake " + gltf + " --transfer shadowed --bands 5 --samples 256 -q -o " + dir + "/asset.prt");
  run_ok("render " + gltf + " " + dir + "/asset.prt --env " + env + " --sun none --window none" + view + "render.exr");
  run_ok("reference " + gltf + " --image --env " + env + " --band-limit 5 --spp 256" + view + "reference.exr");
  return test::compare_rel_rms(dir + "/render.exr", dir + "/reference.exr");
}

// The issue 33 acceptance rule: texturing costs no accuracy (textured within 1.5x of the mean-colour copy).
void check_asset(const Asset& asset) {
  const std::string name = std::string("render_texture_") + asset.folder;
  const double textured = asset_error(asset, test::fresh_temp_dir(name), false);
  const double mean = asset_error(asset, test::fresh_temp_dir(name + "_mean"), true);
  std::printf("%s, 96x96, 5 bands, shadowed, studio.exr: rel_rms against prt reference --image: textured %.4f, "
              "textures replaced by their mean colours %.4f\n", asset.folder, textured, mean);
  CHECK(textured <= 1.5 * mean);
}

}  // namespace

TEST_CASE("prt render of the textured BoxTextured asset is as close to prt reference --image as its mean-colour copy",
          "[render][gl][texture][cli][slow]") {
  check_asset({"BoxTextured", "BoxTextured.gltf", "30,25,auto"});
}

// KHR_texture_transform (offset, rotation, scale, all three) with clamped samplers, on flat quads with
// small marker quads 1 cm in front of them.
TEST_CASE("prt render of the TextureTransformTest asset is as close to prt reference --image as its mean-colour copy",
          "[render][gl][texture][cli][slow]") {
  check_asset({"TextureTransformTest", "TextureTransformTest.gltf", "0,0,auto"});
}

// Two UV sets (the base colour on TEXCOORD_0, the metallic-roughness texture on TEXCOORD_1).
TEST_CASE("prt render of the BoxTexcoords asset is as close to prt reference --image as its mean-colour copy",
          "[render][gl][texture][cli][slow]") {
  check_asset({"BoxTexcoords", "boxTexcoords.gltf", "30,25,auto"});
}
