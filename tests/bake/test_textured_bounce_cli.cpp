// Colour bleeding from a textured floor (issue 33, "Bounces"): light that bounces off the floor onto a
// white wall carries the floor's base colour at the hit point, so an interreflected `prt bake` shaded
// per vertex by `prt shade` agrees with `prt reference` (the path tracer, which looks the texture up at
// each hit) on the wall's vertices. The floor's texture is red near the wall and green beyond; its two
// triangles' vertex albedos (footprint averages) mix the two, so a bake that interpolated vertex
// albedos at the hits would bleed a red-green mix onto the wall. The same per lightmap texel: a texel
// bake shaded by `prt shade --lightmap` against `prt reference --texels` on the wall's texels.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/atomic_file.h"
#include "image/compare.h"
#include "image/image.h"
#include "mesh/writers.h"
#include "support/run_prt.h"
#include "transfer/transfer_file.h"

using namespace prt;

namespace {

constexpr int kWallGrid = 5;  // wall vertices per side

// A 64 x 64 PNG (8-bit sRGB codes 255 and 13): red in the image rows py >= 48 (v < 1/4 with OBJ's v up:
// the floor's first metre, z < 1), green elsewhere.
void write_floor_texture(const std::string& path) {
  image::Image png(64, 64, 3);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool red = y >= 48;
      png.at(x, y, 0) = red ? 1.0f : 0.05f;
      png.at(x, y, 1) = red ? 0.05f : 1.0f;
      png.at(x, y, 2) = 0.05f;
    }
  image::write(path, png);
}

// The floor y = 0, x in [-2, 2], z in [0, 4], facing +y, textured (vt = ((x + 2) / 8, z / 4)), and a
// white wall z = 0, x in [-1, 1], y in [0, 2], facing +z, as a kWallGrid^2 vertex grid, untextured, its
// vt in [0.55, 0.95] x [0.05, 0.95] (OBJ ignores map_Kd unless every corner has a vt; the vt are also
// the lightmap UVs, one chart per surface).
std::string write_scene(const std::string& dir) {
  write_floor_texture(dir + "/floor.png");
  std::ofstream(dir + "/scene.mtl") << "newmtl floor\nKd 1 1 1\nmap_Kd -clamp on floor.png\nnewmtl wall\nKd 0.8 0.8 0.8\n";
  std::ofstream obj(dir + "/scene.obj");
  obj << "mtllib scene.mtl\nv -2 0 0\nv 2 0 0\nv 2 0 4\nv -2 0 4\nvt 0 0\nvt 0.5 0\nvt 0.5 1\nvt 0 1\nvn 0 1 0\nvn 0 0 1\n"
         "usemtl floor\nf 1/1/1 4/4/1 3/3/1\nf 1/1/1 3/3/1 2/2/1\n";
  for (int j = 0; j < kWallGrid; ++j)
    for (int i = 0; i < kWallGrid; ++i) {
      const double s = double(i) / (kWallGrid - 1), t = double(j) / (kWallGrid - 1);
      obj << "v " << -1.0 + 2.0 * s << ' ' << 2.0 * t << " 0\nvt " << 0.55 + 0.4 * s << ' ' << 0.05 + 0.9 * t << '\n';
    }
  obj << "usemtl wall\n";
  auto corner = [](int i, int j) {  // the wall's vertex (i, j) with its own vt: "v/vt/2"
    const int v = 5 + i + j * kWallGrid;
    return std::to_string(v) + "/" + std::to_string(v) + "/2 ";
  };
  for (int j = 0; j + 1 < kWallGrid; ++j)
    for (int i = 0; i + 1 < kWallGrid; ++i) {
      obj << "f " << corner(i, j) << corner(i + 1, j) << corner(i + 1, j + 1) << '\n';
      obj << "f " << corner(i, j) << corner(i + 1, j + 1) << corner(i, j + 1) << '\n';
    }
  image::Image env(64, 32, 3);
  for (float& x : env.pixels) x = 1.0f;
  image::write(dir + "/white.exr", env);
  return dir + "/scene.obj";
}

// The wall's vertices (after the floor's 4) of a colour PLY, as floats.
std::vector<float> wall_values(const std::string& path) {
  const mesh::ColourPly ply = mesh::read_ply_colours(path);
  REQUIRE(ply.colours.size() == 4 + kWallGrid * kWallGrid);
  std::vector<float> out;
  for (std::size_t v = 4; v < ply.colours.size(); ++v)
    for (int c = 0; c < 3; ++c) out.push_back(ply.colours[v][c]);
  return out;
}

double srgb_to_linear(double code) { return code <= 0.04045 ? code / 12.92 : std::pow((code + 0.055) / 1.055, 2.4); }

// The floor's albedo at (x, z): write_floor_texture's colours (texels within 0.05 of the red-green edge,
// which the bilinear filter blends, are left out: returns false).
bool floor_albedo(double z, glm::dvec3* albedo) {
  if (std::abs(z - 1.0) < 0.05) return false;
  const double low = srgb_to_linear(13.0 / 255.0);
  *albedo = z < 1.0 ? glm::dvec3(1.0, low, low) : glm::dvec3(low, 1.0, low);
  return true;
}

