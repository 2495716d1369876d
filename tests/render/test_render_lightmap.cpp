// Texel (lightmap) transfer on the GPU (render/renderer_lightmap.h) against the CPU:
// - at texel centres (Renderer::render_texels: each triangle drawn at its lightmap UV, pixel (i, j) =
//   texel (i, j)), the GPU's per-pixel sampling and dot product equal prt::shade::shade_diffuse of each
//   texel's own block under the object-frame lighting (rotated in double by sh::Rotation), with and
//   without discs (their bounce-only layers and their exact direct light), and prt shade --lightmap of
//   a baked lightmap;
// - in the camera's view, every pixel equals the CPU's bilinear lookup of the texel grid at the UV of the
//   pixel's surface point, found by a double ray cast (cpu_raster.h), dotted with the lighting; the
//   per-pixel sun equals the per-vertex pass's; a distant chart is filtered over the coverage-aware mips.
// The transfers are synthetic (texel blocks made here), except the one compared with prt shade --lightmap.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

#include "bake/bake.h"
#include "cpu_raster.h"
#include "light/scene_lighting.h"
#include "lightmap/lightmap_scenes.h"  // tests/lightmap
#include "lightmap/lightmap_shading.h"
#include "lightmap/texel_bake.h"
#include "light/disc.h"
#include "mesh/mesh.h"
#include "render/headless_context.h"
#include "render/renderer.h"
#include "render_fixtures.h"
#include "sh/rotation.h"
#include "shade/shade.h"
#include "support/texel_transfer.h"
#include "transfer/half.h"

using namespace prt;
using namespace prt::render_test;

