// The .prtprobes file (round trip, damage detection), grids and point lists, the Bevy KTX2 container,
// the three.js JSON shape, and the `prt probes` / `prt probes-relight` commands with their one-line errors.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "image/image.h"
#include "probes/exporters.h"
#include "probes/probe_file.h"
#include "probes/probe_set.h"
#include "support/run_prt.h"

using namespace prt;

namespace {

probes::ProbeSet sample_set(bool transfer) {
  probes::ProbeSet p;
  p.layout = probes::ProbeSet::Layout::grid;
  p.grid.counts = {{2, 1, 2}};
  p.grid.lo = {0, 0, 0};
  p.grid.hi = {2, 1, 2};
  p.bands = 2;
  for (const glm::dvec3& x : probes::grid_positions(p.grid)) p.positions.emplace_back(x);
  for (std::size_t i = 0; i < 4 * 4; ++i) p.coefficients.emplace_back(0.1f * i, -0.2f * i, 1.0f / (i + 1));
  p.valid = {1, 0, 1, 1};
  p.backface_fraction = {0.0f, 0.9f, 0.1f, 0.25f};
  p.sky = sh::RgbCoefficients(2);
  p.sky.values[0] = {3.5, 2.0, 1.0};
  if (transfer) {
    p.transfer_bands = 2;
    p.transfer_channels = 1;
    for (std::size_t i = 0; i < 4 * 4 * 4; ++i) p.transfer.push_back(0.01f * i);
    p.transfer_bias.assign(16, glm::vec3(0.5f));
    p.transfer_environment = sh::RgbCoefficients(2);
    p.sky_bias = sh::RgbCoefficients(2);
  }
  p.parameters_json = R"({"rays":1024})";
  return p;
}

std::string write_text(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// A floor and a closed box as OBJ (the CLI tests' scene).
std::string write_scene(const std::string& dir) {
  std::string obj;
  obj += "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nf 1 3 2\nf 1 4 3\n";
  const char* box =
      "v -0.5 0.01 -0.5\nv 0.5 0.01 -0.5\nv 0.5 0.01 0.5\nv -0.5 0.01 0.5\n"
      "v -0.5 1 -0.5\nv 0.5 1 -0.5\nv 0.5 1 0.5\nv -0.5 1 0.5\n"
      "f 5 6 7\nf 5 7 8\nf 9 11 10\nf 9 12 11\nf 5 10 6\nf 5 9 10\nf 7 12 8\nf 7 11 12\nf 6 11 7\nf 6 10 11\nf 8 9 5\nf 8 12 9\n";
  obj += box;
  return write_text(dir, "scene.obj", obj);
}

// A small sky (64 x 32 equirect, brighter above) written once per process: keeps the CLI runs fast.
std::string sky() {
  static const std::string path = [] {
    const std::string dir = test::fresh_temp_dir("probe_cli_sky");
    image::Image sky(64, 32, 3);
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 64; ++x)
        for (int c = 0; c < 3; ++c) sky.at(x, y, c) = y < 16 ? 1.0f + 0.02f * x + 0.3f * c : 0.2f;
    image::write(dir + "/sky.exr", sky);
    return dir + "/sky.exr";
  }();
  return path;
}

}  // namespace

