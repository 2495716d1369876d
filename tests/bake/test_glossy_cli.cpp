// `prt bake --transfer glossy-*` and `prt shade --eye` through the real binary: outputs equal to the
// library's, float16 storage, one-line errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include "brdf/brdf.h"
#include "brdf/projection.h"
#include "core/atomic_file.h"
#include "light/light_file.h"
#include "mesh/mesh.h"
#include "mesh/writers.h"
#include "shade/glossy.h"
#include "support/run_prt.h"
#include "support/shapes.h"
#include "transfer/transfer_file.h"

using namespace prt;

namespace {

// A dim, directional-ish 3-band light (values of the shaded mesh stay inside [0, 1], which the PLY
// loader keeps as albedo).
std::string write_light(const std::string& dir) {
  sh::RgbCoefficients l(3);
  l.values[0] = glm::dvec3(0.5, 0.45, 0.4);
  l.values[2] = glm::dvec3(0.3, 0.25, 0.2);
  l.values[3] = glm::dvec3(-0.15, -0.1, -0.05);
  l.values[6] = glm::dvec3(0.05, 0.04, 0.03);
  const std::string path = dir + "/light.json";
  light::write_light_file(path, l, {});
  return path;
}

bool contains(const std::string& haystack, const std::string& needle) { return haystack.find(needle) != std::string::npos; }

}  // namespace

TEST_CASE("prt bake glossy and prt shade --eye match the library, float16 adds little", "[glossy][cli]") {
  const std::string dir = test::fresh_temp_dir("glossy_cli");
  const mesh::Mesh torus = test::torus(1.0f, 0.45f, 24, 12);
  const std::string mesh_path = dir + "/torus.ply";
  mesh::write_ply(mesh_path, torus.positions, {}, torus.indices);
  const std::string spec = "phong:exponent=12,ks=0.4,kd=0.4";
  const std::string common = "bake " + mesh_path + " --transfer glossy-interreflected --bounces 1 --brdf " + spec +
                             " --bands 3 --samples 64 -q";
  REQUIRE(test::run_prt(common + " --threads 1 -o " + dir + "/one.prt").exit_code == 0);
  REQUIRE(test::run_prt(common + " --threads 2 -o " + dir + "/two.prt").exit_code == 0);
  REQUIRE(test::run_prt(common + " --float16 -o " + dir + "/half.prt").exit_code == 0);
  CHECK(read_file(dir + "/one.prt") == read_file(dir + "/two.prt"));
  const test::RunResult info = test::run_prt("info " + dir + "/one.prt");
  CHECK(contains(info.output, "kind: glossy-interreflected"));
  CHECK(contains(info.output, "output bands: 3 (9 rows)"));

  const std::string light = write_light(dir);
  const test::RunResult shade = test::run_prt("shade " + mesh_path + " " + dir + "/one.prt --light " + light +
                                              " --eye 0,3,4 --window none -o " + dir + "/out.ply");
  INFO(shade.output);
  REQUIRE(shade.exit_code == 0);
  const mesh::Mesh shaded = mesh::load_mesh(dir + "/out.ply", nullptr, true);
  const mesh::Mesh loaded = mesh::load_mesh(mesh_path, nullptr, true);
  const transfer::TransferData transfer = transfer::read_transfer(dir + "/one.prt");
  const brdf::BrdfMatrix b = brdf::project(brdf::parse_brdf(spec), 3);
  const std::vector<glm::vec3> expected =
      shade::shade_glossy_eye(transfer, b, light::read_light_file(light), loaded.positions, loaded.normals, glm::vec3(0, 3, 4));
  REQUIRE(shaded.albedo.size() == expected.size());
  double largest = 0.0;
  for (std::size_t v = 0; v < expected.size(); ++v)
    for (int c = 0; c < 3; ++c) {
      REQUIRE(expected[v][c] < 1.0f);  // the PLY loader clamps colours to [0, 1]
      REQUIRE(shaded.albedo[v][c] == Approx(std::max(0.0f, expected[v][c])).margin(1e-6));
      largest = std::max(largest, static_cast<double>(expected[v][c]));
    }
  CHECK(largest > 0.1);

  // float16: the shaded radiance changes by well under 1% of its range.
  const transfer::TransferData half = transfer::read_transfer(dir + "/half.prt");
  CHECK(half.header.scalar == transfer::Scalar::float16);
  const std::vector<glm::vec3> from_half =
      shade::shade_glossy_eye(half, b, light::read_light_file(light), loaded.positions, loaded.normals, glm::vec3(0, 3, 4));
  double worst = 0.0;
  for (std::size_t v = 0; v < expected.size(); ++v)
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(static_cast<double>(from_half[v][c] - expected[v][c])));
  CHECK(worst < 2e-3 * largest);
}

TEST_CASE("glossy bake and shade errors are one line", "[glossy][cli]") {
  const std::string dir = test::fresh_temp_dir("glossy_cli_errors");
  const mesh::Mesh sphere = test::uv_sphere(6, 12);
  const std::string mesh_path = dir + "/sphere.ply";
  mesh::write_ply(mesh_path, sphere.positions, {}, sphere.indices);
  REQUIRE(test::run_prt("bake " + mesh_path + " --bands 3 --samples 16 -q -o " + dir + "/diffuse.prt").exit_code == 0);
  REQUIRE(test::run_prt("bake " + mesh_path + " --transfer glossy-shadowed --brdf lambert --bands 3 --samples 16 -q -o " + dir +
                        "/glossy.prt")
              .exit_code == 0);
  const std::string light = write_light(dir);
  const std::string out = dir + "/o.prt";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"bake " + mesh_path + " --transfer glossy-shadowed -o " + out, "has no materials, so glossy transfer needs --brdf"},
      {"bake " + mesh_path + " --transfer glossy-shadowed --brdf velvet -o " + out, "unknown BRDF 'velvet'"},
      {"bake " + mesh_path + " --transfer glossy-shadowed --brdf phong:exponent=-2 -o " + out, "out of range"},
      {"bake " + mesh_path + " --transfer glossy-shadowed --brdf lambert --bands 3 --bands-out 4 -o " + out, "--bands-out 4 is out of range"},
      {"bake " + mesh_path + " --transfer shadowed --brdf lambert -o " + out, "--brdf applies to glossy transfer only"},
      {"bake " + mesh_path + " --transfer glossy-shadowed --brdf lambert --gltf " + dir + "/x.glb -o " + out, "glTF export of glossy"},
      {"shade " + mesh_path + " " + dir + "/glossy.prt --light " + light + " -o " + dir + "/o.ply", "needs --eye"},
      {"shade " + mesh_path + " " + dir + "/diffuse.prt --light " + light + " --eye 0,0,3 -o " + dir + "/o.ply",
       "apply to glossy transfer"},
      {"shade " + mesh_path + " " + dir + "/glossy.prt --light " + light + " --eye 0,0 -o " + dir + "/o.ply", "--eye: expected X,Y,Z"},
      {"shade " + mesh_path + " " + dir + "/glossy.prt --light " + light + " --eye 0,0,3 --brdf ggx:roughness=2 -o " + dir + "/o.ply",
       "roughness 2 is out of range"},
  };
  for (const auto& [arguments, expected] : cases) {
    const test::RunResult r = test::run_prt(arguments);
    INFO(arguments << "\n" << r.output);
    CHECK(r.exit_code == 1);
    CHECK(contains(r.output, expected));
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
  }
}
