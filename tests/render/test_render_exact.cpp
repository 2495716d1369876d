// The GPU computes what the CPU does: headless renders against prt::shade::shade_diffuse interpolated at
// the surface point each pixel's ray meets, found on the CPU from the camera convention alone (no GPU
// matrix, no triangle-id buffer: cpu_raster.h); the SH and
// image backgrounds against prt::sh::eval and Environment::radiance, the tone map pass against
// prt::image::to_display.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "core/constants.h"
#include "cpu_raster.h"
#include "light/environment.h"
#include "render/headless_context.h"
#include "render/renderer.h"
#include "render_fixtures.h"
#include "shade/shade.h"
#include "sh/basis.h"
#include "sh/rotation.h"
#include "support/random_draws.h"

using namespace prt;
using namespace prt::render_test;

namespace {

constexpr int kWidth = 160, kHeight = 120;
// GPU (float rasteriser, perspective-correct interpolation) against the double ray: docs/conventions.md.
constexpr double kExactTolerance = 2e-5;

// The lighting the object sees: the environment's, rotated by R_object^-1 R_environment (in double,
// through prt::sh::Rotation, not the renderer's float fast path).
sh::RgbCoefficients object_frame_lighting(const sh::RgbCoefficients& lighting, const glm::dmat3& environment_rotation,
                                          const glm::dmat3& object_rotation) {
  const sh::Rotation rotation(lighting.bands, glm::transpose(object_rotation) * environment_rotation);
  return rotation.apply(lighting);
}

struct Case {
  const char* name;
  int bands, channels, truncate;
  render::Camera camera;
  glm::dvec3 environment_ypr, object_ypr;
  std::size_t max_range_bytes;  // 0: the implementation's buffer-texture limit
};

}  // namespace

TEST_CASE("headless PRT render equals the CPU shading rasterised with the same camera", "[render][gl]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  const mesh::Mesh mesh = bumpy_sphere(20, 40, glm::vec3(0.3f, -0.2f, 0.1f));
  renderer.set_mesh(mesh);

  const Case cases[] = {
      {"5 bands RGB, auto camera", 5, 3, 0, render::Camera{}, {0, 0, 0}, {0, 0, 0}, 0},
      {"5 bands RGB, orbit, rotated lighting and object", 5, 3, 0, render::Camera{35.0, 25.0, 4.0}, {70, 20, -10},
       {-30, 15, 5}, 0},
      {"6 bands RGB truncated to 3", 6, 3, 3, render::Camera{-120.0, -30.0, 0.0}, {10, 0, 0}, {0, 40, 0}, 0},
      {"4 bands grey", 4, 1, 0, render::Camera{200.0, 60.0, 3.5}, {0, 0, 90}, {0, 0, 0}, 0},
      // 802 vertices of 300 bytes in views of at most 80400 bytes: 268 vertices per view, 3 views (llvmpipe).
      {"5 bands RGB split over 3 buffer-texture views", 5, 3, 0, render::Camera{-40.0, 10.0, 0.0}, {30, 0, 0}, {0, 0, 0},
       80400},
  };
  for (const Case& c : cases) {
    SECTION(c.name) {
      const transfer::TransferData transfer = unshadowed_transfer(mesh, c.bands, c.channels, glm::vec3(0.9f, 0.6f, 0.35f));
      const int index = renderer.add_transfer(transfer, "test", c.max_range_bytes);
      const sh::RgbCoefficients lighting = test_lighting(c.bands);
      renderer.set_lighting(lighting, nullptr);

      render::FrameSettings settings = black_frame(index, c.truncate, c.environment_ypr, c.object_ypr);
      settings.camera = c.camera;
      renderer.render(settings, kWidth, kHeight);
      const image::Image gpu = renderer.read_radiance();
      const std::vector<std::uint32_t> ids = renderer.read_triangle_ids();

      sh::RgbCoefficients seen = object_frame_lighting(lighting, settings.environment_rotation, settings.object_rotation);
      if (c.truncate > 0) seen = seen.truncated(c.truncate);
      const std::vector<glm::vec3> per_vertex = shade::shade_diffuse(transfer, seen);
      double smallest = 1e30;
      for (const glm::vec3& v : per_vertex) smallest = std::min({smallest, double(v.x), double(v.y), double(v.z)});
      REQUIRE(smallest > 0.05);  // the relative error below is meaningful: no radiance near zero

      // The CPU finds each pixel's surface point itself (cpu_raster.h: the camera of docs/conventions.md,
      // one double ray per pixel centre, no GPU matrix or triangle ids) and interpolates prt shade's
      // per-vertex radiance there; pixels off the silhouette are compared.
      const std::vector<PixelHit> hits = cast_pixels(mesh, c.camera.azimuth_degrees, c.camera.elevation_degrees,
                                                     c.camera.distance, settings.object_rotation, kWidth, kHeight);
      const image::Image cpu = interpolate_hits(mesh, per_vertex, hits, kWidth, kHeight);
      std::size_t covered = 0;
      const double worst = max_relative_error_interior(gpu, cpu, hits, 1e-6, covered);
      INFO("compared pixels " << covered << ", max relative error " << worst);
      CHECK(covered > static_cast<std::size_t>(kWidth * kHeight / 20));
      CHECK(worst <= kExactTolerance);

      // Background pixels are black (cleared) and every covered pixel names a real triangle.
      bool background_black = true, ids_valid = true;
      for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
          const std::uint32_t id = ids[static_cast<std::size_t>(y) * kWidth + x];
          if (id == render::kNoTriangle)
            background_black = background_black && gpu.at(x, y, 0) == 0.0f && gpu.at(x, y, 1) == 0.0f && gpu.at(x, y, 2) == 0.0f;
          else
            ids_valid = ids_valid && id < mesh.triangle_count();
        }
      CHECK(background_black);
      CHECK(ids_valid);
    }
  }
}

