// Where a texel bake's UVs come from (lightmap/uv_source.h) and what it tolerates in a user's UVs
// (lightmap/uv_validation.h, "Lightmap UV defects"): generated UVs against hand-made ones on the box on
// the two-triangle floor, 11 zero-area triangles in 110k named in the summary, UVs a hair outside
// [0,1] clamped, tiling UVs refused and then generated with --uv auto. Runs the real prt binary.
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>

#include <catch2/catch.hpp>

#include <glm/geometric.hpp>

#include "image/image.h"
#include "lightmap/lightmap_scenes.h"
#include "mesh/engine_gltf.h"
#include "mesh/mesh.h"
#include "support/run_prt.h"
#include "transfer/transfer_file.h"

namespace prt {

namespace {

const char* kEngine = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

// The lightmap UV of floor point (x, 0, z) of `m`: barycentric in the floor triangle (all corners at
// y = 0, normal up) that contains it; false if none does.
bool floor_uv(const mesh::Mesh& m, double x, double z, glm::vec2& uv) {
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    glm::dvec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = glm::dvec3(m.positions[m.indices[3 * t + std::size_t(k)]]);
    if (p[0].y != 0.0 || p[1].y != 0.0 || p[2].y != 0.0) continue;
    const double d = (p[1].x - p[0].x) * (p[2].z - p[0].z) - (p[2].x - p[0].x) * (p[1].z - p[0].z);
    const double b1 = ((x - p[0].x) * (p[2].z - p[0].z) - (p[2].x - p[0].x) * (z - p[0].z)) / d;
    const double b2 = ((p[1].x - p[0].x) * (z - p[0].z) - (x - p[0].x) * (p[1].z - p[0].z)) / d;
    if (b1 < 0.0 || b2 < 0.0 || b1 + b2 > 1.0) continue;
    const glm::dvec2 u = glm::dvec2(m.lightmap_uv[3 * t]) * (1.0 - b1 - b2) + glm::dvec2(m.lightmap_uv[3 * t + 1]) * b1 +
                         glm::dvec2(m.lightmap_uv[3 * t + 2]) * b2;
    uv = glm::vec2(u);
    return true;
  }
  return false;
}

// Bakes (shadowed, 64 x 64) and shades `mesh_path` under `sky`; returns the lit texel image.
image::Image bake_and_shade(const std::string& dir, const std::string& mesh_path, const std::string& sky, const std::string& name) {
  const std::string lm = dir + "/" + name + ".prt", lit = dir + "/" + name + "_lit.exr";
  const test::RunResult b = test::run_prt("bake " + mesh_path + " --quiet --lightmap 64 --samples 512 -o " + lm);
  INFO(b.output);
  REQUIRE(b.exit_code == 0);
  REQUIRE(test::run_prt("shade " + mesh_path + " " + lm + " --env " + sky + " --sun none --window none --lightmap -o " + lit).exit_code == 0);
  return image::read_rgb(lit);
}

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A user's file with the lightmap UVs of `m` as TEXCOORD_1: one node, one primitive (materials dropped, so
// that its triangles keep the mesh's order and numbers).
void write_user_uvs(const std::string& path, mesh::Mesh m) {
  m.materials.clear();
  m.triangle_material.clear();
  m.textures.clear();
  m.base_color_uv.clear();
  m.lightmap_uv_set = 1;
  mesh::EngineExtras as_loaded;
  as_loaded.lightmap_set = 1;
  as_loaded.as_loaded = true;
  mesh::write_engine_glb(path, path, m, as_loaded);
}

}  // namespace

