// `prt bake`, `prt shade`, `prt info`, `prt compare` through the real binary: outputs, one-line errors,
// no partial files, SIGINT, byte-identical files for any thread count.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <thread>

#include <sys/wait.h>
#include <unistd.h>

#include <glm/geometric.hpp>

#include "core/atomic_file.h"
#include "mesh/writers.h"
#include "support/run_prt.h"
#include "support/shapes.h"

using namespace prt;
namespace fs = std::filesystem;

namespace {

std::string write_torus(const std::string& dir, int major, int minor) {
  const mesh::Mesh m = test::torus(1.0f, 0.45f, major, minor);
  const std::string path = dir + "/torus.ply";
  mesh::write_ply(path, m.positions, {}, m.indices);
  return path;
}

std::string write_constant_light(const std::string& dir) {
  const std::string path = dir + "/white.json";
  std::ofstream f(path);
  f << R"({"bands": 1, "basis": "real-orthonormal-condon-shortley", "index": "l*(l+1)+m",
           "frame": "right-handed, +Y up", "coefficients": [[3.5449077018, 3.5449077018, 3.5449077018]]})";
  return path;
}

// True once `pid` runs the prt binary (after exec) and has installed its SIGINT handler.
bool catches_sigint(pid_t pid) {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/" + std::to_string(pid) + "/exe", ec);
  if (ec || exe.filename() != "prt") return false;
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("SigCgt:", 0) == 0) return (std::stoull(line.substr(7), nullptr, 16) & (1ull << (SIGINT - 1))) != 0;
  return false;
}

bool contains(const std::string& haystack, const std::string& needle) { return haystack.find(needle) != std::string::npos; }

}  // namespace

TEST_CASE("prt bake writes identical files for 1 and 2 threads and prt info reads them", "[bake][cli]") {
  const std::string dir = test::fresh_temp_dir("bake_threads");
  const std::string mesh = write_torus(dir, 32, 16);
  auto r1 = test::run_prt("bake " + mesh + " --transfer interreflected --bounces 2 --samples 128 --bands 4 --footprint vertex --threads 1 -q -o " + dir + "/one.prt");
  REQUIRE(r1.exit_code == 0);
  auto r2 = test::run_prt("bake " + mesh + " --transfer interreflected --bounces 2 --samples 128 --bands 4 --footprint vertex --threads 2 -q -o " + dir + "/two.prt");
  REQUIRE(r2.exit_code == 0);
  CHECK(read_file(dir + "/one.prt") == read_file(dir + "/two.prt"));
  auto info = test::run_prt("info " + dir + "/one.prt");
  CHECK(info.exit_code == 0);
  CHECK(contains(info.output, "kind: interreflected"));
  CHECK(contains(info.output, "bands: 4 (16 coefficients)"));
  CHECK_FALSE(contains(info.output, "footprint"));  // vertex is not recorded (files as before area existed)

  // The default footprint, area: also independent of the thread count, and recorded in the parameters.
  for (const char* threads : {"1", "2"})
    REQUIRE(test::run_prt("bake " + mesh + " --transfer interreflected --bounces 2 --samples 128 --bands 4 --threads " +
                          threads + " -q -o " + dir + "/area" + threads + ".prt").exit_code == 0);
  CHECK(read_file(dir + "/area1.prt") == read_file(dir + "/area2.prt"));
  CHECK(read_file(dir + "/area1.prt") != read_file(dir + "/one.prt"));
  CHECK(contains(test::run_prt("info " + dir + "/area1.prt").output, "\"footprint\":\"area\""));
}

