// SH lighting files: exact round trips, the documented keys, and one-line errors for bad files.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <limits>

#include "core/atomic_file.h"
#include "core/error.h"
#include "light/light_file.h"
#include "light_test_util.h"
#include "sh/basis.h"

using namespace prt;

namespace {

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

std::string header(int bands) {
  return "{\"bands\": " + std::to_string(bands) +
         ", \"basis\": \"real-orthonormal-condon-shortley\", \"index\": \"l*(l+1)+m\", \"frame\": \"right-handed, +Y up\", ";
}

}  // namespace

TEST_CASE("light files round-trip every coefficient bit for bit", "[light_file]") {
  test::TempDir dir("light_file");
  for (int bands : {1, 3, 9, sh::kMaxBands}) {
    auto c = test::random_coefficients(bands, 40 + bands);
    c.values.back() = glm::dvec3(1e-300, -123456.789012345678, 0.1);  // extremes and inexact decimals
    light::LightFileInfo info;
    info.source = "some \"quoted\" name\\with backslash.exr";
    info.window = "hanning(4)";
    info.yaw = 90;
    info.pitch = -12.5;
    info.roll = 0.125;
    const std::string path = dir.file("light.json");
    light::write_light_file(path, c, info);
    const auto back = light::read_light_file(path);
    REQUIRE(back.bands == bands);
    for (std::size_t i = 0; i < c.values.size(); ++i) CHECK(back.values[i] == c.values[i]);
  }
}

TEST_CASE("light files carry the documented keys in order", "[light_file]") {
  sh::RgbCoefficients c(2);
  c.values[0] = glm::dvec3(0.5, 1.0, 0.0);
  light::LightFileInfo info;
  info.source = "sky.exr";
  const std::string text = light::format_light_file(c, info);
  const char* keys[] = {"\"bands\": 2", "\"basis\": \"real-orthonormal-condon-shortley\"", "\"index\": \"l*(l+1)+m\"",
                        "\"frame\": \"right-handed, +Y up\"", "\"quantity\": \"radiance\"", "\"source\": \"sky.exr\"",
                        "\"window\": \"none\"", "\"rotation_ypr_degrees\": [0.0, 0.0, 0.0]", "\"coefficients\": ["};
  std::size_t at = 0;
  for (const char* key : keys) {
    INFO(key);
    const std::size_t found = text.find(key, at);
    REQUIRE(found != std::string::npos);
    at = found;
  }
  CHECK(text.find("[0.5, 1.0, 0.0]") != std::string::npos);
  // One coefficient triple per line: 4 lines for 2 bands.
  CHECK(std::count(text.begin(), text.end(), '\n') == 10 + 4 + 2);
}

TEST_CASE("reading a bad light file names it and the problem", "[light_file]") {
  test::TempDir dir("light_file_bad");
  const std::string path = dir.file("bad.json");
  auto check_error = [&](const std::string& text, const std::string& problem) {
    write_text(path, text);
    INFO(text);
    CHECK_THROWS_WITH(light::read_light_file(path), Catch::StartsWith(path + ": " + problem));
  };
  const std::string one = "\"coefficients\": [[1, 2, 3]]}";
  CHECK_THROWS_WITH(light::read_light_file(dir.file("none.json")), Catch::StartsWith(dir.file("none.json") + ": cannot open"));
  check_error("{\"bands\": 1,", "not valid JSON");
  check_error("[1, 2]", "not an SH lighting file");
  check_error("{\"basis\": \"x\"}", "missing key \"bands\"");
  check_error(header(0) + "\"coefficients\": []}", "\"bands\" is 0, out of range 1..32");
  check_error(header(33) + "\"coefficients\": []}", "\"bands\" is 33, out of range 1..32");
  check_error("{\"bands\": 2.5}", "\"bands\" must be an integer");
  check_error("{\"bands\": 1, \"basis\": \"real-orthonormal\", \"index\": \"l*(l+1)+m\", \"frame\": \"right-handed, +Y up\", " + one,
              "\"basis\" is \"real-orthonormal\", expected \"real-orthonormal-condon-shortley\"");
  check_error("{\"bands\": 1, \"basis\": \"real-orthonormal-condon-shortley\", \"index\": \"l^2+l+m\", \"frame\": \"right-handed, +Y up\", " + one,
              "\"index\" is");
  check_error("{\"bands\": 1, \"basis\": \"real-orthonormal-condon-shortley\", \"index\": \"l*(l+1)+m\", \"frame\": \"left-handed\", " + one,
              "\"frame\" is");
  check_error("{\"bands\": 1, \"basis\": \"real-orthonormal-condon-shortley\", \"index\": \"l*(l+1)+m\", \"frame\": \"right-handed, +Y up\"}",
              "missing key \"coefficients\"");
  check_error(header(1) + "\"quantity\": \"irradiance\", " + one, "\"quantity\" is \"irradiance\", expected \"radiance\"");
  check_error(header(2) + one, "\"coefficients\" must be an array of 4 [r, g, b] triples for 2 bands, got 1");
  check_error(header(1) + "\"coefficients\": [[1, 2]]}", "coefficient 0 is not an [r, g, b] triple");
  check_error(header(1) + "\"coefficients\": [[1, \"2\", 3]]}", "coefficient 0 has a non-numeric entry");
  // Every message is one line.
  write_text(path, "{\n\"bands\": \n");
  try {
    light::read_light_file(path);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find('\n') == std::string::npos);
  }
  // A hand-written minimal file is accepted.
  write_text(path, header(1) + one);
  CHECK(light::read_light_file(path).values[0] == glm::dvec3(1, 2, 3));
}

TEST_CASE("writing refuses non-finite or inconsistent sets and leaves nothing behind", "[light_file]") {
  test::TempDir dir("light_file_write");
  sh::RgbCoefficients c(2);
  c.values[1].y = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(light::write_light_file(dir.file("x.json"), c, {}), Catch::Contains("x.json: SH coefficient 1 is not finite"));
  c.values.pop_back();
  CHECK_THROWS_WITH(light::write_light_file(dir.file("x.json"), c, {}), Catch::Contains("inconsistent"));
  CHECK(dir.entries().empty());
}
