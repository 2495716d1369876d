// `prt light` through the real binary: outputs match the library, and every bad input gives one
// line "prt: <file or option>: <problem>", exit status 1, and no output file or temporary.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "image/image.h"
#include "light/environment.h"
#include "light/light_file.h"
#include "light/projection.h"
#include "light_test_util.h"
#include "sh/rotation.h"
#include "sh/window.h"

using namespace prt;

namespace {

struct RunResult {
  int status = -1;
  std::string out, err;
};

std::string read_all(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs `prt light <args>` in `dir`; stdout and stderr are captured outside it.
RunResult run_light(const test::TempDir& dir, const std::string& args) {
  static test::TempDir capture("cli_capture");
  const std::string prt = std::string(PRT_BINARY_DIR) + "/src/cli/prt";
  const std::string command = "cd '" + dir.path().string() + "' && '" + prt + "' light " + args + " > '" +
                              capture.file("out") + "' 2> '" + capture.file("err") + "'";
  const int raw = std::system(command.c_str());
  RunResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = read_all(capture.file("out"));
  r.err = read_all(capture.file("err"));
  return r;
}

// base + 0.1 c in channel c, plus `spot` in one texel.
void write_equirect(const std::string& path, int width, int height, float base, float spot = 50.0f) {
  image::Image im(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) im.at(x, y, c) = base + 0.1f * c + (x == width / 3 && y == height / 4 ? spot : 0.0f);
  image::write(path, im);
}

// A failing run: exit status 1, exactly `message` + newline on stderr, and the folder unchanged.
void check_failure(const test::TempDir& dir, const std::string& args, const std::string& message) {
  const auto before = dir.entries();
  const RunResult r = run_light(dir, args);
  INFO("prt light " << args);
  CHECK(r.status == 1);
  CHECK(r.err == "prt: " + message + "\n");
  CHECK(dir.entries() == before);
}

}  // namespace

TEST_CASE("prt light writes the library's projection, rotated and windowed as asked", "[cli]") {
  test::TempDir dir("cli_light");
  write_equirect(dir.file("sky.exr"), 64, 32, 0.5f);
  const auto expected = light::project(light::load_environment(dir.file("sky.exr")), 4);

  RunResult r = run_light(dir, "sky.exr --bands 4 -o plain.json");
  REQUIRE(r.status == 0);
  CHECK(r.err.empty());
  auto got = light::read_light_file(dir.file("plain.json"));
  REQUIRE(got.bands == 4);
  for (std::size_t i = 0; i < got.values.size(); ++i) CHECK(got.values[i] == expected.values[i]);

  // --rotate: R = Ry(yaw) Rx(pitch) Rz(roll) applied to the environment (a leading minus is fine).
  r = run_light(dir, "sky.exr --bands 4 --rotate -30,45,10 -o rotated.json --threads 1");
  REQUIRE(r.status == 0);
  const auto rotated =
      sh::Rotation(4, sh::rotation_from_yaw_pitch_roll(-30, 45, 10)).apply(expected);
  CHECK(test::max_difference(light::read_light_file(dir.file("rotated.json")), rotated) < 1e-12);
  CHECK(read_all(dir.file("rotated.json")).find("\"rotation_ypr_degrees\": [-30.0, 45.0, 10.0]") != std::string::npos);

  // --window: the library's weights, recorded with the parameter used.
  r = run_light(dir, "sky.exr --bands 4 --window hanning -o windowed.json");
  REQUIRE(r.status == 0);
  auto windowed = expected;
  sh::apply_window(sh::window_weights(sh::Window::hanning, 4), windowed);
  CHECK(test::max_difference(light::read_light_file(dir.file("windowed.json")), windowed) < 1e-15);
  CHECK(read_all(dir.file("windowed.json")).find("\"window\": \"hanning(5)\"") != std::string::npos);
}

TEST_CASE("prt light previews: linear EXR and tone-mapped PNG", "[cli]") {
  test::TempDir dir("cli_preview");
  write_equirect(dir.file("sky.exr"), 64, 32, 0.5f);
  RunResult r = run_light(dir, "sky.exr -o l.json --preview p.exr --preview-width 64");
  REQUIRE(r.status == 0);
  const auto c = light::read_light_file(dir.file("l.json"));
  const auto preview = image::read_rgb(dir.file("p.exr"));
  const auto expected = light::render_equirect(c, 64, 32);
  REQUIRE(preview.width == 64);
  REQUIRE(preview.height == 32);
  CHECK(preview.pixels == expected.pixels);

  // PNG: constant radiance 0.18, exposure 0 -> ACES (Narkowicz) -> sRGB -> 8 bits, default 512x256.
  write_equirect(dir.file("grey.exr"), 32, 16, 0.18f, 0.0f);
  r = run_light(dir, "grey.exr -o g.json --preview g.png");
  REQUIRE(r.status == 0);
  const auto png = image::read_rgb(dir.file("g.png"));  // read back linearised from sRGB
  REQUIRE(png.width == 512);
  REQUIRE(png.height == 256);
  const double grey = light::read_light_file(dir.file("g.json")).values[0].x / (2 * std::sqrt(3.14159265358979323846));
  const double aces = grey * (2.51 * grey + 0.03) / (grey * (2.43 * grey + 0.59) + 0.14);
  const double encoded = aces <= 0.0031308 ? 12.92 * aces : 1.055 * std::pow(aces, 1 / 2.4) - 0.055;
  const double byte = std::round(encoded * 255.0) / 255.0;
  const double linear_byte = byte <= 0.04045 ? byte / 12.92 : std::pow((byte + 0.055) / 1.055, 2.4);
  CHECK(png.at(256, 128, 0) == Approx(linear_byte).margin(0.003));
  // One stop more exposure is brighter.
  r = run_light(dir, "grey.exr -o g2.json --preview g2.png --exposure 1");
  REQUIRE(r.status == 0);
  CHECK(image::read_rgb(dir.file("g2.png")).at(256, 128, 0) > png.at(256, 128, 0) + 0.02);
}

TEST_CASE("prt light reports invalid pixels in one warning and goes on", "[cli]") {
  test::TempDir dir("cli_warning");
  image::Image im(16, 8, 3);
  for (float& p : im.pixels) p = 1.0f;
  im.at(1, 1, 0) = std::nanf("");
  im.at(2, 1, 1) = -2.0f;
  image::write(dir.file("bad.exr"), im);
  const RunResult r = run_light(dir, "bad.exr -o l.json");
  CHECK(r.status == 0);
  CHECK(r.err == "prt: warning: bad.exr: set 1 NaN, 0 Inf and 1 negative pixel values to 0\n");
  CHECK(std::filesystem::exists(dir.file("l.json")));
}

TEST_CASE("prt light: every bad input is one line, status 1, and leaves no file", "[cli]") {
  test::TempDir dir("cli_errors");
  write_equirect(dir.file("sky.exr"), 64, 32, 0.5f);
  image::write(dir.file("wide.exr"), image::Image(30, 20, 3));
  {
    std::ofstream(dir.file("text.exr")) << "not an image\n";
  }
  check_failure(dir, "missing.exr -o l.json", "missing.exr: file not found");
  check_failure(dir, "wide.exr -o l.json",
                "wide.exr: image is 30x20: expected an equirect map (2:1) or a cube cross (4N x 3N or 3N x 4N)");
  check_failure(dir, "a.exr,b.exr -o l.json",
                "a.exr,b.exr: expected six comma-separated cube faces (+X,-X,+Y,-Y,+Z,-Z), got 2");
  check_failure(dir, "sky.exr --bands 0 -o l.json", "--bands 0: out of range 1..32");
  check_failure(dir, "sky.exr --bands 33 -o l.json", "--bands 33: out of range 1..32");
  check_failure(dir, "sky.exr --rotate 1,2 -o l.json", "--rotate: expected YAW,PITCH,ROLL in degrees, got '1,2'");
  check_failure(dir, "sky.exr --rotate 90,x,0 -o l.json", "--rotate: expected YAW,PITCH,ROLL in degrees, got '90,x,0'");
  check_failure(dir, "sky.exr --window box -o l.json",
                "--window: unknown window 'box' (expected auto, none, hanning, lanczos or laplacian)");
  check_failure(dir, "sky.exr --window hanning --window-param=-1 -o l.json", "--window-param -1: must be a finite number > 0");
  check_failure(dir, "sky.exr -o nowhere/l.json", "nowhere/l.json: output folder does not exist");
  check_failure(dir, "sky.exr -o l.json --preview p.txt",
                "p.txt: unsupported preview format '.txt' (use .png, .jpg, .exr or .hdr)");
  check_failure(dir, "sky.exr -o l.json --preview p.png --preview-width 63", "--preview-width 63: must be even, 2..16384");
  // Unreadable input: the message starts with the file and OpenImageIO's reason follows.
  const auto before = dir.entries();
  const RunResult r = run_light(dir, "text.exr -o l.json --preview p.png");
  CHECK(r.status == 1);
  CHECK(r.err.rfind("prt: text.exr: cannot read as an image", 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(dir.entries() == before);
}
