// `prt info` on every kind of file prt writes: probe files (.prtprobes) and BRDF matrices (.bin, .json)
// besides transfer and lighting files; the numbers it prints are the files' own (bands, counts, spec).
#include <catch2/catch.hpp>

#include <fstream>
#include <string>

#include "support/run_prt.h"

using namespace prt;

TEST_CASE("prt info describes probe files and BRDF matrix files", "[probes][cli]") {
  const std::string dir = test::fresh_temp_dir("info_cli");
  {
    std::ofstream obj(dir + "/quad.obj");
    obj << "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nf 1 3 2\nf 1 4 3\n";
  }
  const test::RunResult baked = test::run_prt("probes " + dir + "/quad.obj --env " + std::string(PRT_SOURCE_DIR) +
                                              "/assets/env/city.exr --grid 2,1,3 --bounds -1,0,-1,1,1,1 --bands 2 --rays 64 --surface-samples 4 -q --format prt -o " +
                                              dir + "/p.prtprobes");
  INFO(baked.output);
  REQUIRE(baked.exit_code == 0);
  const test::RunResult probes = test::run_prt("info " + dir + "/p.prtprobes");
  INFO(probes.output);
  CHECK(probes.exit_code == 0);
  CHECK(probes.output.find("prt probe file") != std::string::npos);
  CHECK(probes.output.find("bands: 2 (4 coefficients)") != std::string::npos);
  CHECK(probes.output.find("probes: 6 (") != std::string::npos);
  CHECK(probes.output.find("layout: grid 2 x 1 x 3") != std::string::npos);

  for (const char* ext : {".bin", ".json"}) {
    const std::string file = dir + "/b" + ext;
    REQUIRE(test::run_prt("brdf phong:exponent=8,ks=0.5 --bands 3 -o " + file).exit_code == 0);
    const test::RunResult brdf = test::run_prt("info " + file);
    INFO(brdf.output);
    CHECK(brdf.exit_code == 0);
    CHECK(brdf.output.find("prt BRDF matrix") != std::string::npos);
    CHECK(brdf.output.find("brdf: phong:exponent=8,ks=0.5") != std::string::npos);
    CHECK(brdf.output.find("bands: 3 (9 x 9 per channel)") != std::string::npos);
  }
  // A damaged probe file is still a one-line error naming the file.
  {
    std::fstream f(dir + "/p.prtprobes", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(8);
    f.put('\x07');
  }
  const test::RunResult damaged = test::run_prt("info " + dir + "/p.prtprobes");
  CHECK(damaged.exit_code == 1);
  CHECK(damaged.output.rfind("prt: " + dir + "/p.prtprobes: ", 0) == 0);
}