namespace {

constexpr int kTexelsWide = 64, kTexelsHigh = 48;

// Adds the quad p0 + s u + t v (s, t in [0, 1]) as two triangles whose corners map to the UV rectangle
// uv0 + s du + t dv (per corner: a quad may reuse another's vertices with different UVs).
void add_chart(mesh::Mesh& m, const glm::vec3& p0, const glm::vec3& u, const glm::vec3& v, const glm::vec2& uv0,
               const glm::vec2& du, const glm::vec2& dv, bool new_vertices = true) {
  if (new_vertices) {
    const glm::vec3 normal = glm::normalize(glm::cross(u, v));
    for (const glm::vec3& p : {p0, p0 + u, p0 + u + v, p0 + v}) {
      m.positions.push_back(p);
      m.normals.push_back(normal);
    }
  }
  const auto first = static_cast<std::uint32_t>(m.positions.size() - 4);
  const glm::vec2 uv[4] = {uv0, uv0 + du, uv0 + du + dv, uv0 + dv};
  for (int k : {0, 1, 2, 0, 2, 3}) {
    m.indices.push_back(first + static_cast<std::uint32_t>(k));
    m.lightmap_uv.push_back(uv[k]);
  }
}

// Charts of a 64 x 48 lightmap: a floor quad, a wall quad (UVs mirrored and turned) and, with
// `duplicate`, the wall again with the same vertices but other UVs (lightmap UVs are per corner; only
// for texel space, where the copies do not fight over depth).
mesh::Mesh charted_mesh(bool duplicate) {
  mesh::Mesh m;
  add_chart(m, {-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, {0.05f, 0.9f}, {0.45f, 0.0f}, {0.0f, -0.8f});
  add_chart(m, {-1, 0, -1}, {2, 0, 0}, {0, 1.2f, 0}, {0.95f, 0.55f}, {0.0f, -0.5f}, {-0.35f, 0.0f});
  if (duplicate) add_chart(m, {-1, 0, -1}, {2, 0, 0}, {0, 1.2f, 0}, {0.6f, 0.62f}, {0.35f, 0.0f}, {0.0f, 0.33f}, false);
  m.albedo.assign(m.positions.size(), glm::vec3(0.7f, 0.55f, 0.4f));
  return m;
}

// A texel transfer for `mesh`: every texel whose centre one of the triangles covers (in UV) gets a block,
// smooth in UV (the closed-form unshadowed transfer of a normal that turns across the lightmap) when
// `smooth`, else pseudo-random, and so do the texels within 2 of a covered one (a gutter); the others
// stay empty (zero). With `bounce`, a bounce-only section.
transfer::TransferData texel_transfer(const mesh::Mesh& mesh, int bands, int channels, bool smooth, bool bounce) {
  transfer::TransferData t = test::empty_texel_transfer(mesh, kTexelsWide, kTexelsHigh, bands, channels, bounce);
  const std::size_t per_texel = t.header.values_per_vertex();
  // Per texel: a one-vertex "mesh" whose normal turns with the UV, for the smooth blocks.
  mesh::Mesh one;
  one.positions = {glm::vec3(0.0f)};
  one.normals = {glm::vec3(0.0f, 1.0f, 0.0f)};
  std::uint32_t state = 12345u;
  auto random = [&] {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) / 16777216.0f - 0.5f;
  };
  for (int j = 0; j < kTexelsHigh; ++j)
    for (int i = 0; i < kTexelsWide; ++i) {
      const glm::vec2 centre((i + 0.5f) / kTexelsWide, (j + 0.5f) / kTexelsHigh);
      bool inside = false;
      for (std::size_t tri = 0; tri < mesh.triangle_count() && !inside; ++tri) {
        const glm::vec2 a = mesh.lightmap_uv[3 * tri], b = mesh.lightmap_uv[3 * tri + 1], c = mesh.lightmap_uv[3 * tri + 2];
        auto edge = [](glm::vec2 p, glm::vec2 q, glm::vec2 x) { return (q.x - p.x) * (x.y - p.y) - (q.y - p.y) * (x.x - p.x); };
        const float e0 = edge(a, b, centre), e1 = edge(b, c, centre), e2 = edge(c, a, centre);
        inside = (e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0);
      }
      if (inside) t.coverage[std::size_t(j) * kTexelsWide + i] = transfer::kTexelCovered;
    }
  for (int j = 0; j < kTexelsHigh; ++j)
    for (int i = 0; i < kTexelsWide; ++i) {
      const std::size_t texel = std::size_t(j) * kTexelsWide + i;
      bool near = false;
      for (int dj = -2; dj <= 2; ++dj)
        for (int di = -2; di <= 2; ++di) {
          const int ii = i + di, jj = j + dj;
          near = near || (ii >= 0 && jj >= 0 && ii < kTexelsWide && jj < kTexelsHigh &&
                          t.coverage[std::size_t(jj) * kTexelsWide + ii] == transfer::kTexelCovered);
        }
      if (!near) continue;
      if (t.coverage[texel] != transfer::kTexelCovered) t.coverage[texel] = transfer::kTexelGutter;
      const glm::vec2 centre((i + 0.5f) / kTexelsWide, (j + 0.5f) / kTexelsHigh);
      one.normals[0] = glm::normalize(glm::vec3(std::sin(4.0f * centre.x), 1.0f, std::cos(3.0f * centre.y) - 0.4f));
      const transfer::TransferData block = unshadowed_transfer(one, bands, channels, glm::vec3(0.8f, 0.6f, 0.45f));
      for (std::size_t k = 0; k < per_texel; ++k) {
        t.values[texel * per_texel + k] = smooth ? block.values[k] : random() * 0.8f / (1.0f + float(k % (bands * bands)));
        if (bounce) t.bounce_only[texel * per_texel + k] = 0.3f * block.values[k] + 0.05f * random();
      }
    }
  return t;
}

sh::RgbCoefficients rotated(const sh::RgbCoefficients& lighting, const render::FrameSettings& settings) {
  return sh::Rotation(lighting.bands, glm::transpose(settings.object_rotation) * settings.environment_rotation).apply(lighting);
}

// prt::shade::shade_diffuse of every texel's block: the texel grid taken as a "mesh" of W x H vertices.
std::vector<glm::vec3> shade_texels(const transfer::TransferData& t, const std::vector<float>& values,
                                    const sh::RgbCoefficients& lighting) {
  transfer::TransferData blocks;
  blocks.header = t.header;
  blocks.header.texel_width = blocks.header.texel_height = 0;
  blocks.header.bounce_only_section = false;
  blocks.header.vertex_count = std::uint64_t(t.header.texel_width) * t.header.texel_height;
  blocks.values = values;
  return shade::shade_diffuse(blocks, lighting);
}

// Largest |gpu - cpu| over texels the GPU drew, in units of the texel's own tolerance:
//   rounding x (sum over terms of |T_i L_i|, floored at 1e-3 of the largest) + 2e-5 x (the largest
//   difference to a 4-neighbour).
// The first is float rounding of the dot product; the second is the sampling point's: the interpolated
// UV is the texel centre to a few float ulps of the texel coordinate (~4e-6 texel at 64 texels), and a
// bilinear filter with float weights (llvmpipe) mixes that fraction of the neighbours in. A sample off by
// a texel, or half of one, costs 1 / 0.5 of the neighbour difference: 10^4 times the bound.
double texel_error(const image::Image& gpu, const std::vector<glm::vec3>& cpu, const std::vector<glm::vec3>& scale,
                   const std::vector<std::uint32_t>& ids, double rounding, std::size_t& drawn) {
  double largest = 0.0;
  for (const glm::vec3& s : scale) largest = std::max({largest, double(s.x), double(s.y), double(s.z)});
  double worst = 0.0;
  drawn = 0;
  for (int j = 0; j < kTexelsHigh; ++j)
    for (int i = 0; i < kTexelsWide; ++i) {
      const std::size_t texel = std::size_t(j) * kTexelsWide + i;
      if (ids[texel] == render::kNoTriangle) continue;
      ++drawn;
      for (int c = 0; c < 3; ++c) {
        double contrast = 0.0;
        for (const auto& [di, dj] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
          const int ii = std::clamp(i + di, 0, kTexelsWide - 1), jj = std::clamp(j + dj, 0, kTexelsHigh - 1);
          contrast = std::max(contrast, std::abs(double(cpu[std::size_t(jj) * kTexelsWide + ii][c]) - cpu[texel][c]));
        }
        const double tolerance = rounding * std::max(double(scale[texel][c]), 1e-3 * largest) + 2e-5 * contrast;
        worst = std::max(worst, std::abs(gpu.at(i, j, c) - cpu[texel][c]) / tolerance);
      }
    }
  return worst;
}

// The per-texel scale sum_i |T_i| |L_i| per channel (the absolute values' dot product).
std::vector<glm::vec3> texel_scale(const transfer::TransferData& t, const std::vector<float>& values, const sh::RgbCoefficients& l) {
  std::vector<float> magnitudes(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) magnitudes[k] = std::abs(values[k]);
  sh::RgbCoefficients absolute = l;
  for (glm::dvec3& c : absolute.values) c = glm::abs(c);
  return shade_texels(t, magnitudes, absolute);
}

}  // namespace

