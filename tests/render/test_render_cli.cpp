// `prt render` end to end: outputs, determinism, the quarter-turn identity through files, and one-line
// errors without output files for bad inputs. Runs the built `prt` binary.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include "core/atomic_file.h"
#include "image/image.h"
#include "render/headless_render.h"
#include "render/headless_context.h"
#include "render/renderer.h"
#include "render/scene_inputs.h"
#include "render_fixtures.h"

using namespace prt;
namespace fs = std::filesystem;

namespace {

const std::string kPrt = std::string(PRT_BINARY_DIR) + "/src/cli/prt";

// A fresh folder with the fixture files, removed at the end of the test case.
struct Fixtures {
  fs::path folder;
  Fixtures() {
    folder = fs::temp_directory_path() / ("prt-render-test-" + std::to_string(::getpid()));
    fs::remove_all(folder);
    fs::create_directories(folder);
    render_test::write_fixture_files(folder.string());
  }
  ~Fixtures() { fs::remove_all(folder); }
  std::string operator/(const std::string& name) const { return (folder / name).string(); }
};

struct Run {
  int status = -1;
  std::string err;
};

// Runs `prt render <arguments>` through the shell with stderr captured; `environment` is prefixed (VAR=value).
Run run_prt(const Fixtures& f, const std::string& arguments, const std::string& environment = "") {
  const std::string err_path = f / "stderr.txt";
  const std::string command = environment + (environment.empty() ? "" : " ") + kPrt + " render " + arguments + " 2> " + err_path;
  const int raw = std::system(command.c_str());
  Run r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.err = read_file(err_path);
  return r;
}

std::size_t line_count(const std::string& text) {
  std::size_t lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

}  // namespace

TEST_CASE("prt render writes PNG and EXR, byte-identical across runs", "[render][gl][cli]") {
  Fixtures f;
  const std::string common = f / "mesh.ply" + " " + f / "transfer.prt" + " --env " + f / "env.exr" +
                             " --size 80x60 --camera 30,20,auto --rotate 20,10,0 --object-rotate 0,15,0 -q";
  for (const std::string& extension : {std::string(".png"), std::string(".exr")}) {
    const Run first = run_prt(f, common + " -o " + f / ("a" + extension));
    INFO(first.err);
    REQUIRE(first.status == 0);
    REQUIRE(run_prt(f, common + " -o " + f / ("b" + extension)).status == 0);
    const bool same_bytes = read_file(f / ("a" + extension)) == read_file(f / ("b" + extension));
    const image::Image a = image::read_rgb(f / ("a" + extension)), b = image::read_rgb(f / ("b" + extension));
    CHECK(a.width == 80);
    CHECK(a.height == 60);
    CHECK(a.pixels == b.pixels);
    // image::write clears OpenImageIO's "DateTime" stamp, so EXR headers are identical too.
    CHECK(same_bytes);
  }
}

TEST_CASE("the EXR from prt render holds exactly the renderer's float radiance", "[render][gl][cli]") {
  Fixtures f;
  REQUIRE(run_prt(f, f / "mesh.ply" + " " + f / "transfer.prt" + " --env " + f / "env.exr" +
                         " --size 64x48 --background sh -q -o " + f / "out.exr")
              .status == 0);
  const image::Image from_file = image::read_rgb(f / "out.exr");
  // An SH lighting file works too (default background: its SH reconstruction).
  const Run json = run_prt(f, f / "mesh.ply" + " " + f / "transfer_grey.prt" + " --env " + f / "light.json" +
                                  " --size 40x30 -q -o " + f / "json.exr");
  INFO(json.err);
  CHECK(json.status == 0);
  CHECK(fs::exists(f / "json.exr"));

  const render::SceneInputs scene = render::load_scene(f / "mesh.ply", {f / "transfer.prt"});
  const render::Lighting lighting = render::load_render_lighting(f / "env.exr", 5);
  render::HeadlessContext context;
  render::Renderer renderer;
  renderer.set_mesh(scene.mesh);
  renderer.add_transfer(scene.transfers[0], "transfer");
  renderer.set_lighting(lighting.coefficients, &lighting.equirect);
  render::FrameSettings settings;
  settings.background = render::Background::sh;
  renderer.render(settings, 64, 48);
  CHECK(renderer.read_radiance().pixels == from_file.pixels);
}

TEST_CASE("prt render --rotate 90,0,0 equals the environment file shifted left by a quarter width", "[render][gl][cli]") {
  Fixtures f;
  const image::Image original = image::read_rgb(f / "env.exr");
  image::Image shifted(original.width, original.height, 3);
  for (int y = 0; y < original.height; ++y)
    for (int x = 0; x < original.width; ++x)
      for (int c = 0; c < 3; ++c) shifted.at(x, y, c) = original.at((x + original.width / 4) % original.width, y, c);
  image::write(f / "env_shifted.exr", shifted);
  const std::string common = f / "mesh.ply" + " " + f / "transfer.prt" + " --size 64x48 --background black -q";
  REQUIRE(run_prt(f, common + " --env " + f / "env.exr" + " --rotate 90,0,0 -o " + f / "rotated.exr").status == 0);
  REQUIRE(run_prt(f, common + " --env " + f / "env_shifted.exr" + " -o " + f / "shifted.exr").status == 0);
  const image::Image a = image::read_rgb(f / "rotated.exr"), b = image::read_rgb(f / "shifted.exr");
  double worst = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    worst = std::max(worst, double(std::fabs(a.pixels[i] - b.pixels[i])));
    largest = std::max(largest, double(b.pixels[i]));
  }
  CHECK(largest > 0.1);
  CHECK(worst / largest < 1e-5);
}