TEST_CASE("prt shade under a white light equals the furnace radiance and prt compare measures a known change", "[bake][cli]") {
  const std::string dir = test::fresh_temp_dir("shade_white");
  const std::string mesh = write_torus(dir, 24, 12);
  REQUIRE(test::run_prt("bake " + mesh + " --transfer unshadowed --bands 3 --albedo 0.5,0.5,0.5 -q -o " + dir + "/t.prt").exit_code == 0);
  auto shade = test::run_prt("shade " + mesh + " " + dir + "/t.prt --light " + write_constant_light(dir) + " -o " + dir + "/out.ply");
  REQUIRE(shade.exit_code == 0);
  const mesh::ColourPly ply = mesh::read_ply_colours(dir + "/out.ply");
  // Unshadowed Lambert under constant radiance 1 (c_0 = 2 sqrt(pi)): exit radiance = albedo.
  for (const glm::vec3& c : ply.colours) REQUIRE(c.r == Approx(0.5f).epsilon(1e-5));
  // B: the same mesh with vertex 0's red halved. Over the n = 3 V values (docs/conventions.md, prt
  // compare): rms = 0.25 / sqrt(n), rel_rms = rms / sqrt(sum b^2 / n), max_abs = 0.25, max_rel = 1.
  std::vector<glm::vec3> changed(ply.colours.size(), glm::vec3(0.5f));
  changed[0].r = 0.25f;
  mesh::write_ply(dir + "/changed.ply", ply.positions, changed, ply.indices);
  auto diff = test::run_prt("compare " + dir + "/out.ply " + dir + "/changed.ply");
  REQUIRE(diff.exit_code == 0);
  const double n = 3.0 * static_cast<double>(ply.colours.size());
  const double rms = 0.25 / std::sqrt(n), rms_b = std::sqrt(((n - 1.0) * 0.25 + 0.0625) / n);
  double got_rms = 0, got_rel = 0, got_abs = 0, got_max_rel = 0;
  REQUIRE(std::sscanf(diff.output.c_str(), "rms=%lf rel_rms=%lf max_abs=%lf max_rel=%lf", &got_rms, &got_rel, &got_abs,
                      &got_max_rel) == 4);
  CHECK(got_rms == Approx(rms).epsilon(1e-5));
  CHECK(got_rel == Approx(rms / rms_b).epsilon(1e-5));
  CHECK(got_abs == Approx(0.25).epsilon(1e-5));
  CHECK(got_max_rel == Approx(1.0).epsilon(1e-5));
  CHECK(contains(diff.output, "vertices=" + std::to_string(ply.colours.size())));
}

TEST_CASE("a cube OBJ of 8 v and 6 vn bakes faceted: each face's vertices shade as its flat normal", "[bake][cli][normals]") {
  // Hard edges through normal indices: every corner of the cube is used by 3 faces with 3 normals.
  const std::string dir = test::fresh_temp_dir("bake_hard_cube");
  const std::string mesh = dir + "/cube.obj";
  {
    std::ofstream obj(mesh);
    for (int c = 0; c < 8; ++c) obj << "v " << (c & 1) << " " << ((c >> 1) & 1) << " " << ((c >> 2) & 1) << "\n";
    obj << "vn -1 0 0\nvn 1 0 0\nvn 0 -1 0\nvn 0 1 0\nvn 0 0 -1\nvn 0 0 1\n";
    // Corners as x + 2y + 4z + 1; faces -X, +X, -Y, +Y, -Z, +Z, counter-clockwise seen from outside.
    obj << "f 1//1 5//1 7//1 3//1\nf 2//2 4//2 8//2 6//2\nf 1//3 2//3 6//3 5//3\n"
           "f 3//4 7//4 8//4 4//4\nf 1//5 3//5 4//5 2//5\nf 5//6 6//6 8//6 7//6\n";
  }
  // Radiance L(w) = 1 + 0.75 (d . w), exactly 2 bands (the SH table of docs/conventions.md, CS phase):
  // c_0 = 2 sqrt(pi), (c_1-1, c_10, c_11) = 0.75 sqrt(4 pi / 3) (-d_y, d_z, -d_x). The Lambert exit
  // radiance of a flat face of normal n is albedo (1 + (2/3) 0.75 (d . n)) = albedo (1 + (d . n) / 2).
  const glm::dvec3 d = glm::normalize(glm::dvec3(1.0, 2.0, 3.0));
  const double k = 0.75 * std::sqrt(4.0 * M_PI / 3.0);
  const std::string light = dir + "/linear.json";
  {
    std::ofstream f(light);
    f.precision(17);
    f << R"({"bands": 2, "basis": "real-orthonormal-condon-shortley", "index": "l*(l+1)+m", "frame": "right-handed, +Y up", "coefficients": [)";
    const double c[4] = {2.0 * std::sqrt(M_PI), -k * d.y, k * d.z, -k * d.x};
    for (int i = 0; i < 4; ++i) f << (i ? ", [" : "[") << c[i] << ", " << c[i] << ", " << c[i] << "]";
    f << "]}";
  }
  REQUIRE(test::run_prt("bake " + mesh + " --transfer unshadowed --bands 2 --albedo 0.5,0.5,0.5 -q -o " + dir + "/t.prt").exit_code == 0);
  const test::RunResult shade = test::run_prt("shade " + mesh + " " + dir + "/t.prt --light " + light +
                                              " --window none --sun none -o " + dir + "/out.ply");
  INFO(shade.output);
  REQUIRE(shade.exit_code == 0);
  const mesh::ColourPly ply = mesh::read_ply_colours(dir + "/out.ply");
  REQUIRE(ply.indices.size() == 36);
  for (std::size_t t = 0; t < ply.indices.size(); t += 3) {
    const glm::dvec3 a(ply.positions[ply.indices[t]]), b(ply.positions[ply.indices[t + 1]]), c(ply.positions[ply.indices[t + 2]]);
    const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
    const double expected = 0.5 * (1.0 + 0.5 * glm::dot(d, n));
    for (int corner = 0; corner < 3; ++corner) CHECK(ply.colours[ply.indices[t + corner]].g == Approx(expected).epsilon(1e-5));
  }
}

