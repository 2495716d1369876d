// The glossy reference estimator against closed forms: normalized BRDFs under a constant environment,
// Lambert against the Lambertian estimator's answer, and the band-limited BRDF on a convex sphere under
// a band-limited environment against the exact SH product (no bake involved).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "brdf/brdf.h"
#include "brdf/frame.h"
#include "brdf/projection.h"
#include "core/error.h"
#include "image/image.h"
#include "light/projection.h"
#include "mesh/writers.h"
#include "reference/glossy_estimator.h"
#include "reference/reference.h"
#include "reference_test_util.h"
#include "sh/basis.h"
#include "sh/rotation.h"
#include "support/run_prt.h"
#include "support/shapes.h"
#include "trace/scene.h"

using namespace prt;

namespace {

reference::GlossyReferenceOptions glossy_options(const std::string& spec, int brdf_bands, int samples, const glm::dvec3& eye) {
  reference::GlossyReferenceOptions o;
  o.estimator.brdf = brdf::parse_brdf(spec);
  o.estimator.brdf_bands = brdf_bands;
  o.samples = samples;
  o.eye = eye;
  return o;
}

// A smooth, strongly varying environment: sky gradient plus a broad warm lobe toward (1, 1, 0.3).
light::Environment test_environment() {
  const glm::dvec3 lobe_axis = glm::normalize(glm::dvec3(1.0, 1.0, 0.3));
  return test::equirect_environment(128, 64, [&](int x, int y) {
    const glm::dvec3 d = light::equirect_direction((x + 0.5) / 128.0, (y + 0.5) / 64.0);
    const double lobe = std::pow(std::max(0.0, glm::dot(d, lobe_axis)), 4.0);
    return glm::dvec3(0.3 + 0.2 * d.y + 3.0 * lobe, 0.35 + 0.25 * d.y + 2.0 * lobe, 0.5 + 0.3 * d.y + 1.0 * lobe);
  });
}

}  // namespace

TEST_CASE("glossy reference under a constant environment: normalized BRDFs give their directional albedo", "[reference][glossy]") {
  // A plane seen along its normal: L_o = c * integral rho(w, n) dw, which is albedo for Lambert, ks for
  // normalized Phong at normal incidence (closed form), and 1 - ln 2 for GGX with alpha = 1 and F0 = 1.
  const mesh::Mesh plane = test::ground_grid(2);
  const reference::EnvironmentSampler env(test::constant_environment(glm::dvec3(2.0, 1.0, 0.5)));
  const struct {
    const char* spec;
    double albedo;
  } cases[] = {{"lambert:albedo=0.6", 0.6}, {"phong:exponent=30,ks=0.7", 0.7}, {"ggx:roughness=1,f0=1", 1.0 - std::log(2.0)}};
  for (const auto& c : cases) {
    std::vector<glm::vec3> error;
    const glm::dvec3 eye(0.0, 1e6, 0.0);  // far above: every view direction is the normal to 1e-6
    const std::vector<glm::vec3> r = reference::glossy_vertex_radiance(plane, env, glossy_options(c.spec, 0, 2048, eye), nullptr, &error);
    const std::size_t centre = 4;  // the middle vertex of the 3 x 3 grid
    INFO(c.spec);
    for (int ch = 0; ch < 3; ++ch)
      CHECK(r[centre][ch] == Approx(c.albedo * std::array<double, 3>{2.0, 1.0, 0.5}[ch]).margin(4 * error[centre][ch] + 1e-4));
  }
}

TEST_CASE("glossy reference with the band-limited BRDF on a sphere equals the exact SH product", "[reference][glossy]") {
  // No occlusion on a convex sphere: L_o(p, v) = integral over the SPHERE of L_N(w) rho_BL(w, v) dw,
  // which for the band-limited environment L_N (N bands) is sum_k (B Rot(F^T) L)_k Y_k(F^T v) exactly.
  const int bands = 4;
  const light::Environment full = test_environment();
  const sh::RgbCoefficients lighting = light::project(full, bands);
  const reference::EnvironmentSampler env(reference::band_limited_environment(full, bands));
  const mesh::Mesh sphere = test::uv_sphere(6, 12);
  for (const char* spec : {"phong:exponent=10,ks=0.6,kd=0.3", "ggx:roughness=0.5,f0=0.9/0.6/0.3"}) {
    const brdf::BrdfMatrix b = brdf::project(brdf::parse_brdf(spec), bands);
    const glm::dvec3 eye(0.5, 2.0, 3.0);
    std::vector<glm::vec3> error;
    const std::vector<glm::vec3> r = reference::glossy_vertex_radiance(sphere, env, glossy_options(spec, bands, 4096, eye), nullptr, &error);
    const int n = bands * bands;
    for (std::size_t v = 0; v < sphere.positions.size(); ++v) {
      const glm::dvec3 normal(sphere.normals[v]);
      const glm::dmat3 frame = brdf::shading_frame(normal);
      const sh::Rotation to_local(bands, glm::transpose(frame));
      std::vector<double> y(n);
      sh::eval(bands, glm::transpose(frame) * glm::normalize(eye - glm::dvec3(sphere.positions[v])), y.data());
      for (int c = 0; c < 3; ++c) {
        std::vector<double> world(n), local(n), out(n);
        for (int i = 0; i < n; ++i) world[i] = lighting.values[i][c];
        to_local.apply(world.data(), local.data());
        brdf::apply(b, b.channels == 3 ? c : 0, local.data(), out.data());
        double expected = 0.0;
        for (int k = 0; k < n; ++k) expected += out[k] * y[k];
        INFO(spec << " vertex " << v << " channel " << c << " +- " << error[v][c]);
        // 4 standard errors, plus the band-limited image's discretisation (reference.h: ~1e-4 relative).
        REQUIRE(r[v][c] == Approx(expected).margin(4 * error[v][c] + 2e-3 * std::abs(expected) + 1e-4));
      }
    }
  }
}

