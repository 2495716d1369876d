// `prt compress`, `prt bake --compress`, `prt info` and `prt shade` of .cprt files through the real
// binary: thread-independent bytes, the shaded output equal to the library's decompressed transfer,
// one-line errors that leave no file.
#include <catch2/catch.hpp>

#include <glm/geometric.hpp>

#include "compress/cprt_file.h"
#include "core/atomic_file.h"
#include "light/light_file.h"
#include "mesh/mesh.h"
#include "mesh/writers.h"
#include "light/scene_lighting.h"
#include "shade/scene_shading.h"
#include "shade/shade.h"
#include "support/run_prt.h"
#include "support/shapes.h"

using namespace prt;

namespace {

bool contains(const std::string& haystack, const std::string& needle) { return haystack.find(needle) != std::string::npos; }

struct Fixture {
  std::string dir, mesh_path, transfer_path, light_path;
};

// A torus with 3-band shadowed transfer (9 values per vertex) and a 3-band light.
Fixture make_fixture(const std::string& name) {
  Fixture f;
  f.dir = test::fresh_temp_dir(name);
  const mesh::Mesh torus = test::torus(1.0f, 0.45f, 24, 12);
  f.mesh_path = f.dir + "/torus.ply";
  mesh::write_ply(f.mesh_path, torus.positions, {}, torus.indices);
  f.transfer_path = f.dir + "/t.prt";
  REQUIRE(test::run_prt("bake " + f.mesh_path + " --bands 3 --samples 64 -q -o " + f.transfer_path).exit_code == 0);
  sh::RgbCoefficients l(3);
  l.values[0] = glm::dvec3(0.5, 0.45, 0.4);
  l.values[2] = glm::dvec3(0.3, 0.25, 0.2);
  l.values[3] = glm::dvec3(-0.15, -0.1, -0.05);
  f.light_path = f.dir + "/light.json";
  light::write_light_file(f.light_path, l, {});
  return f;
}

}  // namespace

TEST_CASE("prt compress: same bytes for 1 and 2 threads and from bake --compress, info, shade of .cprt", "[compress][cli]") {
  const Fixture f = make_fixture("compress_cli");
  const std::string common = "compress " + f.transfer_path + " --clusters 12 --pca 3 --light " + f.light_path;
  const test::RunResult one = test::run_prt(common + " --threads 1 -o " + f.dir + "/one.cprt");
  INFO(one.output);
  REQUIRE(one.exit_code == 0);
  CHECK(contains(one.output, "12 clusters, 3 PCA vectors"));
  CHECK(contains(one.output, "shaded radiance rel. error (rms)"));
  REQUIRE(test::run_prt(common + " --threads 2 -q -o " + f.dir + "/two.cprt").exit_code == 0);
  CHECK(read_file(f.dir + "/one.cprt") == read_file(f.dir + "/two.cprt"));
  // bake --compress K,N: the same model (same seed), without the radiance error.
  REQUIRE(test::run_prt("bake " + f.mesh_path + " --bands 3 --samples 64 -q --compress 12,3 -o " + f.dir + "/baked.cprt").exit_code == 0);
  REQUIRE(test::run_prt("compress " + f.transfer_path + " --clusters 12 --pca 3 -q -o " + f.dir + "/plain.cprt").exit_code == 0);
  CHECK(read_file(f.dir + "/baked.cprt") == read_file(f.dir + "/plain.cprt"));

  const test::RunResult info = test::run_prt("info " + f.dir + "/one.cprt");
  CHECK(contains(info.output, "prt compressed transfer file"));
  CHECK(contains(info.output, "compression: CPCA, 12 clusters, 3 PCA vectors"));
  CHECK(contains(info.output, "transfer rel. error (rms): "));

  // prt shade of the .cprt = shade_diffuse of the decompressed transfer (within float PLY storage).
  REQUIRE(test::run_prt("shade " + f.mesh_path + " " + f.dir + "/one.cprt --light " + f.light_path + " -o " + f.dir + "/out.ply")
              .exit_code == 0);
  const mesh::ColourPly shaded = mesh::read_ply_colours(f.dir + "/out.ply");
  const std::vector<glm::vec3> expected =
      shade::shade_diffuse(compress::decompress(compress::read_cprt(f.dir + "/one.cprt")), light::read_light_file(f.light_path));
  const std::vector<glm::vec3> uncompressed = shade::shade_diffuse(transfer::read_transfer(f.transfer_path), light::read_light_file(f.light_path));
  REQUIRE(shaded.colours.size() == expected.size());
  double differs = 0;
  for (std::size_t v = 0; v < expected.size(); ++v)
    for (int c = 0; c < 3; ++c) {
      CHECK(shaded.colours[v][c] == Approx(expected[v][c]).margin(1e-6));
      differs = std::max(differs, static_cast<double>(std::abs(expected[v][c] - uncompressed[v][c])));
    }
  CHECK(differs > 1e-5);  // it is the compressed transfer that was shaded
}

