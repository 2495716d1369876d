// Textured albedo through the real binary: `prt bake` then `prt shade` per vertex on a checker quad
// (OBJ + MTL map_Kd) under constant light equals the exact footprint averages of the checker; `prt info`
// names the albedo source; `--albedo` overrides the file's textures with a note.
#include <catch2/catch.hpp>

#include "mesh/writers.h"
#include "support/checker_quad.h"
#include "support/run_prt.h"

using namespace prt;

namespace {

bool contains(const std::string& haystack, const std::string& needle) { return haystack.find(needle) != std::string::npos; }

struct BakeAndShade {
  test::RunResult bake, info;
  mesh::ColourPly shaded;
};

// prt bake (unshadowed, 1 band, `options` added), prt info of the transfer, prt shade under white.json.
BakeAndShade bake_and_shade(const std::string& dir, const std::string& obj, const std::string& options) {
  BakeAndShade out;
  out.bake = test::run_prt("bake " + obj + " --transfer unshadowed --bands 1 " + options + " -o " + dir + "/t.prt");
  REQUIRE(out.bake.exit_code == 0);
  out.info = test::run_prt("info " + dir + "/t.prt");
  REQUIRE(test::run_prt("shade " + obj + " " + dir + "/t.prt --light " + dir + "/white.json -o " + dir + "/s.ply").exit_code == 0);
  out.shaded = mesh::read_ply_colours(dir + "/s.ply");
  REQUIRE(out.shaded.colours.size() == 4);
  return out;
}

}  // namespace

TEST_CASE("prt shade per vertex on a textured checker quad equals the footprint average", "[bake][cli][albedo]") {
  const std::string dir = test::fresh_temp_dir("albedo_checker");
  glm::dvec3 a, b;
  const std::string obj = test::write_checker_quad(dir, &a, &b);
  const BakeAndShade run = bake_and_shade(dir, obj, "-q");
  CHECK(contains(run.info.output, R"("albedo":"mesh","albedo_source":"texture")"));
  const mesh::ColourPly& shaded = run.shaded;
  // vt = (x, y) is v up: image row py sits at y = 1 - py / 64, so the quad's squares [0, 1/2]^2 and
  // [1/2, 1]^2 (the diagonal squares) show kB. Under constant radiance 1 an unshadowed vertex reflects
  // its albedo. The exact hat-weighted footprint averages (derived in tests/mesh/test_texture.cpp), D
  // the diagonal squares' colour and O the others': (5 D + 3 O) / 8 at (0,0) and (1,1), (D + 3 O) / 4
  // at (1,0) and (0,1).
  const glm::dvec3 want[4] = {(5.0 * b + 3.0 * a) / 8.0, (b + 3.0 * a) / 4.0, (5.0 * b + 3.0 * a) / 8.0, (b + 3.0 * a) / 4.0};
  for (int v = 0; v < 4; ++v)
    for (int c = 0; c < 3; ++c) CHECK(double(shaded.colours[v][c]) == Approx(want[v][c]).epsilon(0.01));
}

TEST_CASE("prt bake --albedo overrides the file's textures with a note, and prt info says so", "[bake][cli][albedo]") {
  const std::string dir = test::fresh_temp_dir("albedo_override");
  glm::dvec3 a, b;
  const std::string obj = test::write_checker_quad(dir, &a, &b);
  const BakeAndShade run = bake_and_shade(dir, obj, "--albedo 0.5,0.25,1");
  CHECK(contains(run.bake.output, obj + ": --albedo 0.5,0.25,1 overrides the file's texture albedo"));
  CHECK(contains(run.info.output, R"("albedo":[0.5,0.25,1.0],"albedo_source":"option")"));
  const mesh::ColourPly& shaded = run.shaded;
  for (int v = 0; v < 4; ++v) {
    CHECK(shaded.colours[v][0] == Approx(0.5).epsilon(1e-5));
    CHECK(shaded.colours[v][1] == Approx(0.25).epsilon(1e-5));
    CHECK(shaded.colours[v][2] == Approx(1.0).epsilon(1e-5));
  }
}