TEST_CASE("probe files round-trip exactly and name their damage", "[probes][file]") {
  for (bool transfer : {false, true}) {
    const probes::ProbeSet p = sample_set(transfer);
    const std::string bytes = probes::format_probe_file(p);
    const probes::ProbeSet q = probes::parse_probe_file(bytes, "x.prtprobes");
    CHECK(q.positions == p.positions);
    CHECK(q.coefficients == p.coefficients);
    CHECK(q.valid == p.valid);
    CHECK(q.backface_fraction == p.backface_fraction);
    CHECK(q.grid.counts == p.grid.counts);
    CHECK(q.sky.values == p.sky.values);
    CHECK(q.transfer == p.transfer);
    CHECK(q.transfer_bias == p.transfer_bias);
    CHECK(q.transfer_bands == p.transfer_bands);
    CHECK(nlohmann::json::parse(q.parameters_json)["rays"] == 1024);
  }
  const std::string good = probes::format_probe_file(sample_set(true));
  auto error_of = [](const std::string& bytes) {
    try {
      probes::parse_probe_file(bytes, "x.prtprobes");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error_of(good.substr(0, 10)).find("truncated") != std::string::npos);
  CHECK(error_of("XXXXXXXX" + good.substr(8)).find("wrong magic") != std::string::npos);
  CHECK(error_of(good.substr(0, good.size() - 4)).find("truncated payload") != std::string::npos);
  std::string flipped = good;
  flipped[flipped.size() - 3] ^= 0x40;
  CHECK(error_of(flipped).find("checksum") != std::string::npos);
  std::string version = good;
  version[8] = 9;
  CHECK(error_of(version).find("unsupported probe file version 9") != std::string::npos);
  for (const std::string& e : {error_of(good.substr(0, 10)), error_of(flipped)}) {
    CHECK(e.rfind("x.prtprobes: ", 0) == 0);
    CHECK(e.find('\n') == std::string::npos);
  }
}

TEST_CASE("grids put probes at cell centres, x fastest, bad grids and point lists are one-line errors", "[probes][file]") {
  probes::Grid g;
  g.counts = {{2, 3, 1}};
  g.lo = {0, 0, 0};
  g.hi = {2, 3, 4};
  const auto x = probes::grid_positions(g);
  REQUIRE(x.size() == 6);
  CHECK(x[0] == glm::dvec3(0.5, 0.5, 2.0));
  CHECK(x[1] == glm::dvec3(1.5, 0.5, 2.0));
  CHECK(x[2] == glm::dvec3(0.5, 1.5, 2.0));
  g.counts = {{2, 0, 1}};
  CHECK_THROWS_WITH(probes::check_grid(g), Catch::Contains("grid: every count must be >= 1"));
  g.counts = {{2, 2, 2}};
  g.hi = {2, 0, 4};
  CHECK_THROWS_WITH(probes::check_grid(g), Catch::Contains("bounds: the box") && Catch::Contains("is empty along y"));

  const std::string dir = test::fresh_temp_dir("probe_points");
  const auto json = probes::read_points_file(write_text(dir, "a.json", R"({"points": [[1,2,3],[4,5,6]]})"));
  CHECK(json.size() == 2);
  CHECK(json[1] == glm::dvec3(4, 5, 6));
  const auto csv = probes::read_points_file(write_text(dir, "a.csv", "x,y,z\n1, 2, 3\n# comment\n\n4,5,6\n"));
  CHECK(csv == json);
  CHECK_THROWS_WITH(probes::read_points_file(write_text(dir, "b.csv", "1,2,3\n1,2\n")), Catch::Contains("b.csv: line 2: expected x,y,z"));
  CHECK_THROWS_WITH(probes::read_points_file(write_text(dir, "c.json", "[]")), Catch::Contains("c.json: the point list is empty"));
  CHECK_THROWS_WITH(probes::read_points_file(write_text(dir, "d.txt", "1,2,3")), Catch::Contains("unknown point list format"));
  CHECK_THROWS_WITH(probes::check_points_inside(json, {0, 0, 0}, {4, 4, 4}, "p.json"),
                    Catch::Contains("p.json: point 1 (4, 5, 6) is outside the scene bounds"));
}

TEST_CASE("exports: three.js marks invalid probes, Bevy fills them, unknown formats are refused", "[probes][file]") {
  const probes::ProbeSet p = sample_set(false);
  const auto doc = nlohmann::json::parse(probes::format_threejs(p));
  CHECK(doc["count"] == 4);
  CHECK(doc["valid"] == nlohmann::json::array({1, 0, 1, 1}));
  const auto unity = nlohmann::json::parse(probes::format_unity(p));
  CHECK(unity["probes"][1]["valid"] == false);
  // Dilation: the invalid probe 1 (x=1, z=0) takes the mean of its valid neighbours 0 and 3.
  const std::vector<glm::vec3> filled = probes::dilate_invalid(p);
  for (int k = 0; k < 4; ++k) CHECK(filled[4 + k] == 0.5f * (p.coefficients[0 + k] + p.coefficients[12 + k]));
  const probes::Ktx2Texture t = probes::read_bevy_ktx2(probes::format_bevy_ktx2(p), "v.ktx2");
  CHECK(t.width == 2);
  CHECK(t.height == 2);
  CHECK(t.depth == 6);
  CHECK_THROWS_WITH(probes::parse_format("unreal"), Catch::Contains("format: unknown format 'unreal'"));
  CHECK_THROWS_WITH(probes::format_filament(p, "1"), Catch::Contains("probe 1 is invalid"));
  CHECK_THROWS_WITH(probes::format_filament(p, "9"), Catch::Contains("probe: expected 'sky' or a probe index"));
}

TEST_CASE("prt probes: bad inputs give one-line errors and leave nothing behind", "[probes][cli]") {
  const std::string dir = test::fresh_temp_dir("probe_cli_errors");
  const std::string scene = write_scene(dir);
  const std::string base = scene + " --env " + sky() + " -q -o " + dir + "/out.json ";
  const std::string points_out = write_text(dir, "far.json", "[[0,0.5,0],[9,9,9]]");
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"--grid 2,2,2 --bounds 0,0,0,1,0,1 --format prt", "--bounds: the box (0, 0, 0) - (1, 0, 1) is empty along y"},
      {"--grid 2,0,2 --format prt", "--grid: every count must be >= 1"},
      {"--points " + points_out + " --format prt", "point 1 (9, 9, 9) is outside the scene bounds"},
      {"--grid 2,2,2 --format unreal", "--format: unknown format 'unreal' (expected prt, threejs, unity, godot, filament, gltf or bevy)"},
      {"--format prt", "give exactly one of --grid NX,NY,NZ and --points FILE"},
      {"--points " + points_out + " --format bevy", "--format bevy needs a probe grid"},
      {"--grid 2,2,2 --format prt --sun 0,1,0,5", "--sun: expected auto, none, DX,DY,DZ,R,G,B,RADIUS_DEG or DX,DY,DZ,E,RADIUS_DEG"},
      {"--grid 2,2,2 --format prt --bands 0", "--bands 0 is out of range 1..16"},
  };
  for (const Case& c : cases) {
    const test::RunResult r = test::run_prt("probes " + base + c.args);
    INFO(c.args << "\n" << r.output);
    CHECK(r.exit_code == 1);
    CHECK(r.output.find("prt: ") == 0);
    CHECK(r.output.find(c.message) != std::string::npos);
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
  }
  const std::vector<std::string> left = {"scene.obj", "far.json"};
  CHECK(test::entries_in(dir) == left.size());
}