TEST_CASE("lightmap render at texel centres equals the CPU dot product of each texel's block", "[render][gl][lightmap]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  const mesh::Mesh mesh = charted_mesh(true);
  renderer.set_mesh(mesh);

  struct Case {
    const char* name;
    int bands, channels, truncate;
    glm::dvec3 environment_ypr, object_ypr;
    bool half;  // a float16 file: RGBA16F layers
  };
  const Case cases[] = {
      {"5 bands RGB, rotated lighting and object", 5, 3, 0, {70, 20, -10}, {-30, 15, 5}, false},
      {"4 bands grey truncated to 2", 4, 1, 2, {0, 0, 90}, {0, 40, 0}, false},
      {"6 bands RGB (27 layers)", 6, 3, 0, {-45, 0, 0}, {0, 0, 0}, false},
      {"5 bands RGB stored as float16 (RGBA16F layers)", 5, 3, 0, {10, -20, 0}, {0, 0, 0}, true},
  };
  for (const Case& c : cases) {
    SECTION(c.name) {
      transfer::TransferData transfer = texel_transfer(mesh, c.bands, c.channels, false, false);
      if (c.half) {  // as read from a float16 file: the values are halves
        transfer.header.scalar = transfer::Scalar::float16;
        for (float& v : transfer.values) v = transfer::half_to_float(transfer::float_to_half(v));
      }
      const int index = renderer.add_lightmap(transfer, "test.prt");
      CHECK(renderer.is_lightmap(index));
      const sh::RgbCoefficients lighting = test_lighting(c.bands);
      renderer.set_lighting(lighting, nullptr);
      render::FrameSettings settings;
      settings.transfer = index;
      settings.bands = c.truncate;
      settings.environment_rotation = sh::rotation_from_yaw_pitch_roll(c.environment_ypr.x, c.environment_ypr.y, c.environment_ypr.z);
      settings.object_rotation = sh::rotation_from_yaw_pitch_roll(c.object_ypr.x, c.object_ypr.y, c.object_ypr.z);
      renderer.render_texels(settings);
      REQUIRE(renderer.width() == kTexelsWide);
      REQUIRE(renderer.height() == kTexelsHigh);
      const image::Image gpu = renderer.read_radiance();
      const std::vector<std::uint32_t> ids = renderer.read_triangle_ids();

      sh::RgbCoefficients seen = rotated(lighting, settings);
      if (c.truncate > 0) seen = seen.truncated(c.truncate);
      const std::vector<glm::vec3> cpu = shade_texels(transfer, transfer.values, seen);
      std::size_t drawn = 0;
      const double worst = texel_error(gpu, cpu, texel_scale(transfer, transfer.values, seen), ids, 2e-6 * c.bands * c.bands, drawn);
      // Every texel whose centre a triangle covers is drawn (the GPU rasterises texel centres) and named
      // by its triangle; no other texel is.
      std::size_t covered = 0, mismatched = 0;
      for (std::size_t texel = 0; texel < ids.size(); ++texel) {
        const bool is_covered = transfer.coverage[texel] == transfer::kTexelCovered;
        covered += is_covered;
        mismatched += is_covered != (ids[texel] != render::kNoTriangle);
      }
      INFO("drawn texels " << drawn << " of " << covered << " covered, worst error / tolerance " << worst);
      CHECK(covered > 600);
      CHECK(mismatched == 0);
      CHECK(worst <= 1.0);
    }
  }
}

