// Error statistics (src/image/compare.h) and `prt compare` on images and per-vertex PLYs: figures
// computed by hand, the one-line output, heatmaps, and one-line errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "image/compare.h"
#include "image/image.h"
#include "mesh/writers.h"
#include "support/run_prt.h"

using namespace prt;

namespace {

// A 4 x 2 RGB image with every value 2, and a copy with value (3, 1, 2) set to 3: one of 24 values off
// by 1, so rms = sqrt(1/24), rms of the reference = 2, max_abs = 1, max_rel = 1/2.
image::Image flat_image() {
  image::Image im(4, 2, 3);
  for (float& v : im.pixels) v = 2.0f;
  return im;
}
image::Image one_off_image() {
  image::Image im = flat_image();
  im.at(3, 1, 2) = 3.0f;
  return im;
}

// The value after "<name>=" in a compare line (at its start or after a space).
double field(const std::string& line, const std::string& name) {
  const std::string key = name + "=";
  std::size_t at = line.rfind(key, 0) == 0 ? 0 : line.find(" " + key);
  REQUIRE(at != std::string::npos);
  if (at > 0 || line[0] == ' ') ++at;
  return std::stod(line.substr(at + key.size()));
}

std::size_t line_count(const std::string& text) {
  std::size_t lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

}  // namespace

TEST_CASE("image::compare_images: rms, rel_rms, max_abs, max_rel and where", "[compare]") {
  const image::Image reference = flat_image();
  const image::ImageDifference same = image::compare_images(reference, reference);
  CHECK(same.values.rms == 0.0);
  CHECK(same.values.rel_rms == 0.0);
  CHECK(same.values.max_abs == 0.0);
  CHECK(same.values.max_rel == 0.0);
  CHECK(same.values.compared == 24);

  image::Image test = one_off_image();
  const image::ImageDifference d = image::compare_images(test, reference);
  CHECK(d.values.rms == Approx(std::sqrt(1.0 / 24.0)));
  CHECK(d.values.reference_rms == Approx(2.0));
  CHECK(d.values.rel_rms == Approx(std::sqrt(1.0 / 24.0) / 2.0));
  CHECK(d.values.max_abs == Approx(1.0));
  CHECK(d.values.max_rel == Approx(0.5));
  CHECK(d.max_abs_x == 3);
  CHECK(d.max_abs_y == 1);
  CHECK(d.max_rel_x == 3);
  CHECK(d.max_rel_y == 1);

  // Relative errors of values darker than 1% of the reference rms are taken against that 1%.
  CHECK(image::relative_error(0.01, 0.0, 2.0) == Approx(0.5));
  CHECK(image::relative_error(3.0, 2.0, 2.0) == Approx(0.5));
  CHECK(std::isnan(image::relative_error(std::nan(""), 2.0, 2.0)));

  test.at(0, 0, 0) = std::numeric_limits<float>::quiet_NaN();
  const image::ImageDifference with_nan = image::compare_images(test, reference);
  CHECK(with_nan.values.non_finite == 1);
  CHECK(with_nan.values.compared == 23);
  CHECK(with_nan.values.rms == Approx(std::sqrt(1.0 / 23.0)));

  // Heatmap: relative error over a 10% full scale; black at 0, white from 10% up, blue where not finite.
  const image::Image heat = image::relative_error_heatmap(test, reference, with_nan.values.reference_rms);
  CHECK(heat.at(3, 1, 0) == 1.0f);
  CHECK(heat.at(3, 1, 1) == 1.0f);
  CHECK(heat.at(3, 1, 2) == 1.0f);
  CHECK(heat.at(1, 0, 0) == 0.0f);
  CHECK(heat.at(1, 0, 1) == 0.0f);
  CHECK(heat.at(1, 0, 2) == 0.0f);
  CHECK(heat.at(0, 0, 0) == 0.0f);
  CHECK(heat.at(0, 0, 2) == 1.0f);
  // 5% relative error is half scale: red 1, green 0.5, blue 0.
  image::Image half = reference;
  half.at(2, 0, 1) = 2.1f;
  const image::Image heat_half = image::relative_error_heatmap(half, reference, 2.0);
  CHECK(heat_half.at(2, 0, 0) == Approx(1.0f));
  CHECK(heat_half.at(2, 0, 1) == Approx(0.5f).margin(1e-5));
  CHECK(heat_half.at(2, 0, 2) == 0.0f);

  CHECK_THROWS_WITH(image::compare_images(image::Image(4, 3, 3), reference, "a.exr", "b.exr"),
                    "a.exr: image is 4x3x3, b.exr is 4x2x3");
  // A reference that is all zeros makes any difference infinitely large relative to it.
  const image::Difference zero_reference = image::compare_values(reference.pixels.data(), image::Image(4, 2, 3).pixels.data(), 24);
  CHECK(std::isinf(zero_reference.rel_rms));
}

TEST_CASE("prt compare on images: one line of figures, a heatmap PNG, one-line errors", "[compare][cli]") {
  const std::string dir = test::fresh_temp_dir("compare_images");
  const std::string a = dir + "/a.exr", b = dir + "/b.exr";
  image::write(a, one_off_image());
  image::write(b, flat_image());

  const test::RunResult same = test::run_prt("compare " + b + " " + b);
  CHECK(same.exit_code == 0);
  CHECK(same.output == "rms=0 rel_rms=0 max_abs=0 max_rel=0 pixels=8\n");

  const test::RunResult known = test::run_prt("compare " + a + " " + b + " --heatmap " + dir + "/heat.png");
  INFO(known.output);
  REQUIRE(known.exit_code == 0);
  CHECK(line_count(known.output) == 1);
  CHECK(field(known.output, "rms") == Approx(std::sqrt(1.0 / 24.0)).epsilon(1e-5));
  CHECK(field(known.output, "rel_rms") == Approx(std::sqrt(1.0 / 24.0) / 2.0).epsilon(1e-5));
  CHECK(field(known.output, "max_abs") == 1.0);
  CHECK(field(known.output, "max_rel") == 0.5);
  CHECK(field(known.output, "pixels") == 8.0);
  const image::Image heat = image::read_rgb(dir + "/heat.png");
  REQUIRE(heat.width == 4);
  REQUIRE(heat.height == 2);
  CHECK(heat.at(3, 1, 0) == 1.0f);  // 50% error: white
  CHECK(heat.at(3, 1, 2) == 1.0f);
  CHECK(heat.at(0, 0, 0) == 0.0f);  // no error: black
  CHECK(heat.at(0, 0, 2) == 0.0f);

  // Any image prt reads (a PNG against itself here); non-finite values are reported when present.
  CHECK(test::run_prt("compare " + dir + "/heat.png " + dir + "/heat.png").output ==
        "rms=0 rel_rms=0 max_abs=0 max_rel=0 pixels=8\n");
  image::Image with_nan = flat_image();
  with_nan.at(1, 1, 1) = std::numeric_limits<float>::quiet_NaN();
  image::write(dir + "/nan.exr", with_nan);
  CHECK(test::run_prt("compare " + dir + "/nan.exr " + b).output ==
        "rms=0 rel_rms=0 max_abs=0 max_rel=0 pixels=8 non_finite=1\n");

  image::write(dir + "/small.exr", image::Image(4, 3, 3));
  mesh::write_ply(dir + "/mesh.ply", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}}, {0, 1, 2});
  const std::size_t before = test::entries_in(dir);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"compare " + dir + "/small.exr " + b, dir + "/small.exr: image is 4x3x3, " + b + " is 4x2x3"},
      {"compare " + dir + "/mesh.ply " + b, dir + "/mesh.ply is a per-vertex PLY but " + b + " is an image"},
      {"compare " + a + " " + dir + "/mesh.ply", dir + "/mesh.ply is a per-vertex PLY but " + a + " is an image"},
      {"compare " + a + " " + dir + "/missing.exr", dir + "/missing.exr"},
      {"compare " + a + " " + b + " --heatmap " + dir + "/heat.exr", dir + "/heat.exr: the heatmap of two images is"},
      {"compare " + a + " " + b + " --heatmap " + dir + "/no/such/heat.png", "heat.png"},
  };
  for (const auto& [arguments, needle] : cases) {
    const test::RunResult r = test::run_prt(arguments);
    INFO(arguments << "\n" << r.output);
    CHECK(r.exit_code == 1);
    CHECK(line_count(r.output) == 1);
    CHECK(r.output.rfind("prt: ", 0) == 0);
    CHECK(r.output.find(needle) != std::string::npos);
  }
  CHECK(test::entries_in(dir) == before);
}