TEST_CASE("prt compress: bad K, N and damaged inputs are one-line errors and leave no file", "[compress][cli]") {
  const Fixture f = make_fixture("compress_cli_errors");
  const std::string out = f.dir + "/o.cprt";
  const std::size_t before = test::entries_in(f.dir);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--clusters 0 --pca 2", "--clusters 0 must be between 1 and the number of points (288)"},
      {"--clusters 289 --pca 2", "--clusters 289 must be between 1 and the number of points (288)"},
      {"--clusters 4 --pca 0", "--pca 0 must be between 1 and the dimension of the transfer (9 values per point)"},
      {"--clusters 4 --pca 10", "--pca 10 must be between 1 and the dimension of the transfer (9 values per point)"},
      {"--clusters 4 --pca 2 --iterations 0", "--iterations 0 must be at least 1"},
  };
  for (const auto& [arguments, message] : cases) {
    const test::RunResult r = test::run_prt("compress " + f.transfer_path + " " + arguments + " -o " + out);
    INFO(r.output);
    CHECK(r.exit_code == 1);
    CHECK(r.output == "prt: " + f.transfer_path + ": " + message + "\n");
  }
  const test::RunResult bake = test::run_prt("bake " + f.mesh_path + " --bands 3 --samples 8 -q --compress 4 -o " + out);
  CHECK(bake.exit_code == 1);
  CHECK(bake.output == "prt: --compress: expected K,N (clusters, PCA vectors), got '4'\n");
  write_file_atomically(f.dir + "/bad.cprt", "PRTCPCA");
  const test::RunResult shade = test::run_prt("shade " + f.mesh_path + " " + f.dir + "/bad.cprt --light " + f.light_path + " -o " + f.dir + "/x.ply");
  CHECK(shade.exit_code == 1);
  CHECK(contains(shade.output, "bad.cprt: "));
  CHECK(std::count(shade.output.begin(), shade.output.end(), '\n') == 1);
  CHECK(test::entries_in(f.dir) == before + 1);  // only bad.cprt was added
}

TEST_CASE("prt shade of an interreflected .cprt under a sun: the split shading with the compressed bounce-only part", "[compress][cli]") {
  const Fixture f = make_fixture("compress_cli_sun");
  const std::string prt_path = f.dir + "/inter.prt", cprt_path = f.dir + "/inter.cprt";
  REQUIRE(test::run_prt("bake " + f.mesh_path + " --transfer interreflected --bounces 1 --bands 3 --samples 64 -q -o " + prt_path).exit_code == 0);
  // A lighting file with a disc beside its SH sky: shading applies the bounce-only part to the disc's SH.
  light::LightFileInfo info;
  light::Disc sun;
  sun.direction = glm::normalize(glm::dvec3(0.3, 1.0, 0.2));
  sun.irradiance = glm::dvec3(4.0, 3.5, 3.0);
  sun.angular_radius = 0.02;
  info.discs = {sun};
  const std::string sun_light = f.dir + "/sun.json";
  light::write_light_file(sun_light, light::read_light_file(f.light_path), info);
  const test::RunResult c = test::run_prt("compress " + prt_path + " --clusters 12 --pca 3 --light " + sun_light + " -o " + cprt_path);
  INFO(c.output);
  REQUIRE(c.exit_code == 0);
  CHECK(contains(c.output, "(what the transfer shades: the sky's SH and the discs' bounce light)"));
  const compress::CompressedTransfer model = compress::read_cprt(cprt_path);
  REQUIRE(model.bounce);
  CHECK(contains(test::run_prt("info " + cprt_path).output, "with the bounce-only part"));

  const test::RunResult s = test::run_prt("shade " + f.mesh_path + " " + cprt_path + " --light " + sun_light + " -o " + f.dir + "/out.ply");
  INFO(s.output);
  REQUIRE(s.exit_code == 0);
  CHECK(!contains(s.output, "warning"));  // the discs' bounce light is there
  const mesh::Mesh mesh = mesh::load_mesh(f.mesh_path, nullptr, true);
  const light::SceneLighting lighting = light::load_scene_lighting(sun_light, 3, glm::dvec3(0.0), {}, {});
  REQUIRE(lighting.discs.size() == 1);
  transfer::TransferData approximate = compress::decompress(model);
  const std::vector<glm::vec3> expected = shade::shade_diffuse_split(mesh, approximate, lighting, "test");
  approximate.bounce_only.assign(approximate.bounce_only.size(), 0.0f);
  const std::vector<glm::vec3> without_bounce = shade::shade_diffuse_split(mesh, approximate, lighting, "test");
  const mesh::ColourPly shaded = mesh::read_ply_colours(f.dir + "/out.ply");
  REQUIRE(shaded.colours.size() == expected.size());
  double bounce = 0;
  for (std::size_t v = 0; v < expected.size(); ++v)
    for (int ch = 0; ch < 3; ++ch) {
      CHECK(shaded.colours[v][ch] == Approx(expected[v][ch]).margin(1e-5));
      bounce = std::max(bounce, static_cast<double>(std::abs(expected[v][ch] - without_bounce[v][ch])));
    }
  CHECK(bounce > 1e-3);  // the disc's bounce light is a visible part of the result
}