TEST_CASE("lightmap render with a disc: bounce-only layers and the exact direct term per texel", "[render][gl][lightmap]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  // A floor only (two charts, both facing +Y): nothing occludes the disc, so the shadow map's visibility
  // is 1 and the direct term is (albedo / pi) E (n . d) at every texel.
  mesh::Mesh mesh;
  add_chart(mesh, {-1, 0, 1}, {1, 0, 0}, {0, 0, -2}, {0.05f, 0.9f}, {0.4f, 0.0f}, {0.0f, -0.8f});
  add_chart(mesh, {0, 0, 1}, {1, 0, 0}, {0, 0, -2}, {0.55f, 0.1f}, {0.0f, 0.8f}, {0.4f, 0.0f});
  mesh.albedo.assign(mesh.positions.size(), glm::vec3(0.7f, 0.55f, 0.4f));
  renderer.set_mesh(mesh);
  const transfer::TransferData transfer = texel_transfer(mesh, 4, 3, true, true);
  const int index = renderer.add_lightmap(transfer, "test.prt");
  renderer.set_surface_albedo(index, mesh.albedo);
  const sh::RgbCoefficients sky = test_lighting(4);
  light::Disc disc;
  disc.direction = glm::normalize(glm::dvec3(0.3, 0.8, -0.2));
  disc.irradiance = glm::dvec3(5.0, 4.0, 3.0);
  disc.angular_radius = 0.01;
  renderer.set_lighting(sky, nullptr);
  renderer.set_discs({disc});
  render::FrameSettings settings;
  settings.transfer = index;
  settings.environment_rotation = sh::rotation_from_yaw_pitch_roll(25, 0, 0);
  renderer.render_texels(settings);
  const image::Image gpu = renderer.read_radiance();
  const std::vector<std::uint32_t> ids = renderer.read_triangle_ids();

  // CPU: sky through the transfer, the disc's SH through the bounce-only part, the direct term exactly.
  const sh::RgbCoefficients seen_sky = rotated(sky, settings);
  const sh::RgbCoefficients seen_disc = rotated(light::discs_coefficients(4, {disc}), settings);
  std::vector<glm::vec3> cpu = shade_texels(transfer, transfer.values, seen_sky);
  const std::vector<glm::vec3> bounce = shade_texels(transfer, transfer.bounce_only, seen_disc);
  std::vector<glm::vec3> scale = texel_scale(transfer, transfer.values, seen_sky);
  const std::vector<glm::vec3> bounce_scale = texel_scale(transfer, transfer.bounce_only, seen_disc);
  const glm::dvec3 d = settings.environment_rotation * disc.direction;
  const glm::dvec3 direct = glm::dvec3(0.7, 0.55, 0.4) / 3.14159265358979323846 * disc.irradiance * std::max(0.0, d.y);
  REQUIRE(direct.z > 0.1);
  for (std::size_t texel = 0; texel < cpu.size(); ++texel) {
    cpu[texel] = glm::max(cpu[texel] + bounce[texel] + glm::vec3(direct), glm::vec3(0.0f));
    scale[texel] += bounce_scale[texel] + glm::vec3(direct);
  }
  std::size_t drawn = 0;
  const double worst = texel_error(gpu, cpu, scale, ids, 1e-5, drawn);
  INFO("drawn texels " << drawn << ", worst error / tolerance " << worst);
  CHECK(drawn > 600);
  CHECK(worst <= 1.0);
}

