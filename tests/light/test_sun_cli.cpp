// The sun/sky split through the real binary: `--sun none --window none` reproduces the files of the
// version before the split bit for bit (golden files in tests/data, written by that version, see
// tests/data/README.md), lighting files carry the discs, and bad --sun values are one-line errors.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "light/light_file.h"
#include "light_test_util.h"
#include "support/run_prt.h"

using namespace prt;
namespace fs = std::filesystem;

namespace {

const std::string kData = std::string(PRT_SOURCE_DIR) + "/tests/data/";
const std::string kSunrise = std::string(PRT_SOURCE_DIR) + "/assets/env/sunrise.exr";

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool contains(const std::string& haystack, const std::string& needle) { return haystack.find(needle) != std::string::npos; }

}  // namespace

TEST_CASE("sun none and window none reproduce the pre-split light, bake and shade files bit for bit", "[light][sun][cli]") {
  test::TempDir dir("sun_golden");
  fs::copy_file(kSunrise, dir.file("sunrise.exr"));
  // prt light records its input as given: run it from the folder, as the golden file was made.
  const std::string light = "cd " + dir.path().string() + " && " + test::prt_binary() +
                            " light sunrise.exr --bands 5 --sun none --window none -o light.json > /dev/null 2>&1";
  REQUIRE(std::system(light.c_str()) == 0);
  CHECK(bytes_of(dir.file("light.json")) == bytes_of(kData + "golden_light_sunrise_b5.json"));

  const std::string mesh = kData + "sphere_on_floor.ply";
  REQUIRE(test::run_prt("bake " + mesh + " --transfer shadowed --bands 4 --samples 64 --footprint vertex -q -o " + dir.file("s.prt")).exit_code == 0);
  CHECK(bytes_of(dir.file("s.prt")) == bytes_of(kData + "golden_shadowed_b4_s64.prt"));
  REQUIRE(test::run_prt("bake " + mesh + " --transfer interreflected --bands 4 --samples 64 --bounces 2 --footprint vertex -q -o " + dir.file("i.prt")).exit_code == 0);
  REQUIRE(test::run_prt("shade " + mesh + " " + dir.file("i.prt") + " --env " + kSunrise +
                        " --rotate 270,0,0 --sun none --window none -o " + dir.file("i.ply")).exit_code == 0);
  CHECK(bytes_of(dir.file("i.ply")) == bytes_of(kData + "golden_shade_interreflected.ply"));
  REQUIRE(test::run_prt("shade " + mesh + " " + dir.file("s.prt") + " --light " + kData +
                        "golden_light_sunrise_b5.json --sun none --window none -o " + dir.file("s.ply")).exit_code == 0);
  CHECK(bytes_of(dir.file("s.ply")) == bytes_of(kData + "golden_shade_shadowed_json.ply"));

  // The defaults (sun auto, window auto) do change the result on this sunny map.
  REQUIRE(test::run_prt("shade " + mesh + " " + dir.file("i.prt") + " --env " + kSunrise + " --rotate 270,0,0 -q -o " +
                        dir.file("d.ply")).exit_code == 0);
  CHECK(bytes_of(dir.file("d.ply")) != bytes_of(kData + "golden_shade_interreflected.ply"));
}

TEST_CASE("prt light reports and stores the sun, and shading from the file equals shading from the map", "[light][sun][cli]") {
  test::TempDir dir("sun_file");
  const test::RunResult r = test::run_prt("light " + kSunrise + " --bands 5 -o " + dir.file("l.json"));
  REQUIRE(r.exit_code == 0);
  CHECK(contains(r.output, "sun: 1 disc"));
  // The auto window windows nothing (light/deringing.h: the shading clamps instead) ...
  CHECK(contains(r.output, "window none"));
  const light::LightFile file = light::read_lighting_file(dir.file("l.json"));
  REQUIRE(file.discs.size() == 1);
  CHECK(file.window == "none");
  // ... even with the sun left in the SH, where it rings into negative irradiance (issue 36).
  const test::RunResult in_sh = test::run_prt("light " + kSunrise + " --bands 5 --sun none -o " + dir.file("n.json"));
  REQUIRE(in_sh.exit_code == 0);
  CHECK(!contains(in_sh.output, "laplacian"));
  CHECK(light::read_lighting_file(dir.file("n.json")).window == "none");
  // The bundled sunrise: the sun is low (about 8 degrees up) toward +X+Z.
  CHECK(file.discs[0].direction.y == Approx(0.14).margin(0.03));

  const std::string mesh = kData + "sphere_on_floor.ply";
  REQUIRE(test::run_prt("bake " + mesh + " --transfer interreflected --bands 5 --samples 64 --bounces 1 -q -o " + dir.file("i.prt")).exit_code == 0);
  REQUIRE(test::run_prt("shade " + mesh + " " + dir.file("i.prt") + " --env " + kSunrise + " -q -o " + dir.file("env.ply")).exit_code == 0);
  REQUIRE(test::run_prt("shade " + mesh + " " + dir.file("i.prt") + " --light " + dir.file("l.json") + " -q -o " + dir.file("json.ply")).exit_code == 0);
  const test::RunResult cmp = test::run_prt("compare " + dir.file("env.ply") + " " + dir.file("json.ply"));
  REQUIRE(cmp.exit_code == 0);
  INFO(cmp.output);
  // The file stores 17 significant digits and the window is applied once either way.
  const std::size_t at = cmp.output.find("max_rel=");
  REQUIRE(at != std::string::npos);
  CHECK(std::stod(cmp.output.substr(at + 8)) < 1e-6);
}

TEST_CASE("malformed sun values are one-line errors and leave no file", "[light][sun][cli]") {
  test::TempDir dir("sun_bad");
  const char* bad[] = {"1,2", "0,1,0,1,1,1", "0,1,0,1,1,1,0", "0,1,0,1,1,1,-2", "0,1,0,-1,1,1,0.5", "0,1,0,0,0,0,0.5",
                       "0,0,0,1,1,1,0.5", "0,1,0,1,1,1,50", "0,1,0,1,nan,1,0.5", "sunny"};
  for (const char* value : bad) {
    INFO(value);
    const test::RunResult r = test::run_prt(std::string("light ") + kSunrise + " --sun " + value + " -o " + dir.file("x.json"));
    CHECK(r.exit_code == 1);
    CHECK(contains(r.output, "--sun: "));
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') <= 2);  // the repair warning, then the error
    CHECK(dir.entries().empty());
  }
  const test::RunResult window = test::run_prt(std::string("light ") + kSunrise + " --window gauss -o " + dir.file("x.json"));
  CHECK(window.exit_code == 1);
  CHECK(contains(window.output, "--window: unknown window 'gauss'"));
}
