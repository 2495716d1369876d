// The 3-channel rule for textured meshes (issue 33; docs/conventions.md "Albedo and textures"): a mesh
// whose every vertex footprint averages its texture to grey still bakes 3-channel transfer, because the
// bounces take the base colour at each hit, which is not grey. The mesh: the inside of an open hexagonal
// prism whose six faces alternate magenta (1, 0, 1) and green (0, 1, 0) texels (nearest filter). Every
// vertex lies on an edge between a magenta and a green face, with equal areas of each around it (mirror
// images: the faces' diagonals alternate), so its footprint average is (1/2, 1/2, 1/2) exactly; the
// light bounced between the faces under a lop-sided sky is not grey. Truth: `prt reference`, the path
// tracer, which looks the texture up at each path vertex (tolerance as test_textured_bounce_cli.cpp).
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "image/compare.h"
#include "image/image.h"
#include "mesh/mesh.h"
#include "mesh/mesh_test_util.h"
#include "mesh/writers.h"
#include "support/run_prt.h"
#include "transfer/transfer_file.h"

using namespace prt;
using nlohmann::json;

namespace {

constexpr int kFaces = 6;        // even: the colours alternate around the prism
constexpr float kHeight = 3.0f;  // tall: most of what a vertex sees is the other faces (bounced light)

// The prism's corners: for k = 0..kFaces, bottom (y = 0) and top (y = kHeight) at angle 2 pi k / kFaces,
// radius 1, normals pointing in (horizontal), u = k / 2 (corner kFaces repeats corner 0's position and
// normal with u = kFaces / 2: a UV seam that the footprint rule joins), v = 0 at the top and 1 at the
// bottom. The 2 x 1 texture repeats: face k (u in [k/2, (k+1)/2]) shows texel k mod 2.
std::string write_prism(const std::string& dir) {
  image::Image png(2, 1, 3);
  const float texels[2][3] = {{1, 0, 1}, {0, 1, 0}};
  for (int x = 0; x < 2; ++x)
    for (int c = 0; c < 3; ++c) png.at(x, 0, c) = texels[x][c];
  image::write(dir + "/stripes.png", png);
  std::string bin;
  const int n = kFaces + 1;
  glm::vec3 lo(1e9f), hi(-1e9f);  // POSITION's min and max
  for (int k = 0; k < n; ++k)
    for (float y : {0.0f, kHeight}) {
      const double a = 2.0 * M_PI * (k % kFaces) / kFaces;
      const glm::vec3 p(float(std::cos(a)), y, float(std::sin(a)));
      lo = glm::min(lo, p), hi = glm::max(hi, p);
      for (int c = 0; c < 3; ++c) mesh::test::put(bin, p[c]);
    }
  for (int k = 0; k < n; ++k)
    for (int row = 0; row < 2; ++row) {
      const double a = 2.0 * M_PI * (k % kFaces) / kFaces;
      for (float x : {float(-std::cos(a)), 0.0f, float(-std::sin(a))}) mesh::test::put(bin, x);
    }
  for (int k = 0; k < n; ++k)
    for (float v : {1.0f, 0.0f}) mesh::test::put(bin, 0.5f * float(k)), mesh::test::put(bin, v);
  // Corner (k, row) is vertex 2k + row; face k's diagonal alternates so that each vertex's two faces are
  // mirror images about it. Winding: counter-clockwise seen from inside (the normals' side).
  for (int k = 0; k < kFaces; ++k) {
    const std::uint32_t b0 = 2 * k, t0 = b0 + 1, b1 = b0 + 2, t1 = b0 + 3;
    const std::uint32_t tris[2][3] = {{b0, t1, t0}, {b0, b1, t1}}, other[2][3] = {{b0, b1, t0}, {b1, t1, t0}};
    for (const auto& tri : k % 2 == 0 ? tris : other)
      for (std::uint32_t i : tri) mesh::test::put(bin, i);
  }
  std::ofstream(dir + "/prism.bin", std::ios::binary) << bin;
  const std::size_t vec3_bytes = std::size_t(2 * n) * 12, uv_bytes = std::size_t(2 * n) * 8;
  json doc = {
      {"asset", {{"version", "2.0"}}},
      {"buffers", {{{"uri", "prism.bin"}, {"byteLength", bin.size()}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", vec3_bytes}},
        {{"buffer", 0}, {"byteOffset", vec3_bytes}, {"byteLength", vec3_bytes}},
        {{"buffer", 0}, {"byteOffset", 2 * vec3_bytes}, {"byteLength", uv_bytes}},
        {{"buffer", 0}, {"byteOffset", 2 * vec3_bytes + uv_bytes}, {"byteLength", std::size_t(kFaces) * 24}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 2 * n}, {"type", "VEC3"}, {"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 2 * n}, {"type", "VEC3"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", 2 * n}, {"type", "VEC2"}},
        {{"bufferView", 3}, {"componentType", 5125}, {"count", kFaces * 6}, {"type", "SCALAR"}}}},
      {"images", {{{"uri", "stripes.png"}}}},
      {"samplers", {{{"magFilter", 9728}, {"minFilter", 9728}}}},
      {"textures", {{{"source", 0}, {"sampler", 0}}}},
      {"materials", {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0}}}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}, {"material", 0}}}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0}};
  std::ofstream(dir + "/prism.gltf") << doc.dump();
  // A sky bright on one side (the left half of the equirect: azimuths around -X), dim on the other.
  image::Image env(64, 32, 3);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) env.at(x, y, c) = x < 32 ? 2.0f : 0.2f;
  image::write(dir + "/sky.exr", env);
  return dir + "/prism.gltf";
}