TEST_CASE("lightmap render in the camera's view equals the CPU's bilinear lookup at each pixel's UV", "[render][gl][lightmap]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  const mesh::Mesh mesh = charted_mesh(false);
  renderer.set_mesh(mesh);
  const transfer::TransferData transfer = texel_transfer(mesh, 3, 3, true, false);
  const int index = renderer.add_lightmap(transfer, "test.prt");
  const sh::RgbCoefficients lighting = test_lighting(3);
  renderer.set_lighting(lighting, nullptr);
  render::FrameSettings settings;
  settings.transfer = index;
  settings.camera = render::Camera{20.0, 35.0, 3.5};
  settings.background = render::Background::black;
  settings.environment_rotation = sh::rotation_from_yaw_pitch_roll(40, 10, 0);
  constexpr int kWidth = 160, kHeight = 120;
  renderer.render(settings, kWidth, kHeight);
  const image::Image gpu = renderer.read_radiance();

  // CPU: the ray through each pixel centre (cpu_raster.h), the UV at its hit from the corners' UVs,
  // OpenGL's bilinear filter with clamp-to-edge (texel coordinates u W - 1/2, v H - 1/2), the dot product.
  const std::vector<glm::vec3> per_texel = shade_texels(transfer, transfer.values, rotated(lighting, settings));
  const std::vector<PixelHit> hits = cast_pixels(mesh, settings.camera.azimuth_degrees, settings.camera.elevation_degrees,
                                                 settings.camera.distance, settings.object_rotation, kWidth, kHeight);
  auto texel = [&](int i, int j) {
    i = std::clamp(i, 0, kTexelsWide - 1);
    j = std::clamp(j, 0, kTexelsHigh - 1);
    return glm::dvec3(per_texel[std::size_t(j) * kTexelsWide + i]);
  };
  double worst = 0.0, largest = 0.0;
  std::size_t compared = 0;
  for (const glm::vec3& v : per_texel) largest = std::max({largest, double(v.x), double(v.y), double(v.z)});
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const PixelHit& hit = hits[std::size_t(y) * kWidth + x];
      if (!interior_hit(hits, kWidth, kHeight, x, y)) continue;
      glm::dvec2 uv(0.0);
      for (int k = 0; k < 3; ++k) uv += hit.b[k] * glm::dvec2(mesh.lightmap_uv[3 * hit.triangle + k]);
      const double tx = uv.x * kTexelsWide - 0.5, ty = uv.y * kTexelsHigh - 0.5;
      const int i = int(std::floor(tx)), j = int(std::floor(ty));
      const double fx = tx - i, fy = ty - j;
      const glm::dvec3 expected = (1 - fy) * ((1 - fx) * texel(i, j) + fx * texel(i + 1, j)) +
                                  fy * ((1 - fx) * texel(i, j + 1) + fx * texel(i + 1, j + 1));
      ++compared;
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(gpu.at(x, y, c) - expected[c]) / largest);
    }
  INFO("compared pixels " << compared << ", max error relative to the largest texel value " << worst);
  CHECK(compared > std::size_t(kWidth * kHeight / 10));
  // llvmpipe filters with float weights; GPUs keep 8 fractional bits: between texels of the smooth data
  // (and its 2-texel gutter, which keeps a chart's rim from reading empty texels) that is below 1e-4 of
  // the largest value. Where the view minifies, trilinear filtering mixes in mip level 1, which for this
  // smooth data is within the same bound of level 0 (measured 8e-7 in all; 2.5e-7 at level 0 alone).
  CHECK(worst <= 1e-4);
}

