// Image files through OpenImageIO: exact float round trips, 8-bit quantisation and sRGB, channel
// handling, the display tone maps, and failures that name the file and leave nothing behind.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include "core/error.h"
#include "image/image.h"
#include "light_test_util.h"

using namespace prt;

namespace {

double srgb_encode(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055; }
double srgb_decode(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

}  // namespace

TEST_CASE("EXR round trips are bit exact, including NaN, Inf and negatives", "[image]") {
  test::TempDir dir("image_exr");
  image::Image im(7, 5, 3);
  for (std::size_t i = 0; i < im.pixels.size(); ++i) im.pixels[i] = static_cast<float>(std::sin(0.37 * i) * 1e3);
  im.pixels[3] = std::nanf("");
  im.pixels[4] = -INFINITY;
  im.pixels[5] = 1e-40f;  // denormal
  image::write(dir.file("a.exr"), im);
  const auto back = image::read_rgb(dir.file("a.exr"));
  REQUIRE(back.width == 7);
  REQUIRE(back.height == 5);
  REQUIRE(back.channels == 3);
  CHECK(std::isnan(back.pixels[3]));
  for (std::size_t i = 0; i < im.pixels.size(); ++i)
    if (i != 3) CHECK(back.pixels[i] == im.pixels[i]);
  CHECK(dir.entries() == std::vector<std::string>{"a.exr"});  // no temporary left
}

TEST_CASE("Radiance .hdr files keep values to RGBE precision", "[image]") {
  test::TempDir dir("image_hdr");
  image::Image im(8, 4, 3);
  for (std::size_t i = 0; i < im.pixels.size(); ++i) im.pixels[i] = static_cast<float>(0.01 * std::exp(0.3 * (i % 40)));
  image::write(dir.file("a.hdr"), im);
  const auto back = image::read_rgb(dir.file("a.hdr"));
  REQUIRE(back.width == 8);
  // RGBE shares one exponent per pixel: each channel is within 1/256 of the pixel's largest.
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      const float largest = std::fmax(im.at(x, y, 0), std::fmax(im.at(x, y, 1), im.at(x, y, 2)));
      for (int c = 0; c < 3; ++c) CHECK(std::fabs(back.at(x, y, c) - im.at(x, y, c)) <= largest / 128.0f);
    }
}

TEST_CASE("8-bit files are display values: quantised with rounding, read back linearised", "[image]") {
  test::TempDir dir("image_png");
  image::Image im(4, 1, 3);
  const float values[4] = {0.0f, 0.5f, 1.0f, 2.0f};
  for (int x = 0; x < 4; ++x)
    for (int c = 0; c < 3; ++c) im.at(x, 0, c) = values[x];
  image::write(dir.file("a.png"), im);
  const auto back = image::read_rgb(dir.file("a.png"));
  CHECK(back.at(0, 0, 0) == 0.0f);
  CHECK(back.at(1, 0, 0) == Approx(srgb_decode(128.0 / 255.0)).margin(1e-6));  // 0.5 * 255 = 127.5 rounds up
  CHECK(back.at(2, 0, 1) == Approx(1.0).margin(1e-6));
  CHECK(back.at(3, 0, 2) == Approx(1.0).margin(1e-6));  // clamped
  CHECK(image::is_display_format("x.PNG"));
  CHECK(image::is_display_format("x.jpeg"));
  CHECK_FALSE(image::is_display_format("x.exr"));
  CHECK_FALSE(image::is_display_format("x.hdr"));
}

TEST_CASE("grey images become RGB, alpha is dropped", "[image]") {
  test::TempDir dir("image_channels");
  image::Image grey(3, 2, 1), rgba(3, 2, 4);
  for (std::size_t i = 0; i < grey.pixels.size(); ++i) grey.pixels[i] = 0.25f * i;
  for (std::size_t i = 0; i < rgba.pixels.size(); ++i) rgba.pixels[i] = 1.0f + i;
  image::write(dir.file("g.exr"), grey);
  image::write(dir.file("rgba.exr"), rgba);
  const auto g = image::read_rgb(dir.file("g.exr"));
  REQUIRE(g.channels == 3);
  for (int c = 0; c < 3; ++c) CHECK(g.at(2, 1, c) == 0.25f * 5);
  const auto a = image::read_rgb(dir.file("rgba.exr"));
  REQUIRE(a.channels == 3);
  CHECK(a.at(1, 0, 0) == 5.0f);
  CHECK(a.at(1, 0, 2) == 7.0f);
}

TEST_CASE("to_display: exposure, tone map, sRGB", "[image]") {
  image::Image im(4, 1, 1);
  im.pixels = {0.18f, 4.0f, -1.0f, std::nanf("")};
  const auto clamp = image::to_display(im, 1.0, image::ToneMap::clamp);
  CHECK(clamp.pixels[0] == Approx(srgb_encode(0.36)).margin(1e-6));
  CHECK(clamp.pixels[1] == 1.0f);
  CHECK(clamp.pixels[2] == 0.0f);
  CHECK(clamp.pixels[3] == 0.0f);
  const auto aces = image::to_display(im, 0.0, image::ToneMap::aces);
  const double x = 0.18, mapped = x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
  CHECK(aces.pixels[0] == Approx(srgb_encode(mapped)).margin(1e-6));
  const double y = 4.0, mapped_y = y * (2.51 * y + 0.03) / (y * (2.43 * y + 0.59) + 0.14);  // 0.973: below white
  CHECK(aces.pixels[1] == Approx(srgb_encode(mapped_y)).margin(1e-6));
  CHECK(aces.pixels[2] == 0.0f);
}

TEST_CASE("image errors name the file and leave nothing behind", "[image]") {
  test::TempDir dir("image_errors");
  CHECK_THROWS_WITH(image::read_rgb(dir.file("none.exr")), dir.file("none.exr") + ": file not found");
  CHECK_THROWS_WITH(image::read_rgb(dir.path().string()), dir.path().string() + ": is a folder, not an image");
  {
    std::ofstream(dir.file("junk.png")) << "junk";
  }
  CHECK_THROWS_WITH(image::read_rgb(dir.file("junk.png")), Catch::StartsWith(dir.file("junk.png") + ": cannot read"));
  const auto before = dir.entries();
  CHECK_THROWS_WITH(image::write(dir.file("out.unknownext"), image::Image(2, 2, 3)),
                    Catch::StartsWith(dir.file("out.unknownext") + ": unsupported image format"));
  CHECK_THROWS_WITH(image::write(dir.file("missing/out.exr"), image::Image(2, 2, 3)),
                    dir.file("missing/out.exr") + ": output folder does not exist");
  CHECK_THROWS_WITH(image::write(dir.file("empty.exr"), image::Image()), Catch::Contains("empty"));
  CHECK(dir.entries() == before);
}
