// The prt command line on hostile arguments and outputs (issue 10's list): one line
// "prt: <file>: <problem>", exit status 1, no output file, inputs never overwritten.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "hardening/bad_input_files.h"
#include "image/image.h"
#include "mesh/writers.h"

namespace prt::test {
namespace {

using Catch::Matchers::Contains;
namespace fs = std::filesystem;

struct Scene {
  std::string dir, mesh, light, env;
};

// A folder with a two-triangle OBJ, a 2-band SH light and a constant 8x4 EXR environment.
const Scene& scene() {
  static const Scene s = [] {
    Scene out;
    out.dir = fresh_temp_dir("hardening_cli");
    out.mesh = out.dir + "/quad.obj";
    write_bytes(out.mesh, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
    out.light = out.dir + "/light.json";
    write_bytes(out.light, R"({"bands":2,"basis":"real-orthonormal-condon-shortley","index":"l*(l+1)+m",)"
                           R"("frame":"right-handed, +Y up","coefficients":[[3.5,3.5,3.5],[0,0,0],[0.5,0.5,0.5],[0,0,0]]})");
    out.env = out.dir + "/env.exr";
    image::Image env(8, 4, 3);
    env.pixels.assign(env.pixels.size(), 1.0f);
    image::write(out.env, env);
    return out;
  }();
  return s;
}

void require_one_line_error(const RunResult& r, const std::string& mentions) {
  INFO(r.output);
  REQUIRE(r.exit_code == 1);
  REQUIRE(is_one_error_line(r.output));
  REQUIRE_THAT(r.output, Contains(mentions));
}

TEST_CASE("CLI11 parse errors are one line with exit status 1", "[hardening][cli]") {
  require_one_line_error(run_prt("bake"), "MESH");
  require_one_line_error(run_prt("bake " + scene().mesh + " -o x.prt --bands notanumber"), "--bands");
  require_one_line_error(run_prt("no-such-command"), "subcommand");
  require_one_line_error(run_prt("bake " + scene().mesh + " -o x.prt --no-such-option"), "--no-such-option");
  // --help and --version still succeed.
  REQUIRE(run_prt("--version").exit_code == 0);
  REQUIRE(run_prt("bake --help").exit_code == 0);
}

TEST_CASE("over-long path components give one line, not a filesystem_error", "[hardening][cli]") {
  const std::string long_name = scene().dir + "/" + std::string(300, 'a');
  require_one_line_error(run_prt("bake " + long_name + ".obj -q -o " + scene().dir + "/x.prt"), "aaaa");
  require_one_line_error(run_prt("bake " + scene().mesh + " -q -o " + long_name + ".prt"), "file name is too long");
  require_one_line_error(run_prt("light " + long_name + ".exr -o " + scene().dir + "/x.json"), "aaaa");
  // A folder component that long made std::filesystem throw (exit 2) before.
  require_one_line_error(run_prt("bake " + scene().mesh + " -q -o " + long_name + "/x.prt"), "aaaa");
}

TEST_CASE("a codec's own stderr text is folded into prt's one line", "[hardening][cli][image]") {
  // A PNG whose IHDR CRC is wrong (bytes 29-32: after the signature, the chunk's length and type and
  // its 13 data bytes): libpng prints its own "libpng error: IHDR: CRC error" line unless prt captures
  // it. (A PNG cut short no longer reaches libpng: image_structure.h refuses it first.)
  const std::string good = scene().dir + "/good.png";
  image::Image grey(4, 4, 3);
  grey.pixels.assign(grey.pixels.size(), 0.5f);
  image::write(good, grey);
  std::string png = file_bytes(good);
  png[29] = static_cast<char>(png[29] ^ 0xff);
  const std::string bad = scene().dir + "/bad_crc.png";
  write_bytes(bad, png);
  const RunResult run = run_prt("light " + bad + " -o " + scene().dir + "/bad_crc.json");
  require_one_line_error(run, bad);
  REQUIRE_THAT(run.output, Contains("(libpng error: IHDR: CRC error)"));
}

TEST_CASE("finite but extreme option values are refused before they reach Embree", "[hardening][cli][range]") {
  const std::string out = scene().dir + "/ref.exr";
  const std::string ref = "reference " + scene().mesh + " --env " + scene().env + " --image --samples 1 -q -o " + out;
  require_one_line_error(run_prt(ref + " --camera 0,0,1e308"), "--camera");
  require_one_line_error(run_prt(ref + " --camera 0,0,1e-300"), "--camera");
  const std::string probes = "probes " + scene().mesh + " --env " + scene().env + " --format prt -q -o " +
                             scene().dir + "/p.prtprobes --grid 2,2,2";
  require_one_line_error(run_prt(probes + " --bounds -1e308,-1e308,-1e308,1e308,1e308,1e308"), "--bounds");
  require_one_line_error(run_prt(probes + " --sun 0,1,0,1e308,1"), "--sun");
  REQUIRE_FALSE(fs::exists(out));
  REQUIRE_FALSE(fs::exists(scene().dir + "/p.prtprobes"));
}

TEST_CASE("an environment map pixel above 1e18 is refused, one at 1e18 is accepted", "[hardening][cli][range]") {
  // 3e38 is finite, but its SH coefficients times transfer overflow float in shading and rendering.
  const std::string out = scene().dir + "/bright.json";
  for (const float value : {3e38f, 1.5e18f}) {
    image::Image env(16, 8, 3);
    env.pixels.assign(env.pixels.size(), 1.0f);
    env.at(5, 2, 1) = value;
    const std::string path = scene().dir + "/bright.exr";
    image::write(path, env);
    require_one_line_error(run_prt("light " + path + " --sun none -o " + out), "pixel (5, 2)");
    REQUIRE_FALSE(fs::exists(out));
  }
  image::Image env(16, 8, 3);
  env.pixels.assign(env.pixels.size(), 1.0f);
  env.at(5, 2, 1) = 1e18f * 0.999f;
  image::write(scene().dir + "/bright.exr", env);
  const RunResult ok = run_prt("light " + scene().dir + "/bright.exr --sun none -o " + out);
  INFO(ok.output);
  REQUIRE(ok.exit_code == 0);
  REQUIRE(fs::exists(out));
}

TEST_CASE("glossy shade with --eye 1e308 is refused instead of writing NaN", "[hardening][cli][range]") {
  const std::string prt_file = scene().dir + "/glossy.prt";
  const RunResult bake = run_prt("bake " + scene().mesh + " -o " + prt_file +
                                 " --transfer glossy-shadowed --brdf phong:exponent=8,ks=0.5 --bands 2 --samples 16 -q");
  INFO(bake.output);
  REQUIRE(bake.exit_code == 0);
  const std::string out = scene().dir + "/glossy.ply";
  const std::string shade = "shade " + scene().mesh + " " + prt_file + " --light " + scene().light + " -o " + out;
  require_one_line_error(run_prt(shade + " --eye 1e308,0,0"), "--eye");
  REQUIRE_FALSE(fs::exists(out));
  REQUIRE(run_prt(shade + " --eye 0,0,5").exit_code == 0);  // the control
}

TEST_CASE("prt compare of all-NaN values does not report rms=0", "[hardening][cli]") {
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<glm::vec3> colours(3, glm::vec3(nan)), ones(3, glm::vec3(1.0f));
  const std::string a = scene().dir + "/nan_a.ply", b = scene().dir + "/nan_b.ply";
  mesh::write_ply(a, positions, colours, {0, 1, 2});
  mesh::write_ply(b, positions, ones, {0, 1, 2});
  const RunResult r = run_prt("compare " + a + " " + b);
  require_one_line_error(r, "NaN");
  REQUIRE_THAT(r.output, !Contains("rms=0"));
}

TEST_CASE("an output equal to an input is refused and the input is untouched", "[hardening][cli][outputs]") {
  const std::string before = file_bytes(scene().mesh);
  require_one_line_error(run_prt("bake " + scene().mesh + " -o " + scene().mesh), "is also the input");
  // The same file spelt differently: dir/./x and dir/sub/../x.
  fs::create_directories(scene().dir + "/sub");
  require_one_line_error(run_prt("bake " + scene().mesh + " -o " + scene().dir + "/./quad.obj"), "is also the input");
  require_one_line_error(run_prt("bake " + scene().mesh + " -o " + scene().dir + "/sub/../quad.obj"),
                         "is also the input");
  REQUIRE(file_bytes(scene().mesh) == before);
  // --gltf equal to -o, and light's preview equal to its output through "./".
  const std::string prt_file = scene().dir + "/twice.prt";
  require_one_line_error(run_prt("bake " + scene().mesh + " -o " + prt_file + " --gltf " + scene().dir + "/./twice.prt"),
                         "given twice");
  require_one_line_error(run_prt("light " + scene().env + " -o " + scene().dir + "/l.exr --preview " + scene().dir +
                                 "/./l.exr"),
                         "given twice");
  const std::string env_before = file_bytes(scene().env);
  require_one_line_error(run_prt("light " + scene().env + " -o " + scene().dir + "/l.json --preview " + scene().env),
                         "is also the input");
  REQUIRE(file_bytes(scene().env) == env_before);
  // compare --heatmap A.ply.
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::string a = scene().dir + "/heat_a.ply";
  mesh::write_ply(a, positions, std::vector<glm::vec3>(3, glm::vec3(1.0f)), {0, 1, 2});
  const std::string a_before = file_bytes(a);
  require_one_line_error(run_prt("compare " + a + " " + a + " --heatmap " + a), "is also the input");
  REQUIRE(file_bytes(a) == a_before);
}

TEST_CASE("an unwritable folder for a second output leaves no first output", "[hardening][cli][outputs]") {
  // /proc accepts no new files, even for root (permission bits would not stop root).
  const std::string prt_file = scene().dir + "/first.prt";
  require_one_line_error(run_prt("bake " + scene().mesh + " -o " + prt_file + " --gltf /proc/second.glb -q"),
                         "/proc/second.glb");
  REQUIRE_FALSE(fs::exists(prt_file));
  const std::string matrix = scene().dir + "/first.json";
  require_one_line_error(run_prt("brdf lambert:albedo=0.5 --bands 2 -o " + matrix + " --preview /proc/second.png -q"),
                         "/proc/second.png");
  REQUIRE_FALSE(fs::exists(matrix));
}

TEST_CASE("an unwritable output folder is found before the work, naming the output", "[hardening][cli][outputs]") {
  const auto start = std::chrono::steady_clock::now();
  const RunResult r = run_prt("bake " + scene().mesh + " -o /proc/out.prt --transfer interreflected --samples 4096 -q");
  require_one_line_error(r, "/proc/out.prt: output folder is not writable");
  REQUIRE(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 5.0);
  // probes --format gltf names the output, not its staging file.
  const RunResult g = run_prt("probes " + scene().mesh + " --env " + scene().env +
                              " --grid 1,1,1 --format gltf -q -o /proc/probes.glb");
  require_one_line_error(g, "/proc/probes.glb");
  REQUIRE_THAT(g.output, !Contains(".tmp-"));
}

}  // namespace
}  // namespace prt::test