TEST_CASE("prt bake and shade refuse bad input with one line and leave no file", "[bake][cli]") {
  const std::string dir = test::fresh_temp_dir("bake_errors");
  const std::string mesh = write_torus(dir, 12, 6);
  std::ofstream(dir + "/mesh.xyz") << "not a mesh";
  const std::size_t before = test::entries_in(dir);
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"bake " + dir + "/missing.obj -o " + dir + "/o.prt", "missing.obj"},
      {"bake " + dir + "/mesh.xyz -o " + dir + "/o.prt", "mesh.xyz"},
      {"bake " + mesh + " --transfer glossy -o " + dir + "/o.prt", "unknown transfer kind 'glossy'"},
      {"bake " + mesh + " --bands 40 -o " + dir + "/o.prt", "--bands 40 is out of range"},
      {"bake " + mesh + " --albedo 1,2 -o " + dir + "/o.prt", "--albedo: expected R,G,B"},
      {"bake " + mesh + " --footprint corner -o " + dir + "/o.prt", "--footprint: expected area or vertex, got 'corner'"},
      {"bake " + mesh + " -o " + dir + "/no/such/dir/o.prt", "output folder does not exist"},
      {"shade " + mesh + " " + dir + "/missing.prt --light x.json -o " + dir + "/o.ply", "missing.prt"},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    auto r = test::run_prt(c.args);
    CHECK(r.exit_code != 0);
    CHECK(contains(r.output, c.message));
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
    CHECK(r.output.rfind("prt: ", 0) == 0);
  }
  CHECK(test::entries_in(dir) == before);

  // A transfer baked for another mesh is refused by shade.
  const std::string other = dir + "/other.ply";
  const mesh::Mesh m = test::torus(1.0f, 0.45f, 13, 6);
  mesh::write_ply(other, m.positions, {}, m.indices);
  REQUIRE(test::run_prt("bake " + other + " --transfer unshadowed -q -o " + dir + "/other.prt").exit_code == 0);
  auto mismatch = test::run_prt("shade " + mesh + " " + dir + "/other.prt --light " + write_constant_light(dir) + " -o " + dir + "/o.ply");
  CHECK(mismatch.exit_code != 0);
  CHECK(contains(mismatch.output, "transfer was baked for a different mesh"));
  CHECK_FALSE(fs::exists(dir + "/o.ply"));
}

TEST_CASE("SIGINT during a bake leaves no output and no temporary", "[bake][cli]") {
  const std::string dir = test::fresh_temp_dir("bake_sigint");
  const std::string mesh = write_torus(dir, 200, 100);
  const std::size_t before = test::entries_in(dir);
  const std::string out = dir + "/o.prt";
  pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    execl(test::prt_binary().c_str(), "prt", "bake", mesh.c_str(), "--transfer", "interreflected", "--samples", "2048",
          "--bounces", "8", "-q", "-o", out.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // Wait until prt has installed its SIGINT handler (bit 1 of SigCgt in /proc/<pid>/status), then
  // give it a moment to be inside the bake.
  for (int tries = 0; tries < 600 && !catches_sigint(pid); ++tries) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  REQUIRE(catches_sigint(pid));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  INFO("status " << status << " signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0));
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK_FALSE(fs::exists(out));
  CHECK(test::entries_in(dir) == before);
}
