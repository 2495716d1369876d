// `mpirun -np N prt ...` through the real binaries (docs/distributed.md): the files of 1, 2 and 3 ranks
// (oversubscribed, with different threads per rank) are byte-identical to a plain single-process run
// for every distributed command; a killed rank ends the job fast with no output; mismatched inputs
// are one clear error. The independent truth is the single-process run without MPI, whose own
// correctness the bake, probe and reference tests check against closed forms.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <glm/geometric.hpp>

#include "bench_meshes.h"
#include "dist/mpi_launch.h"
#include "image/image.h"
#include "mesh/writers.h"
#include "transfer/transfer_file.h"

using namespace prt;

namespace {

struct Inputs {
  std::string dir, grey, coloured, large, sky;
};

// A bumpy icosphere (2,562 vertices: self-shadowing ridges) grey and with per-vertex colours, a larger one
// (10,242 vertices) for the fault test, and a small sky; written once per process, in its own folder.
const Inputs& inputs() {
  static const Inputs in = [] {
    Inputs i;
    i.dir = test::fresh_temp_dir("dist_inputs");  // per process: ctest runs the tags in parallel
    const mesh::Mesh m = bench::bumpy_icosphere(4, 0.35f);
    i.grey = i.dir + "/grey.ply";
    mesh::write_ply(i.grey, m.positions, {}, m.indices);
    std::vector<glm::vec3> colours;
    for (const glm::vec3& p : m.positions) colours.push_back(glm::vec3(0.5f) + 0.3f * glm::normalize(p));
    i.coloured = i.dir + "/coloured.ply";
    mesh::write_ply(i.coloured, m.positions, colours, m.indices);
    const mesh::Mesh big = bench::bumpy_icosphere(5, 0.35f);
    i.large = i.dir + "/large.ply";
    mesh::write_ply(i.large, big.positions, {}, big.indices);
    image::Image sky(64, 32, 3);
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 64; ++x)
        for (int c = 0; c < 3; ++c) sky.at(x, y, c) = y < 16 ? 1.0f + 0.05f * x + 0.3f * c : 0.1f;
    i.sky = i.dir + "/sky.exr";
    image::write(i.sky, sky);
    return i;
  }();
  return in;
}

// Runs `arguments` (which write to "-o OUT") once without MPI and under each of `rank_counts` ranks
// (threads per rank 2 for 1 and 2 ranks, else 1), and checks that the files are byte for byte the same.
// Returns the plain run's path.
std::string check_identical(const std::string& name, const std::string& arguments, const std::string& extension,
                            const std::vector<int>& rank_counts = {1, 2, 3}) {
  const std::string dir = test::fresh_temp_dir("dist_" + name);
  const std::string plain = dir + "/plain" + extension;
  const test::RunResult base = test::run_prt(arguments + " -o " + plain + " --threads 2 -q");
  INFO(base.output);
  REQUIRE(base.exit_code == 0);
  const std::string expected = test::file_bytes(plain);
  REQUIRE(expected.size() > 0);
  for (int ranks : rank_counts) {
    const std::string out = dir + "/np" + std::to_string(ranks) + extension;
    const std::string threads = ranks <= 2 ? "2" : "1";
    const test::RunResult run = test::run_prt_ranks(ranks, arguments + " -o " + out + " --threads " + threads + " -q");
    INFO(name << ", " << ranks << " rank(s): " << run.output);
    REQUIRE(run.exit_code == 0);
    CHECK(test::file_bytes(out) == expected);
  }
  return plain;
}

}  // namespace

TEST_CASE("mpirun -np 1, 2, 3 bakes byte-identical diffuse transfer", "[dist][bake][slow]") {
  const Inputs& in = inputs();
  check_identical("shadowed", "bake " + in.grey + " --transfer shadowed --bands 4 --samples 64 --footprint vertex", ".prt");
  // Interreflected with colour (3 channels): the bounce passes exchange the previous pass; the file
  // carries the bounce-only section, which must be identical too.
  const std::string file =
      check_identical("interreflected", "bake " + in.coloured + " --transfer interreflected --bands 3 --samples 32 --bounces 3", ".prt");
  const transfer::TransferData data = transfer::read_transfer(file);
  CHECK(data.header.bounce_only_section);
  CHECK(data.header.channels == 3);
  // The automatic bounce count: the stopping rule sees the same energies on every rank.
  check_identical("interreflected_auto", "bake " + in.grey + " --transfer interreflected --bands 2 --samples 16", ".prt");
  // Rays from points of each vertex's footprint: chosen per vertex, whichever rank traces it.
  check_identical("interreflected_area",
                  "bake " + in.grey + " --transfer interreflected --bands 3 --samples 64 --bounces 2 --footprint area", ".prt");
}

