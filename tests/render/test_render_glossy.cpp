// The GPU's glossy PRT pass computes what the CPU does: headless renders of glossy transfers against
// prt::shade::glossy_outgoing_coefficients (the O of `prt shade`) evaluated on the CPU, pixel by pixel,
// with the same camera convention: for the point p the CPU's own ray through the pixel centre meets
// (cpu_raster.h, barycentrics b), the view v = normalize(eye - p) in mesh coordinates, and
// sum_i b_i sum_k O_i[k] Y_k(F_i^T v) in each corner's own frame (renderer.h, prt_glossy). At a vertex
// that is exactly prt shade's radiance toward the eye.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include "bake/bake.h"
#include "cpu_raster.h"
#include "brdf/brdf.h"
#include "brdf/frame.h"
#include "brdf/projection.h"
#include "render/headless_context.h"
#include "render/renderer.h"
#include "render_fixtures.h"
#include "sh/basis.h"
#include "sh/rotation.h"
#include "shade/glossy.h"
#include "support/run_prt.h"

using namespace prt;
using namespace prt::render_test;

namespace {

constexpr int kWidth = 160, kHeight = 120;
// GPU (float) against the CPU's double ray and double SH evaluation.
constexpr double kGlossyTolerance = 2e-5;

// The CPU reference image (see the top of this file) at the surface points the CPU's own rays met
// (cpu_raster.h: no GPU matrix, no triangle ids); pixels without a hit stay 0.
image::Image glossy_on_cpu(const mesh::Mesh& mesh, const std::vector<glm::vec3>& outgoing, int out_bands,
                           const glm::dvec3& eye_object, const std::vector<PixelHit>& hits) {
  image::Image out(kWidth, kHeight, 3);
  const int n = out_bands * out_bands;
  std::vector<double> y(static_cast<std::size_t>(n));
  for (int py = 0; py < kHeight; ++py)
    for (int px = 0; px < kWidth; ++px) {
      const PixelHit& h = hits[static_cast<std::size_t>(py) * kWidth + px];
      if (h.triangle == render::kNoTriangle) continue;
      const glm::dvec3 view = glm::normalize(eye_object - h.point);
      glm::dvec3 value(0.0);
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t corner = mesh.indices[3 * h.triangle + k];
        const glm::dmat3 frame = brdf::shading_frame(glm::dvec3(mesh.normals[corner]));
        sh::eval(out_bands, glm::transpose(frame) * view, y.data());
        glm::dvec3 radiance(0.0);
        for (int i = 0; i < n; ++i) radiance += y[static_cast<std::size_t>(i)] * glm::dvec3(outgoing[corner * n + i]);
        value += h.b[k] * radiance;
      }
      for (int c = 0; c < 3; ++c) out.at(px, py, c) = static_cast<float>(value[c]);
    }
  return out;
}

transfer::TransferData glossy_transfer(const mesh::Mesh& mesh, transfer::Kind kind, int bands, int bands_out, const std::string& spec) {
  bake::BakeOptions o;
  o.kind = kind;
  o.bands = bands;
  o.bands_out = bands_out;
  o.samples = 64;
  o.bounces = 1;
  o.brdf = brdf::parse_brdf(spec);
  o.threads = 1;
  return bake::bake(mesh, o);
}

struct Case {
  const char* name;
  transfer::Kind kind;
  int bands, bands_out, truncate;
  const char* spec;
  render::Camera camera;
  glm::dvec3 environment_ypr, object_ypr;
  std::size_t max_range_bytes;
};

}  // namespace

TEST_CASE("headless glossy render equals prt shade's outgoing coefficients evaluated toward the eye", "[render][gl][glossy]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  const mesh::Mesh mesh = bumpy_sphere(16, 32, glm::vec3(0.2f, -0.1f, 0.1f));
  renderer.set_mesh(mesh);
  const Case cases[] = {
      {"5x5 grey, auto camera", transfer::Kind::glossy_shadowed, 5, 5, 0, "phong:exponent=20,ks=0.5,kd=0.4", render::Camera{},
       {0, 0, 0}, {0, 0, 0}, 0},
      {"RGB interreflected 4x4, rotated lighting and object", transfer::Kind::glossy_interreflected, 4, 4, 0,
       "ggx:roughness=0.4,f0=0.9/0.6/0.3,albedo=0.2/0.3/0.4", render::Camera{35.0, 25.0, 4.0}, {70, 20, -10}, {-30, 15, 5}, 0},
      {"9x25 non-square, lighting truncated to 4 bands", transfer::Kind::glossy_shadowed, 5, 3, 4, "blinn:exponent=30,ks=0.6,kd=0.3",
       render::Camera{-120.0, -30.0, 0.0}, {10, 0, 0}, {0, 40, 0}, 0},
      {"split over 4 buffer-texture views", transfer::Kind::glossy_shadowed, 3, 3, 0, "phong:exponent=8,kd=0.5,ks=0.5",
       render::Camera{200.0, 60.0, 3.5}, {0, 0, 90}, {0, 0, 0}, 40000},
  };
  for (const Case& c : cases) {
    SECTION(c.name) {
      const transfer::TransferData transfer = glossy_transfer(mesh, c.kind, c.bands, c.bands_out, c.spec);
      const int index = renderer.add_transfer(transfer, "test", c.max_range_bytes);
      const brdf::BrdfMatrix b = brdf::project(brdf::parse_brdf(c.spec), c.bands_out);
      renderer.set_brdf(index, b);
      const sh::RgbCoefficients lighting = test_lighting(c.bands);
      renderer.set_lighting(lighting, nullptr);

      render::FrameSettings settings = black_frame(index, c.truncate, c.environment_ypr, c.object_ypr);
      settings.camera = c.camera;
      renderer.render(settings, kWidth, kHeight);
      const image::Image gpu = renderer.read_radiance();

      // The lighting the object sees (double rotation), truncated as the renderer does.
      sh::RgbCoefficients seen =
          sh::Rotation(lighting.bands, glm::transpose(settings.object_rotation) * settings.environment_rotation).apply(lighting);
      if (c.truncate > 0) seen = seen.truncated(c.truncate);
      const std::vector<glm::vec3> outgoing = shade::glossy_outgoing_coefficients(transfer, b, seen);
      glm::dvec3 eye_object;
      const std::vector<PixelHit> hits = cast_pixels(mesh, c.camera.azimuth_degrees, c.camera.elevation_degrees,
                                                     c.camera.distance, settings.object_rotation, kWidth, kHeight, &eye_object);
      const image::Image cpu = glossy_on_cpu(mesh, outgoing, c.bands_out, eye_object, hits);
      double largest = 0.0;
      for (float v : cpu.pixels) largest = std::max(largest, std::abs(static_cast<double>(v)));
      std::size_t covered = 0;
      const double worst = max_relative_error_interior(gpu, cpu, hits, 0.02 * largest, covered);
      INFO("compared pixels " << covered << ", max error relative to max(|cpu|, 2% of the largest) " << worst);
      CHECK(covered > static_cast<std::size_t>(kWidth * kHeight / 20));
      CHECK(worst <= kGlossyTolerance);
    }
  }
}