TEST_CASE("prt probes bakes every format, probes-relight applies a rotated sky", "[probes][cli]") {
  const std::string dir = test::fresh_temp_dir("probe_cli_formats");
  const std::string scene = write_scene(dir);
  const std::string base = "probes " + scene + " --env " + sky() + " --grid 3,2,3 --rays 256 --surface-samples 64 -q ";
  for (const char* f : {"prt", "threejs", "unity", "godot", "filament", "bevy"}) {
    const test::RunResult r = test::run_prt(base + "--format " + f + " -o " + dir + "/out." + f);
    INFO(f << ": " << r.output);
    CHECK(r.exit_code == 0);
  }
  const test::RunResult gltf = test::run_prt(base + "--format gltf --specular-size 8 -o " + dir + "/out.glb");
  INFO(gltf.output);
  REQUIRE(gltf.exit_code == 0);
  const std::string glb = read_file(dir + "/out.glb");
  CHECK(glb.compare(0, 4, "glTF") == 0);
  CHECK(glb.find("\"EXT_lights_image_based\"") != std::string::npos);
  CHECK(glb.find("\"irradianceCoefficients\"") != std::string::npos);
  // The probe in the box's middle cell row is invalid; the summary names it.
  const test::RunResult verbose = test::run_prt("probes " + scene + " --env " + sky() +
                                                " --grid 3,2,3 --rays 256 --surface-samples 64 --format prt -o " + dir + "/v.prtprobes");
  CHECK(verbose.output.find("inside geometry") != std::string::npos);
  const probes::ProbeSet baked = probes::read_probe_file(dir + "/out.prt");
  CHECK(baked.count() == 18);
  CHECK(baked.valid_count() < 18);

  const test::RunResult with_transfer = test::run_prt(base + "--transfer --format prt -o " + dir + "/t.prtprobes");
  REQUIRE(with_transfer.exit_code == 0);
  const test::RunResult relit = test::run_prt("probes-relight " + dir + "/t.prtprobes --env " + sky() +
                                              " --rotate 90,0,0 -q -o " + dir + "/r.prtprobes");
  INFO(relit.output);
  REQUIRE(relit.exit_code == 0);
  const probes::ProbeSet t = probes::read_probe_file(dir + "/t.prtprobes"), r = probes::read_probe_file(dir + "/r.prtprobes");
  CHECK(t.coefficients != r.coefficients);
  const test::RunResult no_transfer = test::run_prt("probes-relight " + dir + "/out.prt --env " + sky() + " -o " + dir + "/x.prtprobes");
  CHECK(no_transfer.exit_code == 1);
  CHECK(no_transfer.output.find("has no transfer") != std::string::npos);
}