TEST_CASE("mpirun -np 1, 2, 3 bakes byte-identical lightmaps", "[dist][bake][slow]") {
  // A floor with a tetrahedron-like tent on it, each in its own chart of the lightmap UVs (OBJ vt).
  const std::string mesh = test::fresh_temp_dir("dist_lightmap_mesh") + "/tent.obj";
  std::ofstream(mesh) << (
                    "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -0.3 0.01 -0.3\nv 0.3 0.01 -0.3\nv 0 0.6 0\n"
                    "vt 0.05 0.05\nvt 0.95 0.05\nvt 0.95 0.6\nvt 0.05 0.6\nvt 0.1 0.7\nvt 0.5 0.7\nvt 0.3 0.95\n"
                    "f 1/1 3/3 2/2\nf 1/1 4/4 3/3\nf 5/5 6/6 7/7\n");
  check_identical("lightmap_shadowed", "bake " + mesh + " --lightmap 32 --transfer shadowed --bands 3 --samples 32", ".prt");
  // The bounce passes gather the previous pass in the texel grid: every rank needs all of it.
  const std::string file = check_identical(
      "lightmap_interreflected", "bake " + mesh + " --lightmap 32x16 --transfer interreflected --bands 3 --samples 32 --bounces 2", ".prt");
  CHECK(transfer::read_transfer(file).header.texel_width == 32);
}

TEST_CASE("mpirun -np 1, 2, 3 bakes byte-identical glossy transfer", "[dist][bake][slow]") {
  const Inputs& in = inputs();
  const std::string brdf = " --brdf phong:exponent=16,ks=0.4,kd=0.4 --bands 3 --samples 16";
  check_identical("glossy_shadowed", "bake " + in.grey + " --transfer glossy-shadowed" + brdf, ".prt");
  check_identical("glossy_interreflected",
                  "bake " + in.grey + " --transfer glossy-interreflected --bounces 1 --brdf ggx:roughness=0.4,f0=0.04,albedo=0.6/0.4/0.3 "
                  "--bands 3 --samples 16",
                  ".prt");
}

// Probes and references read an image (OpenImageIO's start-up costs most of each run here), so the
// image reference runs only on 3 ranks.
TEST_CASE("mpirun -np 1, 2, 3 bakes byte-identical probes and references", "[dist][scene][slow]") {
  const Inputs& in = inputs();
  check_identical("probes",
                  "probes " + in.grey + " --env " + in.sky + " --grid 4,3,4 --format prt --rays 64 --surface-samples 16 --bounces 2 --transfer",
                  ".prt");
  check_identical("reference", "reference " + in.grey + " --env " + in.sky + " --samples 16 --bounces 1 --footprint vertex", ".ply");
  check_identical("reference_area", "reference " + in.grey + " --env " + in.sky + " --samples 32 --bounces 1 --footprint area", ".ply");
  check_identical("reference_image",
                  "reference " + in.grey + " --env " + in.sky + " --samples 4 --image --size 40x30", ".exr", {3});
}