TEST_CASE("bad inputs to prt render give one-line errors, a non-zero exit and no output", "[render][gl][cli]") {
  Fixtures f;
  const std::string mesh = f / "mesh.ply", transfer = f / "transfer.prt", env = f / "env.exr";
  const std::string out = f / "out.png";

  // A copy of the shaders with one broken, for PRT_SHADER_DIR.
  const fs::path broken = f.folder / "broken_shaders";
  fs::create_directories(broken);
  for (const auto& entry : fs::directory_iterator(fs::path(PRT_SOURCE_DIR) / "shaders"))
    fs::copy_file(entry.path(), broken / entry.path().filename());
  std::ofstream(broken / "prt_diffuse.vert", std::ios::app) << "\nthis is not GLSL;\n";

  // Each runs `prt render` once (about a second each on a loaded 2-core machine, so the list keeps to
  // one case per kind of failure; argument parsing is covered in depth by test_render_support.cpp).
  struct BadCase {
    const char* what;
    std::string arguments, environment, expected_in_message, output;
  };
  const std::string jpg = f / "out.jpg";
  const BadCase cases[] = {
      {"missing mesh", f / "nope.ply" + " " + transfer + " --env " + env, "", f / "nope.ply", out},
      {"missing transfer", mesh + " " + f / "nope.prt" + " --env " + env, "", f / "nope.prt", out},
      {"transfer of another mesh", mesh + " " + f / "other.prt" + " --env " + env, "",
       f / "other.prt" + ": transfer was baked for a different mesh", out},
      {"missing environment", mesh + " " + transfer + " --env " + f / "nope.exr", "", f / "nope.exr", out},
      {"broken shader", mesh + " " + transfer + " --env " + env, "PRT_SHADER_DIR=" + broken.string(),
       (broken / "prt_diffuse.vert").string() + ": GLSL compile error", out},
      {"bad size", mesh + " " + transfer + " --env " + env + " --size 64by48", "", "--size: ", out},
      {"bad camera", mesh + " " + transfer + " --env " + env + " --camera 0,95,3", "", "--camera: ", out},
      {"unsupported output format", mesh + " " + transfer + " --env " + env, "", jpg + ": output must be", jpg},
  };
  for (const BadCase& c : cases) {
    const Run r = run_prt(f, c.arguments + " -o " + c.output, c.environment);
    INFO(c.what << ": stderr: " << r.err);
    CHECK(r.status == 1);
    CHECK(line_count(r.err) == 1);
    CHECK(r.err.rfind("prt: ", 0) == 0);
    CHECK(r.err.find(c.expected_in_message) != std::string::npos);
    CHECK_FALSE(fs::exists(c.output));
  }
}

TEST_CASE("render_to_file refuses bad bands and an env background without an image, before writing", "[render]") {
  Fixtures f;
  render::RenderOptions options;
  options.mesh_path = f / "mesh.ply";
  options.transfer_path = f / "transfer.prt";
  options.environment = f / "env.exr";
  options.output = f / "out.exr";
  options.quiet = true;
  options.bands = 6;
  CHECK_THROWS_WITH(render::render_to_file(options), "bands: must be between 1 and the transfer's 5 bands, got 6");
  options.bands = 0;
  options.environment = f / "light.json";
  options.background = render::Background::environment;
  CHECK_THROWS_WITH(render::render_to_file(options),
                    Catch::StartsWith(f / "light.json" + ": background env needs an environment image"));
  options.output = f / "out.tiff";
  CHECK_THROWS_WITH(render::render_to_file(options), Catch::StartsWith(f / "out.tiff" + ": output must be"));
  options.output = f / "no_such_folder/out.png";
  CHECK_THROWS_WITH(render::render_to_file(options), Catch::Contains("output folder does not exist"));
  CHECK_FALSE(fs::exists(f / "out.exr"));
}

TEST_CASE("shader includes nest (sun_light.glsl includes sun_pcss.glsl), and a loop of includes is a one-line error", "[render][gl][cli]") {
  Fixtures f;
  const std::string common = f / "mesh.ply" + " " + f / "transfer.prt" + " --env " + f / "env.exr";
  // A copy of the shaders in which prt_diffuse.vert includes loop.glsl, which includes itself.
  const fs::path looped = f.folder / "looped_shaders";
  fs::create_directories(looped);
  for (const auto& entry : fs::directory_iterator(fs::path(PRT_SOURCE_DIR) / "shaders"))
    fs::copy_file(entry.path(), looped / entry.path().filename());
  std::ofstream(looped / "loop.glsl") << "#include \"loop.glsl\"\n";
  std::ofstream(looped / "prt_diffuse.vert", std::ios::app) << "\n#include \"loop.glsl\"\n";
  const Run r = run_prt(f, common + " -o " + f / "out.png", "PRT_SHADER_DIR=" + looped.string());
  INFO("stderr: " << r.err);
  CHECK(r.status == 1);
  CHECK(line_count(r.err) == 1);
  CHECK(r.err.find("shaders/loop.glsl: includes nested more than 4 deep") != std::string::npos);
  CHECK_FALSE(fs::exists(f / "out.png"));
}