TEST_CASE("prt compare on per-vertex PLYs: the same figures, the heatmap as a PLY", "[compare][cli]") {
  const std::string dir = test::fresh_temp_dir("compare_plys");
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  const std::vector<std::uint32_t> indices = {0, 1, 2, 1, 3, 2};
  // Reference all 1; the test has one value 1.2 and one 0.97: rms = sqrt((0.04 + 0.0009) / 12),
  // reference rms 1, max_abs 0.2, max_rel 0.2.
  const std::vector<glm::vec3> reference(4, glm::vec3(1.0f));
  std::vector<glm::vec3> test = reference;
  test[1].g = 1.2f;
  test[3].b = 0.97f;
  mesh::write_ply(dir + "/a.ply", positions, test, indices);
  mesh::write_ply(dir + "/b.ply", positions, reference, indices);
  const test::RunResult r = test::run_prt("compare " + dir + "/a.ply " + dir + "/b.ply --heatmap " + dir + "/heat.ply");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const double d1 = double(1.2f) - 1.0, d2 = double(0.97f) - 1.0;
  CHECK(field(r.output, "rms") == Approx(std::sqrt((d1 * d1 + d2 * d2) / 12.0)).epsilon(1e-5));
  CHECK(field(r.output, "rel_rms") == Approx(std::sqrt((d1 * d1 + d2 * d2) / 12.0)).epsilon(1e-5));
  CHECK(field(r.output, "max_abs") == Approx(0.2).epsilon(1e-5));
  CHECK(field(r.output, "max_rel") == Approx(0.2).epsilon(1e-5));
  CHECK(field(r.output, "vertices") == 4.0);
  const mesh::ColourPly heat = mesh::read_ply_colours(dir + "/heat.ply");
  REQUIRE(heat.colours.size() == 4);
  CHECK(heat.colours[0] == glm::vec3(0, 0, 1));  // 0: blue
  CHECK(heat.colours[1] == glm::vec3(1, 0, 0));  // >= 10%: red
  CHECK(test::run_prt("compare " + dir + "/a.ply " + dir + "/b.ply --heatmap " + dir + "/heat.png").exit_code == 1);
}
