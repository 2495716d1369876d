// The headline of the sun/sky split: per-vertex `prt shade` with its default options (sun auto, window
// auto) against the independent path tracer `prt reference` with the full environment and the same
// bounce count, on the bundled lion under three CC0 maps with a sun, one without (courtyard, overcast:
// 4% from a 6-band bake; 5 bands cannot hold its sky) and a studio lit by four soft boxes
// (docs/conventions.md, "Sun and sky"). Tolerance 4% rel_rms; the reference's own Monte Carlo noise at these path counts is
// about 1% rel_rms (it adds in quadrature). Also: no vertex has a negative channel, and on sunrise the
// split beats the unsplit lighting (--sun none --window none) by more than a factor of two.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "support/run_prt.h"

using namespace prt;

namespace {

const std::string kRoot = PRT_SOURCE_DIR;
const std::string kLion = kRoot + "/assets/meshes/guardian_lion_10k.ply";

double field(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(key + "=");
  REQUIRE(at != std::string::npos);
  return std::stod(text.substr(at + key.size() + 1));
}

// The smallest channel of a binary colour PLY written by prt shade (float x, y, z, red, green, blue).
float smallest_channel(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  const std::string bytes = s.str();
  const std::size_t body = bytes.find("end_header\n") + 11;
  const std::size_t vertices = static_cast<std::size_t>(std::stoull(bytes.substr(bytes.find("element vertex ") + 15)));
  float smallest = 1e30f;
  for (std::size_t v = 0; v < vertices; ++v)
    for (int c = 3; c < 6; ++c) {
      float x;
      std::memcpy(&x, bytes.data() + body + 24 * v + 4 * c, 4);
      smallest = std::min(smallest, x);
    }
  return smallest;
}

double shaded_error(const std::string& dir, const std::string& env, int spp, const std::string& options,
                    const std::string& transfer = "lion.prt", const std::string& reference_options = "--footprint vertex") {
  const std::string tag = env + (options.empty() ? "" : "_none") + "_" + transfer;
  const std::string map = kRoot + "/assets/env/" + env + ".exr";
  const std::string ref = dir + "/ref_" + env + (reference_options.find("area") == std::string::npos ? "" : "_area") + ".ply";
  if (!std::ifstream(ref))
    REQUIRE(test::run_prt("reference " + kLion + " --env " + map + " --bounces 3 --samples " + std::to_string(spp) + " " +
                          reference_options + " -q -o " + ref)
                .exit_code == 0);
  REQUIRE(test::run_prt("shade " + kLion + " " + dir + "/" + transfer + " --env " + map + " " + options + " -q -o " + dir + "/" + tag + ".ply")
              .exit_code == 0);
  if (options.empty()) CHECK(smallest_channel(dir + "/" + tag + ".ply") >= 0.0f);
  const test::RunResult cmp = test::run_prt("compare " + dir + "/" + tag + ".ply " + ref);
  REQUIRE(cmp.exit_code == 0);
  WARN(env << " " << options << ": " << cmp.output);
  return field(cmp.output, "rel_rms");
}

}  // namespace

TEST_CASE("default shading of the lion matches the path-traced truth within 4% under maps with and without a sun",
          "[sun][reference][slow]") {
  const std::string dir = test::fresh_temp_dir("sun_accuracy");
  REQUIRE(test::run_prt("bake " + kLion + " --transfer interreflected --bands 5 --samples 512 --bounces 3 --footprint vertex -q -o " + dir + "/lion.prt")
              .exit_code == 0);
  const double sunrise = shaded_error(dir, "sunrise", 1024, "");
  CHECK(sunrise <= 0.04);
  CHECK(sunrise < 0.5 * shaded_error(dir, "sunrise", 1024, "--sun none --window none"));
  CHECK(shaded_error(dir, "city", 512, "") <= 0.04);
  CHECK(shaded_error(dir, "sunset", 512, "") <= 0.04);
  CHECK(shaded_error(dir, "studio", 512, "") <= 0.04);     // four soft boxes, held out as four discs
  // No sun: nothing is held out, and the sky's own truncation is the error. At 5 bands it is 4.5% with
  // a 2048-path reference, all of it the band limit (shade is 1.0% from `prt reference --band-limit 5`,
  // the references' noise): no 5-band lighting reaches 4% on this detailed sky. The 4% holds from
  // 6 bands, the band count docs/conventions.md ("A sky without a compact source") gives for such skies.
  CHECK(shaded_error(dir, "courtyard", 512, "") <= 0.055);
  REQUIRE(test::run_prt("bake " + kLion + " --transfer interreflected --bands 6 --samples 512 --bounces 3 --footprint vertex -q -o " + dir + "/lion6.prt")
              .exit_code == 0);
  CHECK(shaded_error(dir, "courtyard", 512, "", "lion6.prt") <= 0.04);
}

TEST_CASE("an area-footprint bake of the lion, sun shaded exactly, matches the area-footprint truth within 4%", "[sun][reference][slow]") {
  // --footprint area on both sides: the sky and bounce terms from the bake, the sun's shadow rays in
  // prt shade from the same footprints (the file records it). Measured 2.4% (vertex footprint: 2.3%);
  // shading the sun from the vertices instead made it 8%.
  const std::string dir = test::fresh_temp_dir("sun_accuracy_area");
  REQUIRE(test::run_prt("bake " + kLion + " --transfer interreflected --bands 5 --samples 1024 --bounces 3 --footprint area -q -o " +
                        dir + "/lion_area.prt")
              .exit_code == 0);
  CHECK(shaded_error(dir, "sunrise", 1024, "", "lion_area.prt", "--footprint area") <= 0.04);
}