TEST_CASE("generated UVs: box on the two-triangle floor lit as with hand-made UVs within 1% rel_rms over the floor", "[lightmap][unwrap]") {
  const std::string dir = test::fresh_temp_dir("uv_generated_floor");
  const std::string hand = dir + "/hand.obj", generated = dir + "/generated.glb", sky = dir + "/sky.exr";
  test::write_obj_with_uv(hand, test::floor_and_box(true));
  test::write_test_sky(sky);
  const test::RunResult u = test::run_prt("unwrap " + hand + " -o " + generated + " --size 64 --padding 2");
  INFO(u.output);
  REQUIRE(u.exit_code == 0);
  const image::Image a = bake_and_shade(dir, hand, sky, "hand"), b = bake_and_shade(dir, generated, sky, "generated");
  const mesh::Mesh ma = mesh::load_mesh(hand, nullptr, true), mb = mesh::load_mesh(generated, nullptr, true);
  // Floor points on a 64 x 64 grid, 0.1 away from the floor's edge and from the box's footprint
  // (|x|, |z| < 0.3: texels there are buried and moved, differently for each chart layout).
  double err = 0.0, norm = 0.0;
  std::size_t points = 0;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      const double x = -0.9 + 1.8 * (i + 0.5) / 64.0, z = -0.9 + 1.8 * (j + 0.5) / 64.0;
      if (std::abs(x) < 0.4 && std::abs(z) < 0.4) continue;
      glm::vec2 ua, ub;
      REQUIRE(floor_uv(ma, x, z, ua));
      REQUIRE(floor_uv(mb, x, z, ub));
      for (int c = 0; c < 3; ++c) {
        const double va = test::bilinear(a, ua, c), vb = test::bilinear(b, ub, c);
        err += (vb - va) * (vb - va);
        norm += va * va;
      }
      ++points;
    }
  const double rel_rms = std::sqrt(err / norm);
  WARN("floor points " << points << ", generated vs hand-made UVs: rel_rms " << rel_rms);
  CHECK(points > 2000);
  CHECK(rel_rms <= 0.01);
}

TEST_CASE("tolerant UVs: 11 zero-area triangles in 110k bake and the summary names each one", "[lightmap][unwrap]") {
  const std::string dir = test::fresh_temp_dir("uv_zero_area");
  REQUIRE(test::run_prt("unwrap " + std::string(kEngine) + " -o " + dir + "/engine.glb --size 512 -q").exit_code == 0);
  mesh::Mesh m = mesh::load_mesh(dir + "/engine.glb", nullptr, true);
  REQUIRE(m.triangle_count() > 100000);
  std::vector<std::size_t> collapsed;
  for (std::size_t k = 0; k < 11; ++k) {
    const std::size_t t = 1234 + 9871 * k;
    m.lightmap_uv[3 * t + 1] = m.lightmap_uv[3 * t + 2] = m.lightmap_uv[3 * t];
    collapsed.push_back(t);
  }
  write_user_uvs(dir + "/user.glb", m);
  const test::RunResult r =
      test::run_prt("bake " + dir + "/user.glb --lightmap 512 --transfer unshadowed --no-sample-repair -o " + dir + "/user.prt");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("11 triangle(s) collapsed to zero UV area") != std::string::npos);
  for (std::size_t t : collapsed) CHECK(r.output.find("node 0 mesh 0 primitive 0 triangle " + std::to_string(t)) != std::string::npos);
  // Before tolerance the same file was refused; the same UVs with far more defects still are.
  mesh::Mesh many = m;
  for (std::size_t t = 0; t < many.triangle_count(); t += 20) many.lightmap_uv[3 * t + 1] = many.lightmap_uv[3 * t + 2] = many.lightmap_uv[3 * t];
  write_user_uvs(dir + "/many.glb", many);
  const test::RunResult refused =
      test::run_prt("bake " + dir + "/many.glb --lightmap 512 --transfer unshadowed -q -o " + dir + "/many.prt");
  CHECK(test::fails_in_one_line(refused, "collapsed to zero UV area"));
  CHECK(refused.output.find("more than the 1% prt repairs") != std::string::npos);
}

TEST_CASE("tolerant UVs: triangles with UVs far outside the unit square are skipped and bounces that hit them read finite texels", "[lightmap][unwrap]") {
  const std::string dir = test::fresh_temp_dir("uv_far_outside");
  const std::string lion = std::string(PRT_SOURCE_DIR) + "/assets/meshes/guardian_lion_10k.ply";
  REQUIRE(test::run_prt("unwrap " + lion + " -o " + dir + "/lion.glb --size 256 -q").exit_code == 0);
  mesh::Mesh m = mesh::load_mesh(dir + "/lion.glb", nullptr, true);
  for (std::size_t t : {100, 5000, 9000, 15000, 19000}) m.lightmap_uv[3 * t + 1] = glm::vec2(1e9f, -3e9f);
  write_user_uvs(dir + "/user.glb", m);
  const test::RunResult r = test::run_prt("bake " + dir + "/user.glb --lightmap 256 --transfer interreflected --samples 16 --bounces 1 -o " +
                                          dir + "/user.prt");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("5 triangle(s) with UVs outside [0,1]") != std::string::npos);
  CHECK(r.output.find("node 0 mesh 0 primitive 0 triangle 9000") != std::string::npos);
  const transfer::TransferData data = transfer::read_transfer(dir + "/user.prt");
  for (float x : data.values) REQUIRE(std::isfinite(x));
}