TEST_CASE("glossy reference: options are checked", "[reference][glossy]") {
  const mesh::Mesh plane = test::ground_grid(1);
  const reference::EnvironmentSampler env(test::constant_environment(glm::dvec3(1.0)));
  reference::GlossyReferenceOptions o = glossy_options("lambert", 0, 16, glm::dvec3(0, 1, 0));
  o.estimator.brdf_bands = 40;
  CHECK_THROWS_WITH(reference::glossy_vertex_radiance(plane, env, o), Catch::Contains("brdf_bands 40"));
  o.estimator.brdf_bands = 0;
  o.samples = 0;
  CHECK_THROWS_WITH(reference::glossy_vertex_radiance(plane, env, o), Catch::Contains("samples 0"));
  o.samples = 16;
  o.estimator.brdf = brdf::Brdf{};
  CHECK_THROWS_WITH(reference::glossy_vertex_radiance(plane, env, o), Catch::Contains("empty BRDF"));
}

TEST_CASE("prt reference --brdf --eye: per-vertex glossy radiance, misuse gives one line", "[reference][glossy][cli]") {
  const std::string dir = test::fresh_temp_dir("reference_glossy_cli");
  const mesh::Mesh plane = test::ground_grid(2);
  mesh::write_ply(dir + "/plane.ply", plane.positions, {}, plane.indices);
  image::write(dir + "/white.exr", test::constant_environment(glm::dvec3(1.0), 32, 16).equirect);
  const std::string base = "reference " + dir + "/plane.ply --env " + dir + "/white.exr --samples 256 -q ";
  // Phong at normal incidence under a white environment: ks (plane seen from far above).
  const test::RunResult ok = test::run_prt(base + "--brdf phong:exponent=10,ks=0.6 --eye 0,1000000,0 -o " + dir + "/out.ply");
  INFO(ok.output);
  REQUIRE(ok.exit_code == 0);
  const mesh::Mesh shaded = mesh::load_mesh(dir + "/out.ply", nullptr, true);
  REQUIRE(shaded.albedo.size() == 9);
  CHECK(shaded.albedo[4].r == Approx(0.6).margin(0.02));
  REQUIRE(test::run_prt(base + "--brdf phong:exponent=10,ks=0.6 --brdf-bands 5 --eye 0,3,1 -o " + dir + "/limited.ply").exit_code == 0);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {base + "--brdf lambert -o " + dir + "/x.ply", "--brdf needs --eye"},
      {base + "--eye 0,1,0 -o " + dir + "/x.ply", "--eye needs --brdf"},
      {base + "--brdf-bands 3 -o " + dir + "/x.ply", "--brdf-bands needs --brdf"},
      {base + "--brdf lambert --eye 0,1,0 --brdf-bands 40 -o " + dir + "/x.ply", "--brdf-bands: expected a band count"},
      {base + "--brdf lambert --eye 0,1,0 --albedo 0.5,0.5,0.5 -o " + dir + "/x.ply", "--albedo does not apply with --brdf"},
      {base + "--brdf lambert --eye 0,1,0 --image -o " + dir + "/x.png", "per vertex only"},
      {base + "--brdf velvet --eye 0,1,0 -o " + dir + "/x.ply", "unknown BRDF 'velvet'"},
      {base + "--brdf lambert --eye 0,1 -o " + dir + "/x.ply", "--eye: expected X,Y,Z"},
  };
  for (const auto& [arguments, expected] : cases) {
    const test::RunResult r = test::run_prt(arguments);
    INFO(arguments << "\n" << r.output);
    CHECK(r.exit_code == 1);
    CHECK(r.output.find(expected) != std::string::npos);
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
  }
}