// What the per-vertex reference does not estimate (estimator.h): over each floor vertex's hat function
// h (its barycentric weight on the floor's two triangles), the mean of albedo(x) E(x) / pi (what a
// renderer multiplying the texture per pixel shows) against albedo_avg x E_avg / pi, from the reference
// radiance L = albedo E / pi at the floor's texel centres (lightmap u < 1/2: x = 8u - 2, z = 4 (1 - v)).
// Returns the largest relative difference over the floor's vertices and channels.
double footprint_product_gap(const image::Image& ref, const std::vector<std::uint8_t>& coverage) {
  const glm::dvec2 corner[4] = {{-2, 0}, {2, 0}, {2, 4}, {-2, 4}};  // the floor's vertices 1..4 in (x, z)
  const int triangles[2][3] = {{0, 3, 2}, {0, 2, 1}};
  glm::dvec3 sum_h[4] = {}, sum_a[4] = {}, sum_e[4] = {}, sum_ae[4] = {};
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 32; ++x) {
      glm::dvec3 a;
      const glm::dvec2 p(8.0 * (x + 0.5) / 64.0 - 2.0, 4.0 * (1.0 - (y + 0.5) / 64.0));
      if (coverage[std::size_t(y) * 64 + x] != transfer::kTexelCovered || !floor_albedo(p.y, &a)) continue;
      const int* t = triangles[p.y > p.x + 2.0 ? 0 : 1];
      const glm::dvec2 e1 = corner[t[1]] - corner[t[0]], e2 = corner[t[2]] - corner[t[0]], d = p - corner[t[0]];
      const double det = e1.x * e2.y - e1.y * e2.x;
      const double b1 = (d.x * e2.y - d.y * e2.x) / det, b2 = (e1.x * d.y - e1.y * d.x) / det;
      const double h[3] = {1.0 - b1 - b2, b1, b2};
      const glm::dvec3 l(ref.at(x, y, 0), ref.at(x, y, 1), ref.at(x, y, 2));
      for (int k = 0; k < 3; ++k) {
        sum_h[t[k]] += h[k];
        sum_a[t[k]] += h[k] * a;
        sum_e[t[k]] += h[k] * l / a;
        sum_ae[t[k]] += h[k] * l;
      }
    }
  double gap = 0.0;
  for (int v = 0; v < 4; ++v)
    for (int c = 0; c < 3; ++c) {
      const double mean_ae = sum_ae[v][c] / sum_h[v][c], product = (sum_a[v][c] / sum_h[v][c]) * (sum_e[v][c] / sum_h[v][c]);
      gap = std::max(gap, std::abs(product - mean_ae) / mean_ae);
    }
  return gap;
}

}  // namespace

TEST_CASE("an interreflected bake bleeds a textured floor's colour at the hits onto a white wall as the reference does",
          "[bake][cli][albedo][bounces]") {
  const std::string dir = test::fresh_temp_dir("textured_bounce");
  const std::string obj = write_scene(dir);
  const std::string env = " --env " + dir + "/white.exr";
  const std::string bake = "bake " + obj + " --transfer interreflected --bounces 2 --bands 1 --samples 4096 -q";
  REQUIRE(test::run_prt(bake + " --threads 2 -o " + dir + "/t.prt").exit_code == 0);
  // The hit lookups keep the bake deterministic: the same bytes for any thread count.
  REQUIRE(test::run_prt(bake + " --threads 1 -o " + dir + "/t1.prt").exit_code == 0);
  CHECK(read_file(dir + "/t.prt") == read_file(dir + "/t1.prt"));
  REQUIRE(test::run_prt("shade " + obj + " " + dir + "/t.prt" + env + " -q -o " + dir + "/shade.ply").exit_code == 0);
  REQUIRE(test::run_prt("reference " + obj + env + " --bounces 2 --samples 16384 -q -o " + dir + "/ref.ply").exit_code == 0);
  const std::vector<float> shade = wall_values(dir + "/shade.ply"), ref = wall_values(dir + "/ref.ply");
  const double rel_rms = image::compare_values(shade.data(), ref.data(), shade.size()).rel_rms;
  INFO("wall rel_rms " << rel_rms);
  CHECK(rel_rms < 0.03);
}

TEST_CASE("a texel bake bleeds a textured floor's colour at the hits onto a white wall as prt reference --texels does",
          "[bake][cli][albedo][bounces][lightmap]") {
  const std::string dir = test::fresh_temp_dir("textured_bounce_texels");
  const std::string obj = write_scene(dir);
  const std::string env = " --env " + dir + "/white.exr", lm = dir + "/lm.prt";
  REQUIRE(test::run_prt("bake " + obj + " --lightmap 64 --transfer interreflected --bounces 2 --bands 1 --samples 1024 -q -o " + lm).exit_code == 0);
  REQUIRE(test::run_prt("shade " + obj + " " + lm + env + " --sun none --window none --lightmap -q -o " + dir + "/lit.exr").exit_code == 0);
  REQUIRE(test::run_prt("reference " + obj + env + " --texels " + lm + " --bounces 2 --samples 1024 -q -o " + dir + "/ref.exr").exit_code == 0);
  const std::vector<std::uint8_t> coverage = transfer::read_transfer(lm).coverage;
  const image::Image lit = image::read_rgb(dir + "/lit.exr"), ref = image::read_rgb(dir + "/ref.exr");
  // The wall's chart: u > 0.5, the lightmap's right half.
  std::vector<float> a, b;
  for (int y = 0; y < 64; ++y)
    for (int x = 32; x < 64; ++x)
      if (coverage[std::size_t(y) * 64 + x] == transfer::kTexelCovered)
        for (int c = 0; c < 3; ++c) a.push_back(lit.at(x, y, c)), b.push_back(ref.at(x, y, c));
  REQUIRE(a.size() > 3 * 500);
  const double rel_rms = image::compare_values(a.data(), b.data(), a.size()).rel_rms;
  INFO("wall texels " << a.size() / 3 << " rel_rms " << rel_rms);
  CHECK(rel_rms < 0.03);
  WARN("floor vertices: largest relative gap between albedo_avg x E_avg and the footprint mean of albedo x E: "
       << footprint_product_gap(ref, coverage));
}
