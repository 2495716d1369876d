// `prt brdf`: files it writes (read back, equal to the library's projection), the preview, errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "brdf/brdf.h"
#include "brdf/brdf_file.h"
#include "brdf/projection.h"
#include "core/error.h"
#include "image/image.h"
#include "support/run_prt.h"

using namespace prt;

TEST_CASE("prt brdf writes B as .json and .bin that read back exactly", "[brdf][cli]") {
  const std::string dir = test::fresh_temp_dir("brdf_cli");
  const std::string spec = "ggx:roughness=0.4,f0=0.9/0.6/0.2,albedo=0.1";
  const test::RunResult json = test::run_prt("brdf " + spec + " --bands 4 -o " + dir + "/b.json --preview " + dir + "/lobe.png");
  INFO(json.output);
  REQUIRE(json.exit_code == 0);
  CHECK(json.output.find("reconstruction error") != std::string::npos);
  const test::RunResult bin = test::run_prt("brdf " + spec + " --bands 4 -q -o " + dir + "/b.bin");
  REQUIRE(bin.exit_code == 0);
  CHECK(bin.output.empty());

  const brdf::BrdfMatrix expected = brdf::project(brdf::parse_brdf(spec), 4);
  for (const std::string name : {"b.json", "b.bin"}) {
    const brdf::BrdfMatrix m = brdf::read_brdf_matrix(dir + "/" + name);
    CHECK(m.bands == 4);
    CHECK(m.channels == 3);
    CHECK(m.spec == brdf::to_spec(brdf::parse_brdf(spec)));
    REQUIRE(m.values.size() == expected.values.size());
    for (std::size_t i = 0; i < m.values.size(); ++i) REQUIRE(m.values[i] == expected.values[i]);
  }
  const image::Image preview = image::read_rgb(dir + "/lobe.png");
  CHECK(preview.width == 960);
  CHECK(preview.height == 540);
  // Something was drawn: not every pixel is white.
  int coloured = 0;
  for (float v : preview.pixels) coloured += v < 0.5f;
  CHECK(coloured > 1000);
}

TEST_CASE("prt brdf rejects bad input with one line and writes nothing", "[brdf][cli]") {
  const std::string dir = test::fresh_temp_dir("brdf_cli_errors");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"brdf velvet -o " + dir + "/b.json", "unknown BRDF 'velvet'"},
      {"brdf phong:exponent=-3 -o " + dir + "/b.json", "out of range"},
      {"brdf lambert --bands 40 -o " + dir + "/b.json", "--bands 40 is out of range"},
      {"brdf lambert -o " + dir + "/b.txt", "must be .json or .bin"},
      {"brdf lambert -o " + dir + "/b.json --preview " + dir + "/p.exr", "--preview must be a .png"},
      {"brdf lambert -o " + dir + "/no/such/dir/b.json", "no/such/dir"},
  };
  for (const auto& [arguments, expected] : cases) {
    const test::RunResult r = test::run_prt(arguments);
    INFO(arguments << "\n" << r.output);
    CHECK(r.exit_code == 1);
    CHECK(r.output.find(expected) != std::string::npos);
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
  }
  CHECK(test::entries_in(dir) == 0);
}

TEST_CASE("reading a damaged BRDF matrix names the problem", "[brdf]") {
  const std::string dir = test::fresh_temp_dir("brdf_read");
  brdf::BrdfMatrix m = brdf::project(brdf::parse_brdf("lambert"), 2);
  brdf::write_brdf_matrix(dir + "/m.bin", m);
  std::filesystem::resize_file(dir + "/m.bin", std::filesystem::file_size(dir + "/m.bin") - 8);
  try {
    brdf::read_brdf_matrix(dir + "/m.bin");
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("does not match the header") != std::string::npos);
  }
  CHECK_THROWS_AS(brdf::read_brdf_matrix(dir + "/missing.json"), Error);
}