TEST_CASE("lightmap render at texel centres equals prt shade --lightmap of a baked lightmap", "[render][gl][lightmap]") {
  // A box on a two-triangle floor baked into a 64 x 64 lightmap (interreflected, one bounce), lit by
  // the sky alone; the CPU side is lightmap::shade_lightmap, what `prt shade --lightmap` writes.
  const mesh::Mesh mesh = test::floor_and_box(true, 0.0f);
  bake::BakeOptions options;
  options.kind = transfer::Kind::interreflected;
  options.bands = 4;
  options.samples = 64;
  options.bounces = 1;
  options.threads = 1;
  lightmap::LightmapOptions size;
  size.width = size.height = 64;
  const transfer::TransferData transfer = lightmap::bake_lightmap(mesh, options, size);
  light::SceneLighting lighting;
  lighting.sky = test_lighting(4);
  lighting.clamp_negative = false;
  const image::Image cpu_image = lightmap::shade_lightmap(mesh, transfer, lighting, "baked.prt");

  render::HeadlessContext context;
  render::Renderer renderer;
  renderer.set_mesh(mesh);
  const int index = renderer.add_lightmap(transfer, "baked.prt");
  renderer.set_lighting(lighting.sky, nullptr);
  render::FrameSettings settings;
  settings.transfer = index;
  renderer.render_texels(settings);
  const image::Image gpu = renderer.read_radiance();
  const std::vector<std::uint32_t> ids = renderer.read_triangle_ids();
  std::vector<glm::vec3> cpu(std::size_t(64) * 64);
  for (std::size_t texel = 0; texel < cpu.size(); ++texel)
    for (int c = 0; c < 3; ++c) cpu[texel][c] = cpu_image.at(int(texel % 64), int(texel / 64), c);
  std::size_t drawn = 0, drawn_not_covered = 0;
  for (std::size_t texel = 0; texel < ids.size(); ++texel)
    drawn_not_covered += ids[texel] != render::kNoTriangle && transfer.coverage[texel] != transfer::kTexelCovered;
  const double worst = texel_error(gpu, cpu, texel_scale(transfer, transfer.values, lighting.sky), ids, 2e-6 * 16, drawn);
  INFO("drawn texels " << drawn << ", worst error / tolerance " << worst);
  CHECK(drawn > 1000);
  CHECK(drawn_not_covered == 0);  // conservative rasterisation covers every texel centre a triangle covers
  CHECK(worst <= 1.0);
}

TEST_CASE("a lightmap's per-pixel sun equals the per-vertex pass's (same shadow maps and direct term)", "[render][gl][lightmap]") {
  // Zero transfer and a black sky: both images are the disc's direct light alone, per pixel, with the
  // box's shadow on the floor from the same shadow maps (prt_sun.frag and prt_lightmap.frag share
  // sun_light.glsl); they must agree to float rounding.
  const mesh::Mesh mesh = test::floor_and_box(true, 0.0f);
  render::HeadlessContext context;
  render::Renderer renderer;
  renderer.set_mesh(mesh);
  const int lightmap = renderer.add_lightmap(test::empty_texel_transfer(mesh, 32, 32, 3, 3, false), "zero.prt");
  transfer::TransferData zero;
  zero.header = test::empty_texel_transfer(mesh, 1, 1, 3, 3, false).header;
  zero.header.texel_width = zero.header.texel_height = 0;
  zero.values.assign(mesh.vertex_count() * zero.header.values_per_vertex(), 0.0f);
  const int vertex = renderer.add_transfer(zero, "zero-vertex.prt");
  const std::vector<glm::vec3> albedo(mesh.vertex_count(), glm::vec3(0.7f, 0.6f, 0.5f));
  renderer.set_surface_albedo(lightmap, albedo);
  renderer.set_surface_albedo(vertex, albedo);
  renderer.set_lighting(sh::RgbCoefficients(3), nullptr);
  light::Disc sun;
  sun.direction = glm::normalize(glm::dvec3(0.6, 0.55, 0.45));
  sun.irradiance = glm::dvec3(4.0, 3.5, 3.0);
  sun.angular_radius = 0.02;
  renderer.set_discs({sun});
  render::FrameSettings settings;
  settings.camera = render::Camera{215.0, 50.0, 0.0};
  settings.background = render::Background::black;
  settings.transfer = lightmap;
  renderer.render(settings, 160, 120);
  const image::Image a = renderer.read_radiance();
  settings.transfer = vertex;
  renderer.render(settings, 160, 120);
  const image::Image b = renderer.read_radiance();
  double largest = 0.0, worst = 0.0;
  std::size_t lit = 0, shadowed = 0;
  for (std::size_t k = 0; k < b.pixels.size(); ++k) largest = std::max(largest, double(b.pixels[k]));
  for (std::size_t k = 0; k < b.pixels.size(); ++k) {
    worst = std::max(worst, std::abs(double(a.pixels[k]) - b.pixels[k]) / largest);
    if (k % 3 == 0) (b.pixels[k] > 0.5 * largest ? lit : shadowed) += 1;
  }
  INFO("largest " << largest << ", worst difference / largest " << worst << ", lit pixels " << lit << ", other " << shadowed);
  CHECK(largest > 0.5);
  CHECK(lit > 2000);
  CHECK(worst <= 1e-5);
}