TEST_CASE("a transfer needing more than 8 buffer-texture views is refused", "[render][gl]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  const mesh::Mesh mesh = bumpy_sphere(20, 40);
  renderer.set_mesh(mesh);
  const transfer::TransferData transfer = unshadowed_transfer(mesh, 5, 3, glm::vec3(0.5f));
  render::TransferBuffer split(transfer, "test", 80400);
  // 300 bytes per vertex: at most 268 vertices per view (fewer if the offset alignment demands it).
  CHECK(split.vertices_per_chunk() <= 268);
  CHECK(split.vertices_per_chunk() >= 200);
  CHECK(split.chunks() == static_cast<int>((mesh.vertex_count() + split.vertices_per_chunk() - 1) / split.vertices_per_chunk()));
  CHECK(split.chunks() >= 3);
  CHECK_THROWS_WITH(renderer.add_transfer(transfer, "big.prt", 3000),
                    Catch::StartsWith("big.prt: transfer is 0.2 MiB; the renderer reads at most 8 buffer textures of 0.0 MiB"));
}

TEST_CASE("cap_pixel_rect holds every pixel whose view direction is in the cap, and little more", "[render]") {
  const mesh::Bounds bounds = mesh::bounds(bumpy_sphere(4, 8));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int w = 96, h = 64;
  int bounded = 0, whole = 0, none = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const render::ViewMatrices view =
        render::orbit_view(render::Camera{360.0 * unit(rng), 160.0 * unit(rng) - 80.0, 2.0 + 5.0 * unit(rng)}, bounds, w, h);
    // Half the caps about the view's centre line (forward, jittered), half anywhere.
    glm::dvec3 d = trial % 2 == 0 ? -view.camera_to_world[2] * 3.0 : glm::dvec3(0.0);
    d += 2.0 * prt::test::draw_vec3<double>(rng, unit) - 1.0;
    d = glm::normalize(d);
    const double radius = glm::radians(0.3 + 40.0 * unit(rng) * unit(rng));
    // Brute force: the bounding box (rows up from the bottom) of the pixels whose centre ray is in the cap.
    int lo_x = w, lo_y = h, hi_x = -1, hi_y = -1;
    for (int py = 0; py < h; ++py)
      for (int px = 0; px < w; ++px) {
        const double nx = (px + 0.5) / w * 2.0 - 1.0, ny = 1.0 - (py + 0.5) / h * 2.0;
        const glm::dvec3 ray = glm::normalize(view.camera_to_world * glm::dvec3(nx * view.tan_half_fov_x, ny * view.tan_half_fov_y, -1.0));
        if (glm::dot(ray, d) < std::cos(radius)) continue;
        const int up = h - 1 - py;
        lo_x = std::min(lo_x, px), hi_x = std::max(hi_x, px), lo_y = std::min(lo_y, up), hi_y = std::max(hi_y, up);
      }
    const std::optional<camera::PixelRect> rect = camera::cap_pixel_rect(view, w, h, d, radius);
    INFO("trial " << trial << ": pixels in the cap x " << lo_x << ".." << hi_x << ", y " << lo_y << ".." << hi_y);
    if (hi_x < 0) {  // no pixel in the cap: nothing, or (part of the cap behind the camera) the whole image
      none += !rect;
      continue;
    }
    REQUIRE(rect);
    CHECK(rect->x0 <= lo_x);
    CHECK(rect->y0 <= lo_y);
    CHECK(rect->x1 > hi_x);
    CHECK(rect->y1 > hi_y);
    const bool is_whole = rect->x0 == 0 && rect->y0 == 0 && rect->x1 == w && rect->y1 == h;
    whole += is_whole;
    // Tight where the cap is wholly in the image (a clipped cap's visible part can be narrower than its
    // rectangle): the 2-pixel margin, one more for a rim between pixel centres, and the 32-gon's widening.
    if (is_whole || lo_x == 0 || lo_y == 0 || hi_x == w - 1 || hi_y == h - 1) continue;
    ++bounded;
    const double slack_x = 4.0 + 0.02 * (hi_x - lo_x), slack_y = 4.0 + 0.02 * (hi_y - lo_y);
    CHECK(rect->x0 >= lo_x - slack_x);
    CHECK(rect->y0 >= lo_y - slack_y);
    CHECK(rect->x1 <= hi_x + 1 + slack_x);
    CHECK(rect->y1 <= hi_y + 1 + slack_y);
  }
  INFO("bounded " << bounded << ", whole image " << whole << ", empty " << none);
  CHECK(bounded > 30);
  CHECK(none > 20);
}