TEST_CASE("tolerant UVs: a hair outside the unit square is clamped and tiling UVs are refused by --uv file and generated by --uv auto", "[lightmap][unwrap]") {
  const std::string dir = test::fresh_temp_dir("uv_tiling");
  mesh::Mesh hair = test::floor_and_box(true);
  hair.lightmap_uv[0].x = -0.0004f;  // floor triangle 0, under half a texel of a 1024 lightmap
  test::write_obj_with_uv(dir + "/hair.obj", hair);
  const test::RunResult h = test::run_prt("bake " + dir + "/hair.obj --lightmap 32 --transfer unshadowed -o " + dir + "/hair.prt");
  INFO(h.output);
  CHECK(h.exit_code == 0);
  CHECK(h.output.find("1 triangle(s) with UVs at most 0.001 outside [0,1], clamped: triangle 0") != std::string::npos);

  mesh::Mesh tiling = test::floor_and_box(true);
  for (glm::vec2& uv : tiling.lightmap_uv) uv = uv * 4.0f - 1.5f;  // a texture repeated 4 times
  test::write_obj_with_uv(dir + "/tiling.obj", tiling);
  CHECK(test::fails_in_one_line(test::run_prt("bake " + dir + "/tiling.obj --lightmap 32 -q -o " + dir + "/t.prt"),
                                "these look like tiling texture UVs (TEXCOORD_0), not lightmap UVs; generate lightmap UVs with --uv auto"));
  const test::RunResult a = test::run_prt("bake " + dir + "/tiling.obj --lightmap 32 --transfer unshadowed --uv auto -o " + dir + "/t.prt");
  INFO(a.output);
  REQUIRE(a.exit_code == 0);
  CHECK(a.output.find("tiling.obj: lightmap UVs generated (lightmap UVs:") != std::string::npos);
  // The generated UVs are prt unwrap's at the bake's size and padding max(1, gutter): same UV fingerprint.
  REQUIRE(test::run_prt("unwrap " + dir + "/tiling.obj -o " + dir + "/t.glb --size 32 --padding 2 -q").exit_code == 0);
  CHECK(transfer::read_transfer(dir + "/t.prt").header.uv_fingerprint == mesh::uv_fingerprint(mesh::load_mesh(dir + "/t.glb", nullptr, true)));
  // Good UVs are kept by --uv auto: the same bytes as --uv file.
  test::write_obj_with_uv(dir + "/good.obj", test::floor_and_box(true));
  REQUIRE(test::run_prt("bake " + dir + "/good.obj --lightmap 32 --transfer unshadowed -q -o " + dir + "/f.prt").exit_code == 0);
  REQUIRE(test::run_prt("bake " + dir + "/good.obj --lightmap 32 --transfer unshadowed -q --uv auto -o " + dir + "/g.prt").exit_code == 0);
  CHECK(bytes_of(dir + "/f.prt") == bytes_of(dir + "/g.prt"));
  CHECK(test::fails_in_one_line(test::run_prt("bake " + dir + "/good.obj --lightmap 32 -q --uv maybe -o " + dir + "/x.prt"),
                                "--uv maybe: expected file, auto or generate"));
  CHECK(test::fails_in_one_line(test::run_prt("bake " + dir + "/good.obj -q --uv auto -o " + dir + "/x.prt"), "--uv applies to texel bakes only"));
  CHECK(!std::ifstream(dir + "/x.prt").good());
}

TEST_CASE("glTF triangle sources: node and mesh and primitive and triangle of every triangle of 2CylinderEngine", "[lightmap][mesh]") {
  mesh::LoadReport report;
  const mesh::Mesh m = mesh::load_mesh(kEngine, &report, true);
  REQUIRE(m.triangle_source.size() == m.triangle_count());
  CHECK(m.source_primitives.size() > 20);
  // Triangles of one primitive are consecutive and their indices increase (degenerate ones dropped between).
  for (std::size_t t = 1; t < m.triangle_count(); ++t)
    if (m.triangle_source[t].primitive == m.triangle_source[t - 1].primitive) CHECK(m.triangle_source[t].triangle > m.triangle_source[t - 1].triangle);
  CHECK(mesh::describe_triangle(m, 0).rfind("node ", 0) == 0);
  CHECK(mesh::describe_triangle(m, 0).find(" mesh ") != std::string::npos);
  CHECK(mesh::describe_triangle(m, 0).find(" primitive ") != std::string::npos);
}

}  // namespace prt