TEST_CASE("a new BRDF matrix changes the glossy render (live edits) and mismatched ones are refused", "[render][gl][glossy]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  const mesh::Mesh mesh = bumpy_sphere(12, 24);
  renderer.set_mesh(mesh);
  const transfer::TransferData transfer = glossy_transfer(mesh, transfer::Kind::glossy_shadowed, 3, 3, "lambert");
  const int index = renderer.add_transfer(transfer, "test");
  renderer.set_lighting(test_lighting(3), nullptr);
  render::FrameSettings settings;
  settings.transfer = index;
  settings.background = render::Background::black;
  CHECK_THROWS_WITH(renderer.render(settings, 64, 48), Catch::Contains("has no BRDF matrix"));
  CHECK_THROWS_WITH(renderer.set_brdf(index, brdf::project(brdf::parse_brdf("lambert"), 4)), Catch::Contains("output 3"));
  renderer.set_brdf(index, brdf::project(brdf::parse_brdf("lambert:albedo=0.5"), 3));
  renderer.render(settings, 64, 48);
  const image::Image half = renderer.read_radiance();
  renderer.set_brdf(index, brdf::project(brdf::parse_brdf("lambert:albedo=1"), 3));
  renderer.render(settings, 64, 48);
  const image::Image full = renderer.read_radiance();
  // Lambert B is linear in the albedo: every covered pixel doubles.
  const std::vector<std::uint32_t> ids = renderer.read_triangle_ids();
  std::size_t covered = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      if (ids[static_cast<std::size_t>(y) * 64 + x] == render::kNoTriangle) continue;
      ++covered;
      for (int c = 0; c < 3; ++c) REQUIRE(full.at(x, y, c) == Approx(2.0 * half.at(x, y, c)).epsilon(1e-5).margin(1e-6));
    }
  CHECK(covered > 100);
  // A diffuse transfer takes no BRDF.
  const int diffuse = renderer.add_transfer(unshadowed_transfer(mesh, 3, 1, glm::vec3(0.5f)), "diffuse");
  CHECK_THROWS_WITH(renderer.set_brdf(diffuse, brdf::project(brdf::parse_brdf("lambert"), 3)), Catch::Contains("needs a glossy transfer"));
}

TEST_CASE("prt render draws glossy transfer, --brdf errors are one line", "[render][gl][glossy][cli]") {
  const std::string dir = test::fresh_temp_dir("render_glossy_cli");
  write_fixture_files(dir);
  const std::string mesh = dir + "/mesh.ply", env = " --env " + dir + "/env.exr --size 64x48 -q";
  REQUIRE(test::run_prt("bake " + mesh + " --transfer glossy-shadowed --brdf phong:exponent=20,kd=0.3 --bands 3 --samples 16 -q -o " +
                        dir + "/glossy.prt")
              .exit_code == 0);
  const test::RunResult ok = test::run_prt("render " + mesh + " " + dir + "/glossy.prt" + env + " -o " + dir + "/glossy.exr");
  INFO(ok.output);
  CHECK(ok.exit_code == 0);
  const image::Image shot = image::read_rgb(dir + "/glossy.exr");
  CHECK(shot.width == 64);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"render " + mesh + " " + dir + "/transfer.prt --brdf lambert" + env + " -o " + dir + "/x.exr", "--brdf applies to glossy"},
      {"render " + mesh + " " + dir + "/glossy.prt --brdf velvet" + env + " -o " + dir + "/x.exr", "unknown BRDF 'velvet'"},
  };
  for (const auto& [arguments, expected] : cases) {
    const test::RunResult r = test::run_prt(arguments);
    INFO(arguments << "\n" << r.output);
    CHECK(r.exit_code == 1);
    CHECK(r.output.find(expected) != std::string::npos);
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
  }
}
