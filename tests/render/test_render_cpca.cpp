// The GPU's CPCA pass (renderer_cpca.h) computes `prt shade` of the compressed transfer at the
// vertices: headless renders of .cprt models against prt::shade of compress::decompress (diffuse:
// shade_diffuse; glossy: shade_glossy_eye toward the renderer's eye), interpolated perspective-
// correctly on the CPU (cpu_raster.h) for the triangle the GPU found at each pixel.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <glm/matrix.hpp>

#include "bake/bake.h"
#include "brdf/projection.h"
#include "compress/cprt_file.h"
#include "cpu_raster.h"
#include "lightmap_scenes.h"
#include "mesh/writers.h"
#include "render/headless_context.h"
#include "render/renderer.h"
#include "render/renderer_cpca.h"
#include "render/scene_inputs.h"
#include "render_fixtures.h"
#include "sh/rotation.h"
#include "shade/glossy.h"
#include "shade/shade.h"
#include "support/run_prt.h"

using namespace prt;
using namespace prt::render_test;

namespace {

constexpr int kWidth = 160, kHeight = 120;

transfer::TransferData baked(const mesh::Mesh& mesh, transfer::Kind kind, int bands, const std::string& spec) {
  bake::BakeOptions o;
  o.kind = kind;
  o.bands = bands;
  o.samples = 64;
  o.threads = 1;
  if (!spec.empty()) o.brdf = brdf::parse_brdf(spec);
  return bake::bake(mesh, o);
}

struct Case {
  const char* name;
  transfer::Kind kind;
  int bands, clusters, pca, truncate;
  const char* spec;
  glm::dvec3 environment_ypr, object_ypr;
};

}  // namespace

TEST_CASE("headless render of a .cprt model equals prt shade of the decompressed transfer at the vertices", "[render][gl][compress]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  const mesh::Mesh mesh = bumpy_sphere(16, 32, glm::vec3(0.2f, -0.1f, 0.1f));
  renderer.set_mesh(mesh);
  const Case cases[] = {
      {"diffuse shadowed, K 16, N 3", transfer::Kind::shadowed, 4, 16, 3, 0, "", {0, 0, 0}, {0, 0, 0}},
      {"diffuse, rotated lighting and object, truncated to 3 bands", transfer::Kind::shadowed, 4, 8, 2, 3, "", {40, 10, 0}, {-20, 30, 5}},
      {"glossy 5x5, K 16, N 4", transfer::Kind::glossy_shadowed, 5, 16, 4, 0, "phong:exponent=20,ks=0.5,kd=0.4", {0, 0, 0}, {0, 0, 0}},
      {"glossy RGB BRDF, rotated, truncated", transfer::Kind::glossy_shadowed, 4, 12, 3, 3,
       "ggx:roughness=0.4,f0=0.9/0.6/0.3,albedo=0.2/0.3/0.4", {70, 20, -10}, {-30, 15, 5}},
  };
  for (const Case& c : cases) {
    SECTION(c.name) {
      const transfer::TransferData original = baked(mesh, c.kind, c.bands, c.spec);
      const compress::CompressedTransfer model = compress::compress_transfer(original, {c.clusters, c.pca}, transfer::Scalar::float32, "test");
      const int index = renderer.add_compressed(model, "test");
      CHECK(renderer.is_compressed(index));
      const bool glossy = transfer::is_glossy(c.kind);
      brdf::BrdfMatrix b;
      if (glossy) {
        b = brdf::project(brdf::parse_brdf(c.spec), c.bands);
        renderer.set_brdf(index, b);
      }
      const sh::RgbCoefficients lighting = test_lighting(c.bands);
      renderer.set_lighting(lighting, nullptr);
      const render::FrameSettings settings = black_frame(index, c.truncate, c.environment_ypr, c.object_ypr);
      renderer.render(settings, kWidth, kHeight);
      const image::Image gpu = renderer.read_radiance();
      const std::vector<std::uint32_t> ids = renderer.read_triangle_ids();

      // prt shade of the .cprt (decompressed) under the lighting the object sees, per vertex.
      sh::RgbCoefficients seen =
          sh::Rotation(lighting.bands, glm::transpose(settings.object_rotation) * settings.environment_rotation).apply(lighting);
      if (c.truncate > 0) seen = seen.truncated(c.truncate);
      const transfer::TransferData approximate = compress::decompress(model);
      const render::ViewMatrices& view = renderer.last_view();
      const glm::vec3 eye_object(view.centre + glm::transpose(settings.object_rotation) * (view.eye - view.centre));
      const std::vector<glm::vec3> at_vertices = glossy ? shade::shade_glossy_eye(approximate, b, seen, mesh.positions, mesh.normals, eye_object)
                                                        : shade::shade_diffuse(approximate, seen);
      const image::Image cpu = interpolate_on_cpu(mesh, at_vertices, renderer.last_model_view_projection(), ids, kWidth, kHeight);
      double largest = 0.0;
      for (float v : cpu.pixels) largest = std::max(largest, std::abs(static_cast<double>(v)));
      std::size_t covered = 0;
      const double worst = max_relative_error(gpu, cpu, ids, 0.02 * largest, covered);
      INFO("covered pixels " << covered << ", max error relative to max(|cpu|, 2% of the largest) " << worst);
      CHECK(covered > static_cast<std::size_t>(kWidth * kHeight / 20));
      CHECK(largest > 0.05);
      CHECK(worst <= 1e-3);
    }
  }
}

TEST_CASE("prt render of a .cprt file equals the library's render of the model, and glossy without a BRDF is refused", "[render][gl][compress]") {
  const std::string dir = test::fresh_temp_dir("render_cpca_cli");
  write_fixture_files(dir);
  const mesh::Mesh loaded = mesh::load_mesh(dir + "/mesh.ply", nullptr, true);
  const std::string spec = "phong:exponent=10,ks=0.5,kd=0.4";
  const transfer::TransferData original = baked(loaded, transfer::Kind::glossy_shadowed, 3, spec);
  const compress::CompressedTransfer model = compress::compress_transfer(original, {8, 2}, transfer::Scalar::float32, "test");
  compress::write_cprt(dir + "/m.cprt", model);
  const test::RunResult r = test::run_prt("render " + dir + "/mesh.ply " + dir + "/m.cprt --env " + dir +
                                          "/light.json --background black --size 96x72 -q -o " + dir + "/out.exr");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const image::Image cli = image::read_rgb(dir + "/out.exr");

  render::HeadlessContext context;
  render::Renderer renderer;
  renderer.set_mesh(loaded);
  const int index = renderer.add_compressed(model, "test");
  render::FrameSettings settings;
  settings.transfer = index;
  settings.background = render::Background::black;
  renderer.set_lighting(test_lighting(3), nullptr);
  CHECK_THROWS_WITH(renderer.render(settings, 32, 24), Catch::Contains("has no BRDF matrix"));
  renderer.set_brdf(index, brdf::project(brdf::parse_brdf(spec), 3));
  renderer.render(settings, 96, 72);
  const image::Image library = renderer.read_radiance();
  REQUIRE(cli.pixels.size() == library.pixels.size());
  double worst = 0, total = 0;
  for (std::size_t i = 0; i < cli.pixels.size(); ++i) {
    worst = std::max(worst, static_cast<double>(std::abs(cli.pixels[i] - library.pixels[i])));
    total += library.pixels[i];
  }
  CHECK(total > 1.0);
  CHECK(worst <= 1e-6);
}
