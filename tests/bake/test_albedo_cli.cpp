// Textured albedo through the real binary: `prt bake` then `prt shade` per vertex on a checker quad
// (OBJ + MTL map_Kd) under constant light equals the exact footprint averages of the checker; `prt info`
// names the albedo source; `--albedo` overrides the file's textures with a note.
#include <catch2/catch.hpp>

#include <fstream>

#include "image/image.h"
#include "mesh/writers.h"
#include "support/run_prt.h"

using namespace prt;

namespace {

bool contains(const std::string& haystack, const std::string& needle) { return haystack.find(needle) != std::string::npos; }

const glm::dvec3 kA(0.8, 0.3, 0.1), kB(0.1, 0.5, 0.9);  // linear; written as float PNG values sRGB-encoded below

double encode_srgb(double x) { return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055; }

// A 64 x 64 PNG of 32 x 32-texel squares (kA where px / 32 + py / 32 is even) and the unit quad in z = 0
// with vt = (x, y), map_Kd clamped to the edge. The 8-bit quantisation moves each colour by less than
// 0.2% of its value: the expected values below use the decoded codes.
std::string write_checker_quad(const std::string& dir, glm::dvec3* a, glm::dvec3* b) {
  image::Image png(64, 64, 3);
  auto quantised = [](const glm::dvec3& c) {
    glm::dvec3 out;
    for (int k = 0; k < 3; ++k) {
      const double code = std::round(encode_srgb(c[k]) * 255.0) / 255.0;
      out[k] = code <= 0.04045 ? code / 12.92 : std::pow((code + 0.055) / 1.055, 2.4);
    }
    return out;
  };
  *a = quantised(kA);
  *b = quantised(kB);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) png.at(x, y, c) = float(encode_srgb(((x / 32 + y / 32) % 2 == 0 ? kA : kB)[c]));
  image::write(dir + "/checker.png", png);
  std::ofstream(dir + "/quad.mtl") << "newmtl checker\nKd 1 1 1\nmap_Kd -clamp on checker.png\n";
  std::ofstream(dir + "/quad.obj") << "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                      "vn 0 0 1\nusemtl checker\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n";
  std::ofstream(dir + "/white.json") << R"({"bands": 1, "basis": "real-orthonormal-condon-shortley", "index": "l*(l+1)+m",
           "frame": "right-handed, +Y up", "coefficients": [[3.5449077018, 3.5449077018, 3.5449077018]]})";
  return dir + "/quad.obj";
}

struct BakeAndShade {
  test::RunResult bake, info;
  mesh::ColourPly shaded;
};

// prt bake (unshadowed, 1 band, `options` added), prt info of the transfer, prt shade under white.json.
BakeAndShade bake_and_shade(const std::string& dir, const std::string& obj, const std::string& options) {
  BakeAndShade out;
  out.bake = test::run_prt("bake " + obj + " --transfer unshadowed --bands 1 " + options + " -o " + dir + "/t.prt");
  REQUIRE(out.bake.exit_code == 0);
  out.info = test::run_prt("info " + dir + "/t.prt");
  REQUIRE(test::run_prt("shade " + obj + " " + dir + "/t.prt --light " + dir + "/white.json -o " + dir + "/s.ply").exit_code == 0);
  out.shaded = mesh::read_ply_colours(dir + "/s.ply");
  REQUIRE(out.shaded.colours.size() == 4);
  return out;
}

}  // namespace

TEST_CASE("prt shade per vertex on a textured checker quad equals the footprint average", "[bake][cli][albedo]") {
  const std::string dir = test::fresh_temp_dir("albedo_checker");
  glm::dvec3 a, b;
  const std::string obj = write_checker_quad(dir, &a, &b);
  const BakeAndShade run = bake_and_shade(dir, obj, "-q");
  CHECK(contains(run.info.output, R"("albedo":"mesh","albedo_source":"texture")"));
  const mesh::ColourPly& shaded = run.shaded;
  // vt = (x, y) is v up: image row py sits at y = 1 - py / 64, so the quad's squares [0, 1/2]^2 and
  // [1/2, 1]^2 (the diagonal squares) show kB. Under constant radiance 1 an unshadowed vertex reflects
  // its albedo. The exact hat-weighted footprint averages (derived in tests/mesh/test_texture.cpp), D
  // the diagonal squares' colour and O the others': (5 D + 3 O) / 8 at (0,0) and (1,1), (D + 3 O) / 4
  // at (1,0) and (0,1).
  const glm::dvec3 want[4] = {(5.0 * b + 3.0 * a) / 8.0, (b + 3.0 * a) / 4.0, (5.0 * b + 3.0 * a) / 8.0, (b + 3.0 * a) / 4.0};
  for (int v = 0; v < 4; ++v)
    for (int c = 0; c < 3; ++c) CHECK(double(shaded.colours[v][c]) == Approx(want[v][c]).epsilon(0.01));
}

TEST_CASE("prt bake --albedo overrides the file's textures with a note, and prt info says so", "[bake][cli][albedo]") {
  const std::string dir = test::fresh_temp_dir("albedo_override");
  glm::dvec3 a, b;
  const std::string obj = write_checker_quad(dir, &a, &b);
  const BakeAndShade run = bake_and_shade(dir, obj, "--albedo 0.5,0.25,1");
  CHECK(contains(run.bake.output, obj + ": --albedo 0.5,0.25,1 overrides the file's texture albedo"));
  CHECK(contains(run.info.output, R"("albedo":[0.5,0.25,1.0],"albedo_source":"option")"));
  const mesh::ColourPly& shaded = run.shaded;
  for (int v = 0; v < 4; ++v) {
    CHECK(shaded.colours[v][0] == Approx(0.5).epsilon(1e-5));
    CHECK(shaded.colours[v][1] == Approx(0.25).epsilon(1e-5));
    CHECK(shaded.colours[v][2] == Approx(1.0).epsilon(1e-5));
  }
}