TEST_CASE("the auto camera frames the bounds and azimuth 0 looks from +Z", "[render]") {
  const mesh::Mesh mesh = bumpy_sphere(8, 16, glm::vec3(1.0f, 2.0f, 3.0f));
  const mesh::Bounds bounds = mesh::bounds(mesh);
  const glm::dvec3 centre = (glm::dvec3(bounds.lo) + glm::dvec3(bounds.hi)) * 0.5;
  const double radius = 0.5 * glm::length(glm::dvec3(bounds.hi) - glm::dvec3(bounds.lo));

  const render::ViewMatrices front = render::orbit_view(render::Camera{0.0, 0.0, 5.0}, bounds, 200, 100);
  CHECK(front.eye.x == Approx(centre.x).margin(1e-12));
  CHECK(front.eye.y == Approx(centre.y).margin(1e-12));
  CHECK(front.eye.z == Approx(centre.z + 5.0));
  const render::ViewMatrices side = render::orbit_view(render::Camera{90.0, 0.0, 5.0}, bounds, 200, 100);
  CHECK(side.eye.x == Approx(centre.x + 5.0));
  const render::ViewMatrices above = render::orbit_view(render::Camera{0.0, 60.0, 2.0}, bounds, 200, 100);
  CHECK(above.eye.y == Approx(centre.y + 2.0 * std::sin(glm::radians(60.0))));

  // Auto: every point of the bounding sphere's silhouette lies inside the view, and it nearly fills the
  // narrower (vertical here, aspect 2) field: the sphere's angular radius is 1/1.05 of half the fov.
  for (int aspect_case = 0; aspect_case < 2; ++aspect_case) {
    const int w = aspect_case == 0 ? 200 : 100, h = aspect_case == 0 ? 100 : 200;
    const render::ViewMatrices v = render::orbit_view(render::Camera{}, bounds, w, h);
    const double angular_radius = std::asin(radius / v.distance);
    const double half_narrow = std::min(std::atan(v.tan_half_fov_x), std::atan(v.tan_half_fov_y));
    CHECK(std::sin(angular_radius) * 1.05 == Approx(std::sin(half_narrow)));
    CHECK(v.near_plane < v.distance - radius);
    CHECK(v.far_plane > v.distance + radius);
  }
}