TEST_CASE("prt probes-relight without --env re-exports a plain probe file as the bake would have", "[probes][cli]") {
  // Truth: the files `prt probes` writes directly in each format from the same bake (same seed, so the
  // same probes); the re-export from the plain .prtprobes must be the same bytes.
  const std::string dir = test::fresh_temp_dir("probe_cli_reexport");
  const std::string scene = write_scene(dir);
  const std::string base = "probes " + scene + " --env " + sky() + " --grid 3,2,3 --rays 256 --surface-samples 64 -q ";
  REQUIRE(test::run_prt(base + "--format prt -o " + dir + "/plain.prtprobes").exit_code == 0);
  for (const char* f : {"threejs", "unity", "godot", "filament", "bevy", "prt"}) {
    const test::RunResult direct = test::run_prt(base + "--format " + f + " -o " + dir + "/direct." + f);
    const test::RunResult again = test::run_prt("probes-relight " + dir + "/plain.prtprobes --format " + f + " -o " + dir + "/again." + f);
    INFO(f << ": " << direct.output << again.output);
    REQUIRE(direct.exit_code == 0);
    REQUIRE(again.exit_code == 0);
    CHECK(again.output.find("re-exported as baked") != std::string::npos);
    const std::string a = read_file(dir + "/direct." + f), b = read_file(dir + "/again." + f);
    CHECK(!a.empty());
    CHECK(a == b);
  }
  const test::RunResult rotate_alone = test::run_prt("probes-relight " + dir + "/plain.prtprobes --rotate 90,0,0 -o " + dir + "/x.json --format threejs");
  CHECK(rotate_alone.exit_code == 1);
  CHECK(rotate_alone.output == "prt: --rotate needs --env (the environment to rotate)\n");
  CHECK(!std::ifstream(dir + "/x.json").good());
}

TEST_CASE("prt probes lights probes with the scene's emission (OBJ/MTL Ke)", "[probes][cli]") {
  // A large emissive floor (Ke 1, Kd 0) under a black sky: a probe above it sees radiance 1 over the
  // lower hemisphere (all but the last 1e-4 radians above the horizon), so c_0 = 2 sqrt(pi) / 2 and
  // c_1 = integral over y < 0 of -0.4886 y = 0.4886 pi.
  const std::string dir = test::fresh_temp_dir("probe_cli_emission");
  write_text(dir, "glow.mtl", "newmtl glow\nKd 0 0 0\nKe 1 1 1\n");
  const std::string scene = write_text(dir, "glow.obj",
                                       "mtllib glow.mtl\nusemtl glow\nv -1e4 0 -1e4\nv 1e4 0 -1e4\nv 1e4 0 1e4\nv -1e4 0 1e4\n"
                                       "v 0 2 0\nf 1 3 2\nf 1 4 3\n");
  image::Image black(8, 4, 3);
  image::write(dir + "/black.exr", black);
  write_text(dir, "p.json", "[[0, 1, 0]]");
  const test::RunResult r = test::run_prt("probes " + scene + " --env " + dir + "/black.exr --points " + dir +
                                          "/p.json --bounces 0 --rays 4096 -q --format prt -o " + dir + "/e.prtprobes");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const probes::ProbeSet p = probes::read_probe_file(dir + "/e.prtprobes");
  CHECK(p.coefficients[0].x == Approx(std::sqrt(3.14159265358979323846)).epsilon(0.01));
  CHECK(p.coefficients[1].x == Approx(0.48860251 * 3.14159265358979323846).epsilon(0.01));
  CHECK(p.coefficients[3].x == Approx(0.0).margin(0.02));
}
