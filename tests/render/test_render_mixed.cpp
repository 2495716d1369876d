// A mixed scene drawn in one frame (Renderer::add_mixed, render/pass_mixed.cpp): the per-vertex pass
// draws the box's triangles, the lightmap pass the floor's and the wall's, into one frame with one depth
// buffer. Checked pixel by pixel against the two single-kind frames of the same renderer (each transfer
// drawing the whole mesh, as before mixed frames existed): every pixel has the triangle id of both
// single-kind frames, and the radiance of the frame of its triangle's kind, which part of the scene file
// names (the "Box" part of tests/lightmap/mixed_scenes.h, not the transfer files' runs), with the sky
// alone and with a sun (the per-vertex pass's deferred direct light, the lightmap's per-pixel one), and
// with a textured per-vertex share (base colour per pixel, the indexed draw vertices drawn by runs).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "camera/camera.h"
#include "light/disc.h"
#include "mesh/mesh.h"
#include "lightmap/mixed_scenes.h"  // tests/lightmap
#include "render/headless_context.h"
#include "render/mixed_frame.h"
#include "render/renderer.h"
#include "render/scene_inputs.h"
#include "render_fixtures.h"
#include "support/run_prt.h"

using namespace prt;
using Catch::Matchers::Contains;

namespace {

constexpr int kWidth = 160, kHeight = 120;

struct Frame {
  image::Image radiance;
  std::vector<std::uint32_t> ids;
};

Frame draw(render::Renderer& renderer, render::FrameSettings settings, int transfer) {
  settings.transfer = transfer;
  renderer.render(settings, kWidth, kHeight);
  return {renderer.read_radiance(), renderer.read_triangle_ids()};
}

// The scene's mixed pair, baked by `prt bake --texel-parts Floor,Wall`: returns the .prt path; `box`
// gets the box's triangles as the scene file's parts name them.
std::string bake_room(const std::string& dir, test::NamedPart& box) {
  std::vector<test::NamedPart> parts;
  test::write_gltf_parts(dir + "/room.gltf", test::room_with_box(true, parts), parts);
  for (const test::NamedPart& part : parts)
    if (part.name == "Box") box = part;
  const test::RunResult r = test::run_prt("bake " + dir + "/room.gltf --lightmap 64 --texel-parts Floor,Wall --transfer interreflected "
                                          "--bounces 1 --bands 3 --samples 32 -q -o " + dir + "/mixed.prt");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return dir + "/mixed.prt";
}

// Draws the mixed frame and both single-kind frames from `camera` and checks the mixed one pixel by
// pixel: the ids of the single-kind frames, and the radiance of the frame of each pixel's kind (the
// box's triangles per vertex, every other triangle per texel).
void check_one_frame(render::Renderer& renderer, const test::NamedPart& box, int mixed, int texel, int vertex, const char* camera,
                     bool with_sun) {
  render::FrameSettings settings = render_test::black_frame(0, 0, glm::dvec3(30.0, 0.0, 0.0), glm::dvec3(0.0));
  settings.camera = render::parse_camera(camera);
  settings.sun = with_sun;
  const Frame one = draw(renderer, settings, mixed);
  const Frame texels = draw(renderer, settings, texel);
  const Frame vertices = draw(renderer, settings, vertex);
  std::size_t box_pixels = 0, texel_pixels = 0, id_mismatches = 0;
  double worst = 0.0;  // largest |one - expected| / max(1, |expected|) over the channels
  for (std::size_t p = 0; p < one.ids.size(); ++p) {
    const std::uint32_t id = texels.ids[p];
    if (one.ids[p] != id || vertices.ids[p] != id) ++id_mismatches;
    const bool is_box = id != render::kNoTriangle && id >= box.first_triangle && id < box.first_triangle + box.triangle_count;
    if (id != render::kNoTriangle) ++(is_box ? box_pixels : texel_pixels);
    const image::Image& expected = is_box ? vertices.radiance : texels.radiance;
    for (int c = 0; c < 3; ++c) {
      const double e = expected.pixels[p * 3 + c], got = one.radiance.pixels[p * 3 + c];
      worst = std::max(worst, std::abs(got - e) / std::max(1.0, std::abs(e)));
    }
  }
  std::printf("mixed one frame, camera %s, sun %d: %zu box pixels, %zu texel pixels, %zu id mismatches, worst rel diff %.3g\n",
              camera, with_sun ? 1 : 0, box_pixels, texel_pixels, id_mismatches, worst);
  INFO("camera " << camera << ", sun " << with_sun);
  CHECK(box_pixels > 200);
  CHECK(texel_pixels > 2000);
  CHECK(id_mismatches == 0);
  CHECK(worst <= 1e-6);
}

}  // namespace

TEST_CASE("A mixed scene in one frame: each pixel is its triangle's kind's own frame, ids kept, sky and sun",
          "[render][gl][lightmap][mixed]") {
  const std::string dir = test::fresh_temp_dir("render_mixed_one_frame");
  test::NamedPart box;
  const std::string pair = bake_room(dir, box);
  const render::SceneInputs scene = render::load_scene(dir + "/room.gltf", render::mixed_transfer_paths(pair));
  REQUIRE(scene.transfers.size() == 2);

  render::HeadlessContext context;
  render::Renderer renderer;
  renderer.set_mesh(scene.mesh);
  const int texel = renderer.add(scene.transfers[0], nullptr, scene.transfer_paths[0]);
  const int vertex = renderer.add(scene.transfers[1], nullptr, scene.transfer_paths[1]);
  const int mixed = renderer.add_mixed(texel, vertex, render::mixed_vertex_runs(scene));
  renderer.set_lighting(render_test::test_lighting(3), nullptr);
  renderer.set_discs({light::parse_disc("0.6,0.55,0.45,3,2.6,2.2,3")});  // direction, E, radius in degrees

  // From the shadow side, and from behind the wall (its back hides part of the box: texel triangles
  // drawn after the box's pixels, over them).
  for (const char* camera : {"215,50,auto", "20,15,auto"})
    for (bool with_sun : {false, true}) check_one_frame(renderer, box, mixed, texel, vertex, camera, with_sun);
}