TEST_CASE("the SH background equals prt::sh::eval along each pixel's view direction", "[render][gl]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  const mesh::Mesh mesh = bumpy_sphere(6, 12);
  renderer.set_mesh(mesh);
  const int bands = 9;  // exercises the generic recurrence in background.frag up to l = 8
  renderer.add_transfer(unshadowed_transfer(mesh, bands, 1, glm::vec3(0.5f)), "test");
  const sh::RgbCoefficients lighting = test_lighting(bands);
  renderer.set_lighting(lighting, nullptr);
  render::FrameSettings settings;
  settings.camera = render::Camera{20.0, 10.0, 6.0};
  settings.background = render::Background::sh;
  settings.environment_rotation = sh::rotation_from_yaw_pitch_roll(40.0, -25.0, 10.0);
  renderer.render(settings, kWidth, kHeight);
  const image::Image gpu = renderer.read_radiance();
  const std::vector<std::uint32_t> ids = renderer.read_triangle_ids();
  const render::ViewMatrices& view = renderer.last_view();

  std::vector<double> y(static_cast<std::size_t>(bands * bands));
  double worst = 0.0;
  std::size_t checked = 0;
  for (int py = 0; py < kHeight; ++py) {
    for (int px = 0; px < kWidth; ++px) {
      if (ids[static_cast<std::size_t>(py) * kWidth + px] != render::kNoTriangle) continue;
      const double nx = (px + 0.5) / kWidth * 2.0 - 1.0, ny = 1.0 - (py + 0.5) / kHeight * 2.0;
      const glm::dvec3 world = glm::normalize(view.camera_to_world * glm::dvec3(nx * view.tan_half_fov_x, ny * view.tan_half_fov_y, -1.0));
      sh::eval(bands, glm::normalize(glm::transpose(settings.environment_rotation) * world), y.data());
      glm::dvec3 expected(0.0);
      for (int i = 0; i < bands * bands; ++i) expected += y[static_cast<std::size_t>(i)] * lighting.values[static_cast<std::size_t>(i)];
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(gpu.at(px, py, c) - expected[c]) / std::fabs(lighting.values[0][c]));
      ++checked;
    }
  }
  INFO("background pixels " << checked << ", max error relative to L00 " << worst);
  CHECK(checked > static_cast<std::size_t>(kWidth * kHeight / 2));
  CHECK(worst < 2e-5);
}