TEST_CASE("mismatched inputs on two ranks are one clear error on every rank, copies are fine", "[dist][faults][slow]") {
  const Inputs& in = inputs();
  const std::string dir = test::fresh_temp_dir("dist_mismatch");
  const std::string bake = " bake --transfer shadowed --bands 3 --samples 16 -q -o " + dir + "/out.prt ";
  // Rank 2 reads another mesh (as if another machine had another version of the file).
  test::RunResult run = test::run_shell(test::mpirun(2) + " " + test::prt_binary() + bake + in.grey + " : -np 1 " +
                                        test::prt_binary() + bake + in.coloured);
  INFO(run.output);
  CHECK(run.exit_code != 0);
  CHECK(run.output.find(in.grey + ": differs between ranks (rank 0: 0x") != std::string::npos);
  CHECK(run.output.find(in.coloured + ": differs between ranks (rank 0: 0x") != std::string::npos);
  CHECK(run.output.find(", rank 2: 0x") != std::string::npos);
  CHECK(test::entries_in(dir) == 0);
  // Different options on one rank.
  run = test::run_shell(test::mpirun(1) + " " + test::prt_binary() + bake + in.grey + " : -np 1 " + test::prt_binary() +
                        bake + in.grey + " --seed 2");
  INFO(run.output);
  CHECK(run.exit_code != 0);
  CHECK(run.output.find("prt: the options: differs between ranks") != std::string::npos);
  CHECK(test::entries_in(dir) == 0);
  // A copy of the same file under another name (copied inputs) is the same input.
  const std::string copy = dir + "/../dist_copy.ply";
  std::filesystem::copy_file(in.grey, copy, std::filesystem::copy_options::overwrite_existing);
  run = test::run_shell(test::mpirun(1) + " " + test::prt_binary() + bake + in.grey + " : -np 1 " + test::prt_binary() +
                        bake + copy);
  INFO(run.output);
  CHECK(run.exit_code == 0);
  CHECK(test::entries_in(dir) == 1);
}

TEST_CASE("a rank that fails alone ends the job with its error and no output", "[dist][faults][slow]") {
  const Inputs& in = inputs();
  const std::string dir = test::fresh_temp_dir("dist_missing");
  const std::string bake = " bake --transfer shadowed --bands 3 --samples 16 -q -o " + dir + "/out.prt ";
  const auto start = std::chrono::steady_clock::now();
  // `timeout`: a job that hangs (a rank waiting forever for the failed one) fails here instead of stalling ctest.
  const test::RunResult run = test::run_shell("timeout 60 " + test::mpirun(2) + " " + test::prt_binary() + bake + in.grey +
                                              " : -np 1 " + test::prt_binary() + bake + dir + "/missing.ply");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  INFO(run.output);
  CHECK(run.exit_code != 0);
  CHECK(run.output.find("prt: " + dir + "/missing.ply: cannot open") != std::string::npos);
  CHECK(seconds < 20.0);
  CHECK(test::entries_in(dir) == 0);
}

TEST_CASE("killing one rank mid-bake ends the job within seconds, with no output and no rank left", "[dist][faults][slow]") {
  const Inputs& in = inputs();
  const std::string dir = test::fresh_temp_dir("dist_kill");
  const std::string log = test::fresh_temp_dir("dist_kill_log") + "/mpirun.log";
  // About 200 M rays: tens of seconds on two cores, so the bake is surely running when rank 1 is killed.
  const pid_t launcher = test::spawn_shell("exec " + test::mpirun(3) + " " + test::prt_binary() + " bake " + in.large +
                                               " --transfer interreflected --bands 3 --samples 4096 --bounces 4 --threads 1 -o " +
                                               dir + "/out.prt",
                                           log);
  REQUIRE(launcher > 0);
  std::vector<pid_t> ranks;
  pid_t victim = -1;
  for (int i = 0; i < 300 && victim < 0; ++i) {  // up to 30 s for the launcher to start its ranks
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    ranks = test::children_of(launcher);
    for (pid_t p : ranks)
      if (test::mpi_rank_of(p) == 1) victim = p;
  }
  REQUIRE(victim > 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // past loading and the fingerprint check
  REQUIRE(test::running(victim));
  const auto killed = std::chrono::steady_clock::now();
  REQUIRE(kill(victim, SIGKILL) == 0);
  int status = 0;
  pid_t done = 0;
  while ((done = waitpid(launcher, &status, WNOHANG)) == 0 &&
         std::chrono::steady_clock::now() - killed < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const double detection = std::chrono::duration<double>(std::chrono::steady_clock::now() - killed).count();
  if (done == 0) kill(launcher, SIGKILL);
  INFO(test::file_bytes(log));
  REQUIRE(done == launcher);
  WARN("killed rank 1; mpirun exited after " << detection << " s with status " << WEXITSTATUS(status));
  CHECK(detection < 10.0);
  CHECK((WIFEXITED(status) && WEXITSTATUS(status) != 0));
  // Every other rank is gone within a few more seconds (the launcher kills them).
  bool any_left = true;
  for (int i = 0; i < 50 && any_left; ++i) {
    any_left = false;
    for (pid_t p : ranks) any_left = any_left || test::running(p);
    if (any_left) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  CHECK_FALSE(any_left);
  CHECK(test::entries_in(dir) == 0);  // no output, not even a temporary
}
