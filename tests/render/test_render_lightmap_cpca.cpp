// A compressed lightmap (texel .cprt) drawn compressed (render/pass_lightmap_cpca.cpp: texels shaded from
// the per-cluster products once per lighting change, a coverage-aware mip chain built on the GPU)
// against the same model decompressed (compress::decompress) and drawn by the uncompressed lightmap
// pass (texture arrays of the reconstructed texel blocks, their mip chain built on the CPU,
// lightmap_mips.h): the same pixels up to float rounding, in the camera's view (near and minified,
// rotated lighting, run-time band truncation), in texel space, and with a disc (its bounce light through
// the model's bounce-only part, its direct light per pixel). Both paths are independent code from the
// products on: the GPU blend and mip shaders here, the CPU reconstruction and mips there.
// A texel .cprt baked and compressed by the CLI, real interreflected transfer of a box on a floor.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "compress/compressed.h"
#include "compress/cprt_file.h"
#include "light/disc.h"
#include "lightmap_scenes.h"
#include "render/headless_context.h"
#include "render/renderer.h"
#include "render/renderer_cpca.h"
#include "render/scene_inputs.h"
#include "render_fixtures.h"
#include "support/run_prt.h"

using namespace prt;
using namespace prt::render_test;

namespace {

struct Frames {
  image::Image compressed, decompressed;
  std::vector<std::uint32_t> ids;
};

// Renders transfers `a` and `b` with the same settings (camera view, or texel space when `texels`).
Frames render_both(render::Renderer& renderer, int a, int b, render::FrameSettings settings, bool texels) {
  Frames out;
  for (int index : {a, b}) {
    settings.transfer = index;
    if (texels)
      renderer.render_texels(settings);
    else
      renderer.render(settings, 160, 120);
    (index == a ? out.compressed : out.decompressed) = renderer.read_radiance();
  }
  out.ids = renderer.read_triangle_ids();
  return out;
}

// Largest |compressed - decompressed| over the drawn pixels, relative to the largest decompressed value.
double relative_max_difference(const Frames& f, std::size_t& drawn) {
  double largest = 0.0, worst = 0.0;
  drawn = 0;
  for (std::size_t p = 0; p < f.ids.size(); ++p) {
    if (f.ids[p] == render::kNoTriangle) continue;
    ++drawn;
    for (int c = 0; c < 3; ++c) {
      const double d = f.decompressed.pixels[3 * p + c];
      largest = std::max(largest, std::abs(d));
      worst = std::max(worst, std::abs(static_cast<double>(f.compressed.pixels[3 * p + c]) - d));
    }
  }
  return largest > 0.0 ? worst / largest : 1.0;
}

}  // namespace

TEST_CASE("a compressed lightmap drawn compressed equals its decompressed texels drawn by the lightmap pass",
          "[render][gl][compress][lightmap]") {
  const std::string dir = test::fresh_temp_dir("render_lightmap_cpca");
  const mesh::Mesh scene_mesh = test::floor_and_box(true);
  test::write_obj_with_uv(dir + "/s.obj", scene_mesh);
  REQUIRE(test::run_prt("bake " + dir + "/s.obj --lightmap 40 --transfer interreflected --bands 6 --samples 64 --quiet -o " + dir +
                        "/lm.cprt --compress 6,3 --float16")
              .exit_code == 0);
  const render::SceneInputs scene = render::load_scene(dir + "/s.obj", {dir + "/lm.cprt"});
  REQUIRE(scene.compressed.size() == 1);
  REQUIRE(scene.compressed[0] != nullptr);  // kept as a model: no texels decompressed on load
  const compress::CompressedTransfer& model = *scene.compressed[0];
  REQUIRE(model.bounce);
  const transfer::TransferData decompressed = compress::decompress(model);

  render::HeadlessContext context;
  render::Renderer renderer;
  renderer.set_mesh(scene.mesh);
  const int a = render::add_scene_transfer(renderer, scene, 0);
  const int b = renderer.add_lightmap(decompressed, "decompressed");
  CHECK(renderer.is_lightmap(a));
  CHECK_FALSE(renderer.is_compressed(a));
  for (int index : {a, b}) renderer.set_surface_albedo(index, std::vector<glm::vec3>(scene.mesh.vertex_count(), glm::vec3(0.6f, 0.5f, 0.4f)));
  renderer.set_lighting(test_lighting(6), nullptr);
  light::Disc disc;
  disc.direction = glm::normalize(glm::dvec3(0.4, 0.8, 0.3));
  disc.irradiance = glm::dvec3(4.0, 3.5, 3.0);
  disc.angular_radius = 0.02;

  struct Case {
    const char* name;
    int bands;
    double distance;
    bool disc, texels;
  };
  const Case cases[] = {{"camera view, all 6 bands", 0, 0.0, false, false}, {"truncated to 4 bands", 4, 0.0, false, false},
                        {"minified (far camera: the mip chains)", 0, 25.0, false, false}, {"with a disc", 0, 0.0, true, false},
                        {"texel space, with a disc", 0, 0.0, true, true}, {"texel space, 2 bands", 2, 0.0, false, true}};
  for (const Case& c : cases) {
    SECTION(c.name) {
      renderer.set_discs(c.disc ? std::vector<light::Disc>{disc} : std::vector<light::Disc>{});
      render::FrameSettings settings = black_frame(a, c.bands, {35, 15, 0}, {-20, 0, 10});
      settings.camera.azimuth_degrees = 30;
      settings.camera.elevation_degrees = 35;
      settings.camera.distance = c.distance;
      const Frames f = render_both(renderer, a, b, settings, c.texels);
      std::size_t drawn = 0;
      const double worst = relative_max_difference(f, drawn);
      std::printf("compressed lightmap vs decompressed, %s: %zu pixels, max |difference| %.3g of the largest value\n", c.name, drawn,
                  worst);
      CHECK(drawn > (c.distance > 0.0 ? 40u : 400u));
      CHECK(worst <= 1e-5);  // float rounding (measured <= 8.2e-7): the order of the sums differs
    }
  }
}

TEST_CASE("a compressed lightmap's viewer label names its model and the GPU's shaded lightmap", "[render][compress][lightmap]") {
  const std::string dir = test::fresh_temp_dir("render_cpca_lightmap_label");
  test::write_obj_with_uv(dir + "/s.obj", test::floor_and_box(true));
  REQUIRE(test::run_prt("bake " + dir + "/s.obj --lightmap 24 --transfer shadowed --bands 3 --samples 32 --quiet -o " + dir + "/lm.prt")
              .exit_code == 0);
  REQUIRE(test::run_prt("compress " + dir + "/lm.prt --clusters 6 --pca 2 -q -o " + dir + "/lm.cprt").exit_code == 0);
  const render::SceneInputs scene = render::load_scene(dir + "/s.obj", {dir + "/lm.cprt", dir + "/lm.prt"});
  REQUIRE(scene.compressed.size() == 2);
  REQUIRE(scene.compressed[0] != nullptr);
  CHECK(scene.compressed[1] == nullptr);
  CHECK(scene.transfers[0].header.is_texel());
  CHECK(scene.transfers[0].values.empty());  // the header only: the model is drawn
  const std::string label = render::transfer_memory_label(scene, 0);
  INFO(label);
  CHECK(label.find(", CPCA K 6 N 2, ") != std::string::npos);
}