// Plus the discs the frame shades: E / (pi sin^2 a) inside each, nothing outside.
TEST_CASE("the image background equals Environment::radiance plus the shaded discs along each view direction", "[render][gl]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  const mesh::Mesh mesh = bumpy_sphere(6, 12);
  renderer.set_mesh(mesh);
  renderer.add_transfer(unshadowed_transfer(mesh, 2, 1, glm::vec3(0.5f)), "test");
  light::Environment environment;
  environment.equirect = smooth_environment(128);
  renderer.set_lighting(test_lighting(2), &environment.equirect);
  render::FrameSettings settings;
  settings.camera = render::Camera{-60.0, 20.0, 3.0};
  settings.environment_rotation = sh::rotation_from_yaw_pitch_roll(-75.0, 30.0, 0.0);
  renderer.render(settings, kWidth, kHeight);
  const render::ViewMatrices view = renderer.last_view();
  auto pixel_direction = [&](double px, double py) {  // environment frame
    const double nx = px / kWidth * 2.0 - 1.0, ny = 1.0 - py / kHeight * 2.0;
    const glm::dvec3 world = glm::normalize(view.camera_to_world * glm::dvec3(nx * view.tan_half_fov_x, ny * view.tan_half_fov_y, -1.0));
    return glm::normalize(glm::transpose(settings.environment_rotation) * world);
  };
  // A disc of 6 degrees centred on a background pixel near the top left corner, and its closed-form radiance.
  light::Disc disc;
  disc.direction = pixel_direction(0.18 * kWidth, 0.2 * kHeight);
  disc.irradiance = glm::dvec3(0.02, 0.05, 0.01);
  disc.angular_radius = 6.0 * kPi / 180.0;
  const double sin_a = std::sin(disc.angular_radius);
  const glm::dvec3 disc_radiance = disc.irradiance / (kPi * sin_a * sin_a);
  const double pixel_angle = 2.0 * std::atan(view.tan_half_fov_y) / kHeight;

  // Renders and compares every background pixel off the disc's rim (where pixels blend) with the map plus,
  // where `drawn`, the disc; counts the pixels inside and outside the disc.
  auto check = [&](bool drawn) {
    renderer.render(settings, kWidth, kHeight);
    const image::Image gpu = renderer.read_radiance();
    const std::vector<std::uint32_t> ids = renderer.read_triangle_ids();
    double worst = 0.0;
    int inside = 0, outside = 0;
    for (int py = 0; py < kHeight; ++py) {
      for (int px = 0; px < kWidth; ++px) {
        if (ids[static_cast<std::size_t>(py) * kWidth + px] != render::kNoTriangle) continue;
        const glm::dvec3 d = pixel_direction(px + 0.5, py + 0.5);
        const double angle = std::atan2(glm::length(glm::cross(d, disc.direction)), glm::dot(d, disc.direction));
        if (std::fabs(angle - disc.angular_radius) < 2.0 * pixel_angle) continue;
        const bool in_disc = angle < disc.angular_radius;
        (in_disc ? inside : outside) += 1;
        const glm::dvec3 expected = environment.radiance(d) + (in_disc && drawn ? disc_radiance : glm::dvec3(0.0));
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(gpu.at(px, py, c) - expected[c]) / std::max(expected[c], 0.1));
      }
    }
    INFO("disc drawn " << drawn << ": " << inside << " pixels inside the disc, " << outside << " outside, max relative error "
                       << worst);
    CHECK(inside > 100);
    CHECK(outside > 1000);
    // GPU bilinear filtering may quantise its weights (8 bits on llvmpipe): allow 1% of a neighbour step.
    CHECK(worst < 5e-3);
  };
  SECTION("no discs") { check(false); }
  SECTION("a disc, shaded and drawn") {
    renderer.set_discs({disc});
    check(true);
  }
  SECTION("a disc not shaded (sun off) is not drawn") {
    renderer.set_discs({disc});
    settings.sun = false;
    check(false);
  }
}

