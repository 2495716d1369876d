// `prt probes --sun auto` (the default): the map's sun becomes the probes' disc (traced with
// visibility) and leaves the sky; the split conserves the light, so the sky probe (environment plus sun,
// unoccluded, projected exactly) is the same as with the whole map (--sun none).
#include <catch2/catch.hpp>

#include <cmath>

#include "probes/probe_file.h"
#include "support/run_prt.h"

using namespace prt;

TEST_CASE("probes hold the map's sun out as a disc and keep the sky probe's light", "[probes][sun][cli]") {
  const std::string dir = test::fresh_temp_dir("probe_sun");
  const std::string mesh = std::string(PRT_SOURCE_DIR) + "/tests/data/sphere_on_floor.ply";
  const std::string env = std::string(PRT_SOURCE_DIR) + "/assets/env/sunrise.exr";
  const std::string common = "probes " + mesh + " --env " + env + " --grid 2,2,2 --format prt --rays 64 --bands 3 --surface-samples 16 ";
  const test::RunResult automatic = test::run_prt(common + "-o " + dir + "/auto.prtprobes");
  REQUIRE(automatic.exit_code == 0);
  CHECK(automatic.output.find("sun found in") != std::string::npos);
  REQUIRE(test::run_prt(common + "--sun none -q -o " + dir + "/none.prtprobes").exit_code == 0);
  const probes::ProbeSet a = probes::read_probe_file(dir + "/auto.prtprobes");
  const probes::ProbeSet n = probes::read_probe_file(dir + "/none.prtprobes");
  REQUIRE(a.sky.values.size() == n.sky.values.size());
  const double scale = n.sky.values[0].y;
  for (std::size_t i = 0; i < n.sky.values.size(); ++i)
    for (int c = 0; c < 3; ++c) CHECK(std::abs(a.sky.values[i][c] - n.sky.values[i][c]) <= 0.01 * scale);
}