TEST_CASE("a distant lightmap is filtered over a coverage-aware mip chain", "[render][gl][lightmap]") {
  // One floor chart in a 64 x 64 lightmap seen from far away (about 3 texels per pixel): trilinear
  // filtering reads mip levels 1-2. With a constant block on the chart (and its gutter), every pixel
  // must be exactly T . L, also at the rim, where a plain box-filtered chain would mix in the empty
  // texels around the chart; with a texel checkerboard of +-80% about it, the mips average it out
  // (level 0 alone would alias: pixels anywhere between 0.2 and 1.8 times the mean).
  mesh::Mesh mesh;
  add_chart(mesh, {-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, {0.1f, 0.75f}, {0.5f, 0.0f}, {0.0f, -0.5f});
  const sh::RgbCoefficients lighting = test_lighting(3);
  render::HeadlessContext context;
  render::Renderer renderer;
  renderer.set_mesh(mesh);
  const transfer::TransferData smooth = texel_transfer(mesh, 3, 3, true, false);
  transfer::TransferData flat = smooth, checker = smooth;
  const std::size_t per = smooth.header.values_per_vertex();
  std::size_t first = 0;  // the first filled texel: its block everywhere on the chart
  while (smooth.coverage[first] == transfer::kTexelEmpty) ++first;
  std::size_t filled = 0;
  for (std::size_t texel = 0; texel < smooth.coverage.size(); ++texel) {
    if (smooth.coverage[texel] == transfer::kTexelEmpty) continue;
    ++filled;
    const float factor = ((texel % kTexelsWide) + (texel / kTexelsWide)) % 2 == 0 ? 1.8f : 0.2f;
    for (std::size_t k = 0; k < per; ++k) {
      flat.values[texel * per + k] = smooth.values[first * per + k];
      checker.values[texel * per + k] = factor * smooth.values[first * per + k];
    }
  }
  REQUIRE(filled > 500);
  const int flat_index = renderer.add_lightmap(flat, "flat.prt");
  const int checker_index = renderer.add_lightmap(checker, "checker.prt");
  renderer.set_lighting(lighting, nullptr);
  render::FrameSettings settings;
  settings.camera = render::Camera{0.0, 60.0, 30.0};
  settings.background = render::Background::black;
  constexpr int kWidth = 160, kHeight = 120;
  // The expected radiance: the block's dot product with the lighting (CPU).
  transfer::TransferData one = smooth;
  one.header.texel_width = one.header.texel_height = 1;
  one.values.assign(smooth.values.begin() + long(first * per), smooth.values.begin() + long((first + 1) * per));
  one.coverage.assign(1, transfer::kTexelCovered);
  const glm::vec3 expected = shade_texels(one, one.values, lighting)[0];
  REQUIRE(expected.z > 0.1f);

  settings.transfer = flat_index;
  renderer.render(settings, kWidth, kHeight);
  const image::Image a = renderer.read_radiance();
  const std::vector<std::uint32_t> ids = renderer.read_triangle_ids();
  double worst = 0.0;
  std::size_t pixels = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (ids[std::size_t(y) * kWidth + x] == render::kNoTriangle) continue;
      ++pixels;
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(a.at(x, y, c) - expected[c]) / double(expected[c]));
    }
  INFO("floor pixels " << pixels << ", worst relative error of the constant chart " << worst);
  CHECK(pixels > 50);
  CHECK(pixels < 400);  // distant: about 3 texels a pixel
  CHECK(worst <= 1e-5);

  settings.transfer = checker_index;
  renderer.render(settings, kWidth, kHeight);
  const image::Image b = renderer.read_radiance();
  double sum = 0.0, squares = 0.0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (ids[std::size_t(y) * kWidth + x] == render::kNoTriangle) continue;
      const double v = b.at(x, y, 2) / expected[2];
      sum += v;
      squares += v * v;
    }
  const double mean = sum / double(pixels), spread = std::sqrt(std::max(0.0, squares / double(pixels) - mean * mean));
  INFO("checkerboard: mean " << mean << " of the flat value, standard deviation " << spread);
  CHECK(std::abs(mean - 1.0) < 0.05);
  CHECK(spread < 0.1);
}