TEST_CASE("A mixed scene in one frame with a textured per-vertex share: the base colour per pixel, drawn by runs",
          "[render][gl][lightmap][mixed][texture]") {
  const std::string dir = test::fresh_temp_dir("render_mixed_textured");
  test::NamedPart box;
  const std::string pair = bake_room(dir, box);
  render::SceneInputs scene = render::load_scene(dir + "/room.gltf", render::mixed_transfer_paths(pair));
  // A 2 x 2 texture of four colours over the mesh at its lightmap UVs (the textured draw of the
  // per-vertex pass: indexed draw vertices, BaseColour::draw_corners).
  mesh::Mesh& m = scene.mesh;
  mesh::Texture texture;
  texture.width = texture.height = 2;
  texture.rgb = {0.9f, 0.2f, 0.1f, 0.1f, 0.8f, 0.2f, 0.2f, 0.3f, 0.9f, 0.9f, 0.9f, 0.2f};
  m.textures = {texture};
  mesh::Material material;
  material.base_color.image = 0;
  material.base_color.filter = mesh::Filter::nearest;
  m.materials = {material};
  m.triangle_material.assign(m.triangle_count(), 0);
  m.base_color_uv = m.lightmap_uv;

  render::HeadlessContext context;
  render::Renderer renderer;
  renderer.set_mesh(m);
  const int texel = renderer.add(scene.transfers[0], nullptr, scene.transfer_paths[0]);
  const int vertex = renderer.add(scene.transfers[1], nullptr, scene.transfer_paths[1]);
  const int mixed = renderer.add_mixed(texel, vertex, render::mixed_vertex_runs(scene));
  renderer.set_textured(mixed, true);  // both shares; the lightmap pass ignores it
  renderer.set_lighting(render_test::test_lighting(3), nullptr);
  renderer.set_discs({light::parse_disc("0.6,0.55,0.45,3,2.6,2.2,3")});
  for (bool with_sun : {false, true}) check_one_frame(renderer, box, mixed, texel, vertex, "215,50,auto", with_sun);
  // The texture shows on the box: its pixels differ from the same frame untextured.
  render::FrameSettings settings = render_test::black_frame(0, 0, glm::dvec3(30.0, 0.0, 0.0), glm::dvec3(0.0));
  settings.camera = render::parse_camera("215,50,auto");
  const Frame textured = draw(renderer, settings, mixed);
  renderer.set_textured(mixed, false);
  const Frame plain = draw(renderer, settings, mixed);
  std::size_t changed = 0;
  for (std::size_t p = 0; p < plain.ids.size(); ++p)
    if (plain.ids[p] >= box.first_triangle && plain.ids[p] < box.first_triangle + box.triangle_count &&
        std::abs(textured.radiance.pixels[3 * p] - plain.radiance.pixels[3 * p]) > 1e-3f)
      ++changed;
  CHECK(changed > 500);
}

TEST_CASE("Renderer::add_mixed refuses shares of the wrong kind and runs outside the mesh", "[render][gl][lightmap][mixed]") {
  const std::string dir = test::fresh_temp_dir("render_mixed_refused");
  test::NamedPart box;
  const std::string pair = bake_room(dir, box);
  const render::SceneInputs scene = render::load_scene(dir + "/room.gltf", render::mixed_transfer_paths(pair));
  render::HeadlessContext context;
  render::Renderer renderer;
  renderer.set_mesh(scene.mesh);
  const int texel = renderer.add(scene.transfers[0], nullptr, scene.transfer_paths[0]);
  const int vertex = renderer.add(scene.transfers[1], nullptr, scene.transfer_paths[1]);
  const render::TriangleRuns runs = render::mixed_vertex_runs(scene);
  CHECK_THROWS_WITH(renderer.add_mixed(vertex, texel, runs), Contains("the texel share must be an uncompressed lightmap"));
  CHECK_THROWS_WITH(renderer.add_mixed(texel, texel, runs), Contains("the per-vertex share must be"));
  const std::uint64_t triangles = scene.mesh.triangle_count();
  CHECK_THROWS_WITH(renderer.add_mixed(texel, vertex, {{triangles - 1, 2}}), Contains("inside the mesh's"));
  CHECK_THROWS_WITH(renderer.add_mixed(texel, vertex, {{4, 2}, {2, 1}}), Contains("increasing, disjoint"));
  CHECK(renderer.transfer_count() == 2);
  CHECK(renderer.add_mixed(texel, vertex, runs) == 2);
}

TEST_CASE("complement_runs: the triangles the runs leave out", "[render][mixed]") {
  using R = render::TriangleRuns;
  CHECK(render::complement_runs(R{{2, 12}}, 16) == R{{0, 2}, {14, 2}});
  CHECK(render::complement_runs(R{}, 5) == R{{0, 5}});
  CHECK(render::complement_runs(R{{0, 5}}, 5) == R{});
  CHECK(render::complement_runs(R{{0, 1}, {3, 1}}, 4) == R{{1, 2}});
}