std::vector<float> vertex_values(const std::string& path) {
  const mesh::ColourPly ply = mesh::read_ply_colours(path);
  std::vector<float> out;
  for (const glm::vec3& c : ply.colours)
    for (int ch = 0; ch < 3; ++ch) out.push_back(c[ch]);
  return out;
}

}  // namespace

TEST_CASE("a textured mesh whose vertex footprints all average to grey bakes 3 channels and bleeds the texture's colours",
          "[bake][cli][albedo][bounces]") {
  const std::string dir = test::fresh_temp_dir("grey_texture_channels");
  const std::string gltf = write_prism(dir);
  // The premise: every vertex's albedo (its footprint average) is grey, exactly (r = g = b as floats).
  const mesh::Mesh mesh = mesh::load_mesh(gltf, nullptr, true);
  REQUIRE(mesh.textured());
  REQUIRE(mesh.albedo.size() == 2 * (kFaces + 1));
  for (const glm::vec3& a : mesh.albedo) {
    INFO("vertex albedo " << a.r << " " << a.g << " " << a.b);
    REQUIRE((a.r == a.g && a.g == a.b));
    CHECK(a.r == Approx(0.5).epsilon(1e-6));
  }
  const std::string env = " --env " + dir + "/sky.exr";
  REQUIRE(test::run_prt("bake " + gltf + " --transfer interreflected --bounces 2 --bands 3 --samples 4096 -q -o " + dir +
                        "/t.prt").exit_code == 0);
  CHECK(transfer::read_transfer_header(dir + "/t.prt").channels == 3);
  REQUIRE(test::run_prt("shade " + gltf + " " + dir + "/t.prt" + env + " --sun none --window none -q -o " + dir +
                        "/shade.ply").exit_code == 0);
  REQUIRE(test::run_prt("reference " + gltf + env + " --band-limit 3 --bounces 2 --samples 16384 -q -o " + dir +
                        "/ref.ply").exit_code == 0);
  const std::vector<float> shade = vertex_values(dir + "/shade.ply"), ref = vertex_values(dir + "/ref.ply");
  REQUIRE(shade.size() == ref.size());
  // The truth is not grey (the sky is): the bounced light is coloured, (g - r) / r a few percent either
  // way. A 1-channel bake (grey transfer) would shade every vertex grey; the bake's colour follows the
  // truth's: its mean distance from it is under half the truth's mean colour.
  double truth_colour = 0.0, colour_error = 0.0;
  const std::size_t vertices = ref.size() / 3;
  for (std::size_t v = 0; v < vertices; ++v) {
    const double truth = (ref[3 * v + 1] - ref[3 * v]) / ref[3 * v], baked = (shade[3 * v + 1] - shade[3 * v]) / shade[3 * v];
    truth_colour += std::abs(truth) / double(vertices);
    colour_error += std::abs(baked - truth) / double(vertices);
  }
  const double rel_rms = image::compare_values(shade.data(), ref.data(), shade.size()).rel_rms;
  INFO("rel_rms " << rel_rms << ", mean |g - r| / r of the reference " << truth_colour << ", mean distance of the bake's "
       << colour_error);
  CHECK(truth_colour > 0.02);
  CHECK(colour_error < 0.5 * truth_colour);
  CHECK(rel_rms < 0.03);
}