TEST_CASE("the window's tone map pass equals prt::image::to_display", "[render][gl]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  const mesh::Mesh mesh = bumpy_sphere(10, 20);
  renderer.set_mesh(mesh);
  renderer.add_transfer(unshadowed_transfer(mesh, 3, 3, glm::vec3(0.9f, 0.5f, 0.2f)), "test");
  light::Environment environment;
  environment.equirect = smooth_environment(64);
  renderer.set_lighting(test_lighting(3), &environment.equirect);
  render::FrameSettings settings;
  renderer.render(settings, 96, 64);
  const image::Image linear = renderer.read_radiance();

  GLuint target_texture = 0, target = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &target_texture);
  glTextureStorage2D(target_texture, 1, GL_RGBA32F, 96, 64);
  glCreateFramebuffers(1, &target);
  glNamedFramebufferTexture(target, GL_COLOR_ATTACHMENT0, target_texture, 0);
  for (image::ToneMap op : {image::ToneMap::aces, image::ToneMap::clamp}) {
    for (double exposure : {-1.0, 0.0, 1.5}) {
      renderer.present(target, exposure, op);
      std::vector<float> rgba(96 * 64 * 4);
      glNamedFramebufferReadBuffer(target, GL_COLOR_ATTACHMENT0);
      glBindFramebuffer(GL_READ_FRAMEBUFFER, target);
      glReadPixels(0, 0, 96, 64, GL_RGBA, GL_FLOAT, rgba.data());
      const image::Image expected = image::to_display(linear, exposure, op);
      double worst = 0.0;
      for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 96; ++x)
          for (int c = 0; c < 3; ++c)
            worst = std::max(worst, double(std::fabs(rgba[(static_cast<std::size_t>(63 - y) * 96 + x) * 4 + c] - expected.at(x, y, c))));
      INFO("exposure " << exposure << ", max display difference " << worst);
      CHECK(worst < 2e-5);  // far below one 8-bit step (1/255)
    }
  }
  glDeleteFramebuffers(1, &target);
  glDeleteTextures(1, &target_texture);
}

TEST_CASE("the Lambert baseline equals albedo * mean radiance * max(n . l, 0) interpolated", "[render][gl]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  mesh::Mesh mesh = bumpy_sphere(16, 32);
  mesh.albedo.assign(mesh.vertex_count(), glm::vec3(0.7f, 0.5f, 0.3f));
  renderer.set_mesh(mesh);
  const sh::RgbCoefficients lighting = test_lighting(3);
  renderer.set_lighting(lighting, nullptr);
  render::FrameSettings settings;
  settings.shading = render::Shading::lambert;
  settings.background = render::Background::black;
  settings.camera = render::Camera{30.0, 20.0, 0.0};
  settings.environment_rotation = sh::rotation_from_yaw_pitch_roll(50.0, 0.0, 0.0);
  settings.object_rotation = sh::rotation_from_yaw_pitch_roll(0.0, 30.0, 0.0);
  renderer.render(settings, kWidth, kHeight);
  const image::Image gpu = renderer.read_radiance();
  const std::vector<std::uint32_t> ids = renderer.read_triangle_ids();

  glm::dvec3 direction, radiance;
  render::lambert_light(lighting, direction, radiance);
  CHECK(radiance.x == Approx(3.0 * 0.28209479177387814));
  const glm::dvec3 light = settings.environment_rotation * direction;
  std::vector<glm::vec3> per_vertex(mesh.vertex_count());
  for (std::size_t v = 0; v < per_vertex.size(); ++v) {
    const double cosine = std::max(0.0, glm::dot(glm::normalize(settings.object_rotation * glm::dvec3(mesh.normals[v])), light));
    per_vertex[v] = glm::vec3(glm::dvec3(mesh.albedo[v]) * radiance * cosine);
  }
  const image::Image cpu = interpolate_on_cpu(mesh, per_vertex, renderer.last_model_view_projection(), ids, kWidth, kHeight);
  double worst = 0.0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::fabs(gpu.at(x, y, c) - cpu.at(x, y, c))));
  INFO("max absolute difference " << worst);
  CHECK(worst < 1e-4 * radiance.x);
}
