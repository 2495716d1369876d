// Shader embedding and PRT_SHADER_DIR, and argument parsing (the image comparison of `prt compare` is
// tested in tests/reference/test_compare.cpp).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>

#include <unistd.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "camera/camera.h"
#include "render/headless_context.h"
#include "render/renderer.h"
#include "render/shader_program.h"

using namespace prt;
namespace fs = std::filesystem;

namespace {

// Sets PRT_SHADER_DIR for the scope of a test.
struct ShaderDirOverride {
  explicit ShaderDirOverride(const std::string& folder) { ::setenv("PRT_SHADER_DIR", folder.c_str(), 1); }
  ~ShaderDirOverride() { ::unsetenv("PRT_SHADER_DIR"); }
};

}  // namespace

TEST_CASE("every file in shaders/ is embedded verbatim and names its pass on the first line", "[render]") {
  ::unsetenv("PRT_SHADER_DIR");
  std::set<std::string> on_disk;
  for (const auto& entry : fs::directory_iterator(fs::path(PRT_SOURCE_DIR) / "shaders")) on_disk.insert(entry.path().filename().string());
  const std::vector<std::string> names = render::embedded_shader_names();
  CHECK(std::set<std::string>(names.begin(), names.end()) == on_disk);
  for (const std::string& name : names) {
    const render::ShaderSource source = render::shader_source(name);
    CHECK(source.origin == "shaders/" + name + " (embedded)");
    CHECK(source.text == read_file(std::string(PRT_SOURCE_DIR) + "/shaders/" + name));
    CHECK(source.text.rfind("// pass: ", 0) == 0);
    CHECK(source.text.substr(0, source.text.find('\n')).find("mirrors") != std::string::npos);
  }
}

TEST_CASE("PRT_SHADER_DIR replaces the embedded shaders and GLSL errors name the file in one line", "[render][gl]") {
  const fs::path folder = fs::temp_directory_path() / ("prt-shaders-test-" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  for (const std::string& name : render::embedded_shader_names())
    std::ofstream(folder / name, std::ios::binary) << render::shader_source(name).text;
  render::HeadlessContext context;
  {
    ShaderDirOverride override_dir(folder.string());
    CHECK(render::shader_source("surface.frag").origin == (folder / "surface.frag").string());
    CHECK_NOTHROW(render::Renderer());

    std::ofstream(folder / "background.frag", std::ios::app) << "\nvoid broken( {\n";
    try {
      render::Renderer renderer;
      FAIL("a broken shader compiled");
    } catch (const Error& e) {
      const std::string message = e.what();
      INFO(message);
      CHECK(message.rfind((folder / "background.frag").string() + ": GLSL compile error: ", 0) == 0);
      CHECK(message.find('\n') == std::string::npos);
    }
    fs::remove(folder / "background.frag");
    CHECK_THROWS_WITH(render::Renderer(), Catch::Contains((folder / "background.frag").string()));
  }
  fs::remove_all(folder);
}

TEST_CASE("camera, size and background arguments are parsed or refused with the option's name", "[render]") {
  const render::Camera a = render::parse_camera("30,-20.5,4");
  CHECK(a.azimuth_degrees == 30.0);
  CHECK(a.elevation_degrees == -20.5);
  CHECK(a.distance == 4.0);
  CHECK(render::parse_camera("auto").distance == 0.0);
  CHECK(render::parse_camera("10,5,auto").azimuth_degrees == 10.0);
  for (const char* bad : {"", "1,2", "1,2,3,4", "a,2,3", "0,90,3", "0,0,0", "0,0,-2", "0,0,nan", "0,0,inf"})
    CHECK_THROWS_WITH(render::parse_camera(bad), Catch::StartsWith("camera: "));
  int w = 0, h = 0;
  render::parse_size("640x480", w, h);
  CHECK(w == 640);
  CHECK(h == 480);
  for (const char* bad : {"640", "640x", "x480", "0x480", "640x0", "-1x5", "640x480x3", "99999x2", "64.5x48"})
    CHECK_THROWS_WITH(render::parse_size(bad, w, h), Catch::StartsWith("size: "));
  CHECK(render::parse_background("env") == render::Background::environment);
  CHECK(render::parse_background("sh") == render::Background::sh);
  CHECK(render::parse_background("black") == render::Background::black);
  CHECK_THROWS_WITH(render::parse_background("white"), Catch::StartsWith("background: "));
}
