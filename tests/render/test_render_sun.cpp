// The renderer's discs (a sun) against the CPU reference: headless renders with set_discs against
// prt::shade::shade_diffuse_split / the glossy split terms, the shadow map's visibility at the vertices
// against the Embree ray visibility of prt::shade::disc_visibility, and the shadow maps redrawn only
// when the lighting changes.
//
// The scene is a box resting on a floor with flat faces (separate vertices per face), so that on a
// triangle whose three corners are all lit (or all in shadow) by the rays, the exact direct term
// (albedo / pi) E max(n . l, 0) V is the same at every pixel and at the corners: there the GPU's per-
// pixel direct light plus its interpolated PRT equals the CPU's per-vertex result interpolated.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <glm/geometric.hpp>
#include <glm/common.hpp>
#include <glm/matrix.hpp>

#include "bake/bake.h"
#include "brdf/brdf.h"
#include "brdf/frame.h"
#include "brdf/projection.h"
#include "compress/compressed.h"
#include "cpu_raster.h"
#include "light/disc.h"
#include "mesh/mesh.h"
#include "render/headless_context.h"
#include "render/renderer.h"
#include "render_fixtures.h"
#include "sh/rotation.h"
#include "shade/disc_direct.h"
#include "shade/glossy.h"
#include "shade/scene_shading.h"
#include "shade/surface_albedo.h"
#include "support/run_prt.h"
#include "trace/scene.h"

using namespace prt;
using namespace prt::render_test;

namespace {

constexpr int kWidth = 200, kHeight = 150;

// A quad p0 + s u + t v (s, t in [0,1]) as an n x n grid of its own vertices, normal u x v.
void add_quad(mesh::Mesh& m, const glm::vec3& p0, const glm::vec3& u, const glm::vec3& v, int n) {
  const auto first = static_cast<std::uint32_t>(m.positions.size());
  const glm::vec3 normal = glm::normalize(glm::cross(u, v));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      m.positions.push_back(p0 + u * (float(i) / n) + v * (float(j) / n));
      m.normals.push_back(normal);
    }
  auto at = [&](int i, int j) { return first + static_cast<std::uint32_t>(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
}

// A unit box on a 4 x 4 floor (y = 0), open at the bottom, its walls starting 1e-3 above the floor:
// a vertex exactly on the contact line would lie on its occluder, where ray visibility is a matter of
// rounding. The floor's grid lines miss the walls' feet for the same reason.
mesh::Mesh box_on_floor() {
  mesh::Mesh m;
  const float lift = 1e-3f;
  add_quad(m, {-2.05f, 0, 2.05f}, {4, 0, 0}, {0, 0, -4}, 40);                 // floor, +Y
  add_quad(m, {-0.5f, 1, 0.5f}, {1, 0, 0}, {0, 0, -1}, 8);                    // top, +Y
  add_quad(m, {-0.5f, lift, 0.5f}, {1, 0, 0}, {0, 1 - lift, 0}, 8);           // front, +Z
  add_quad(m, {0.5f, lift, -0.5f}, {-1, 0, 0}, {0, 1 - lift, 0}, 8);          // back, -Z
  add_quad(m, {0.5f, lift, 0.5f}, {0, 0, -1}, {0, 1 - lift, 0}, 8);           // right, +X
  add_quad(m, {-0.5f, lift, -0.5f}, {0, 0, 1}, {0, 1 - lift, 0}, 8);          // left, -X
  return m;
}

light::Disc test_sun() {
  light::Disc d;
  d.direction = glm::normalize(glm::dvec3(0.6, 0.7, 0.35));
  d.irradiance = glm::dvec3(6.0, 5.5, 4.5);
  d.angular_radius = 0.4 * 3.14159265358979323846 / 180.0;
  return d;
}

transfer::TransferData bake_transfer(const mesh::Mesh& mesh, transfer::Kind kind, int bands, const std::string& spec = "") {
  bake::BakeOptions o;
  o.kind = kind;
  o.bands = bands;
  o.samples = 64;
  o.bounces = 1;
  o.albedo = glm::vec3(0.7f, 0.6f, 0.5f);
  if (!spec.empty()) o.brdf = brdf::parse_brdf(spec);
  o.threads = 1;
  return bake::bake(mesh, o);
}

// Triangles whose three corners the rays see fully lit or fully shadowed, and whose corners the shadow
// map agrees with: there the direct term is constant over the triangle.
std::vector<bool> uniform_triangles(const mesh::Mesh& mesh, const std::vector<float>& rays, const std::vector<float>& map) {
  std::vector<bool> out(mesh.triangle_count());
  for (std::size_t t = 0; t < out.size(); ++t) {
    bool lit = true, dark = true;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.indices[3 * t + k];
      lit = lit && rays[v] == 1.0f && map[v] == 1.0f;
      dark = dark && rays[v] == 0.0f && map[v] == 0.0f;
    }
    out[t] = lit || dark;
  }
  return out;
}

// Largest relative error (denominator floored at 2% of the largest expected value) over pixels of
// uniform triangles; counts them.
double uniform_error(const image::Image& gpu, const image::Image& cpu, const std::vector<std::uint32_t>& ids,
                     const std::vector<bool>& uniform, std::size_t& counted) {
  double largest = 0.0;
  for (float v : cpu.pixels) largest = std::max(largest, std::abs(static_cast<double>(v)));
  double worst = 0.0;
  counted = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const std::uint32_t t = ids[static_cast<std::size_t>(y) * kWidth + x];
      if (t == render::kNoTriangle || !uniform[t]) continue;
      ++counted;
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(gpu.at(x, y, c) - cpu.at(x, y, c)) / std::max(std::abs(double(cpu.at(x, y, c))), 0.02 * largest));
    }
  return worst;
}

// Fraction of the vertices facing the disc (n . d > 0; the others get no direct light either way)
// where shadow-map and ray visibility disagree about lit (V >= 0.5) or not; `facing` counts them.
double disagreement(const mesh::Mesh& mesh, const light::Disc& disc, const std::vector<float>& map,
                    const std::vector<float>& rays, std::size_t& facing) {
  std::size_t differ = 0;
  facing = 0;
  for (std::size_t v = 0; v < map.size(); ++v) {
    if (!(glm::dot(glm::dvec3(mesh.normals[v]), disc.direction) > 0.0)) continue;
    ++facing;
    differ += (map[v] >= 0.5f) != (rays[v] >= 0.5f);
  }
  return static_cast<double>(differ) / static_cast<double>(std::max<std::size_t>(facing, 1));
}

double smallest_channel(const image::Image& image) {
  double smallest = 1e30;
  for (float v : image.pixels) smallest = std::min(smallest, static_cast<double>(v));
  return smallest;
}

// test_lighting(3) as the sky plus `sun`, set on `renderer`.
light::SceneLighting light_with_sun(render::Renderer& renderer, const light::Disc& sun) {
  light::SceneLighting lighting;
  lighting.sky = test_lighting(3);
  lighting.discs = {sun};
  renderer.set_lighting(lighting.sky, nullptr);
  renderer.set_discs(lighting.discs);
  return lighting;
}

render::FrameSettings frame(int transfer, const render::Camera& camera) {
  render::FrameSettings s;
  s.camera = camera;
  s.transfer = transfer;
  s.background = render::Background::black;
  return s;
}

// The box on the floor in a headless renderer, the test sun and Embree's visibility of it per vertex.
struct SunScene {
  render::HeadlessContext context;
  render::Renderer renderer;
  mesh::Mesh mesh = box_on_floor();
  light::Disc sun = test_sun();
  std::vector<float> rays;
  SunScene() {
    renderer.set_mesh(mesh);
    const trace::Scene scene(mesh);
    rays = shade::disc_visibility(mesh, sun, scene);
  }
};

struct GlossyFrame {
  image::Image gpu;
  std::vector<std::uint32_t> ids;
  std::vector<float> map;  ///< the shadow map's visibility at the vertices
};

// Renders glossy transfer `index` with `surface` (matrix `b`) under `sky` and `sun`, looking down the
// sun's mirror direction off the floor (azimuth -120, elevation 44 degrees): the highlight is in view.
GlossyFrame render_glossy_with_sun(render::Renderer& renderer, int index, const brdf::Brdf& surface, const brdf::BrdfMatrix& b,
                                   const sh::RgbCoefficients& sky, const light::Disc& sun) {
  renderer.set_brdf(index, b, surface);
  renderer.set_lighting(sky, nullptr);
  renderer.set_discs({sun});
  const render::FrameSettings settings = frame(index, render::Camera{-120.0, 40.0, 0.0});
  renderer.render(settings, kWidth, kHeight);
  return {renderer.read_radiance(), renderer.read_triangle_ids(), renderer.shadow_visibility(settings, 0)};
}

// The disc's direct light toward v at a point of a face with normal n, visibility `visible`:
// E fbar(F^T d, F^T v) cos V with brdf::eval_cosine in the face's frame.
glm::dvec3 glossy_direct(const brdf::Brdf& surface, const light::Disc& sun, const glm::dvec3& n, const glm::dvec3& v, double visible) {
  const glm::dmat3 to_local = glm::transpose(brdf::shading_frame(n));
  return sun.irradiance * brdf::eval_cosine(surface, to_local * sun.direction, to_local * v) * visible;
}

// The GPU frame against the CPU image on uniformly lit or shadowed triangles: max relative error <= bound.
void check_uniform(const GlossyFrame& f, const image::Image& cpu, const mesh::Mesh& mesh, const std::vector<float>& rays, double bound) {
  std::size_t counted = 0;
  const double worst = uniform_error(f.gpu, cpu, f.ids, uniform_triangles(mesh, rays, f.map), counted);
  INFO("pixels on uniformly lit or shadowed triangles " << counted << ", max relative error " << worst);
  CHECK(counted > static_cast<std::size_t>(kWidth * kHeight / 10));
  CHECK(worst <= bound);
  CHECK(smallest_channel(f.gpu) >= 0.0);
}

}  // namespace

TEST_CASE("diffuse render with a sun equals shade_diffuse_split on the box and floor", "[render][gl][sun]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  const mesh::Mesh mesh = box_on_floor();
  renderer.set_mesh(mesh);
  const light::Disc sun = test_sun();
  const trace::Scene scene(mesh);
  const std::vector<float> rays = shade::disc_visibility(mesh, sun, scene);

  // Also CPCA-compressed (renderer_cpca.cpp): its bounce-only part in the products, the direct light as here.
  for (const bool compressed : {false, true})
  for (const transfer::Kind kind : {transfer::Kind::shadowed, transfer::Kind::interreflected}) {
    SECTION(std::string(transfer::kind_name(kind)) + (compressed ? ", CPCA K 24 N 4" : "")) {
      const transfer::TransferData baked = bake_transfer(mesh, kind, 3);
      if (kind == transfer::Kind::interreflected) REQUIRE(!baked.bounce_only.empty());
      const compress::CompressedTransfer model = compress::compress_transfer(baked, {24, 4}, transfer::Scalar::float32, "test");
      const transfer::TransferData transfer = compressed ? compress::decompress(model) : baked;  // what the GPU should shade
      const int index = compressed ? renderer.add_compressed(model, "test") : renderer.add_transfer(transfer, "test");
      renderer.set_surface_albedo(index, shade::surface_albedo(mesh, transfer.header, "test"));
      const light::SceneLighting lighting = light_with_sun(renderer, sun);
      const render::FrameSettings settings = frame(index, render::Camera{30.0, 35.0, 0.0});
      renderer.render(settings, kWidth, kHeight);
      const image::Image gpu = renderer.read_radiance();
      const std::vector<std::uint32_t> ids = renderer.read_triangle_ids();
      const std::vector<float> map = renderer.shadow_visibility(settings, 0);

      const std::vector<glm::vec3> cpu_vertex = shade::shade_diffuse_split(mesh, transfer, lighting, "test");
      const image::Image cpu = interpolate_on_cpu(mesh, cpu_vertex, renderer.last_model_view_projection(), ids, kWidth, kHeight);
      std::size_t counted = 0;
      const double worst = uniform_error(gpu, cpu, ids, uniform_triangles(mesh, rays, map), counted);
      INFO("pixels on uniformly lit or shadowed triangles " << counted << ", max relative error " << worst);
      CHECK(counted > static_cast<std::size_t>(kWidth * kHeight / 10));
      CHECK(worst <= 1e-3);
      CHECK(smallest_channel(gpu) >= 0.0);
    }
  }
}

// The deferred disc pass on a curved mesh: at every pixel of a triangle the rays and the map both see
// uniformly lit or shadowed, the GPU equals, computed here per pixel from the CPU rasteriser's
// perspective-correct barycentrics b: sum b_i rest_i + (sum b_i albedo_i) / pi E max(normalize(sum b_i
// n_i) . d, 0) V, with rest = split shading minus its direct term at the vertices (the sky and bounce
// light, which the mesh draw interpolates) and V the triangle's visibility. The box's flat faces
// cannot tell a wrong interpolation of the normal or the albedo; the lion's curved ones do.
TEST_CASE("deferred disc pass on the lion equals the direct light evaluated per pixel", "[render][gl][sun]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  const mesh::Mesh mesh = mesh::load_mesh(PRT_SOURCE_DIR "/assets/meshes/guardian_lion_10k.ply", nullptr, true);
  renderer.set_mesh(mesh);
  light::Disc sun = test_sun();
  sun.direction = glm::normalize(glm::dvec3(0.3, 0.8, 0.5));
  const trace::Scene scene(mesh);
  const std::vector<float> rays = shade::disc_visibility(mesh, sun, scene);
  const transfer::TransferData transfer = bake_transfer(mesh, transfer::Kind::shadowed, 3);
  const int index = renderer.add_transfer(transfer, "test");
  const std::vector<glm::vec3> albedo = shade::surface_albedo(mesh, transfer.header, "test");
  renderer.set_surface_albedo(index, albedo);
  const light::SceneLighting lighting = light_with_sun(renderer, sun);
  const render::FrameSettings settings = frame(index, render::Camera{40.0, 30.0, 0.0});
  renderer.render(settings, kWidth, kHeight);
  const image::Image gpu = renderer.read_radiance();
  const std::vector<std::uint32_t> ids = renderer.read_triangle_ids();
  const std::vector<bool> uniform = uniform_triangles(mesh, rays, renderer.shadow_visibility(settings, 0));

  const std::vector<glm::vec3> split = shade::shade_diffuse_split(mesh, transfer, lighting, "test");
  const std::vector<glm::vec3> direct = shade::disc_direct_diffuse(mesh, albedo, lighting.discs, &scene);
  std::vector<bool> usable(uniform);  // no clamp at a corner: split - direct is the rest there
  for (std::size_t t = 0; t < usable.size(); ++t)
    for (int k = 0; k < 3; ++k) usable[t] = usable[t] && glm::all(glm::greaterThan(split[mesh.indices[3 * t + k]], glm::vec3(0.0f)));
  const image::Image cpu = per_pixel_on_cpu(mesh, renderer.last_model_view_projection(), ids, kWidth, kHeight, [&](const PixelPoint& p) {
    glm::dvec3 rest(0.0), a(0.0), n(0.0);
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t v = p.corner[i];
      rest += p.weight[i] * glm::dvec3(split[v] - direct[v]);
      a += p.weight[i] * glm::dvec3(albedo[v]);
      n += p.weight[i] * glm::dvec3(mesh.normals[v]);
    }
    const double visibility = rays[p.corner[0]];  // 1 or 0 on a uniform triangle
    const double cosine = std::max(0.0, glm::dot(glm::normalize(n), sun.direction));
    return glm::max(rest + a / 3.14159265358979323846 * sun.irradiance * (cosine * visibility), glm::dvec3(0.0));
  });
  // Per pixel, the largest relative error over the channels (denominator floored at 2% of the largest
  // value). A penumbra may reach into a triangle whose corners are lit (the map resolves shadows per
  // pixel, the corners do not see them): a few pixels differ for that reason, hence the 99th percentile.
  double largest = 0.0;
  for (float v : cpu.pixels) largest = std::max(largest, std::abs(static_cast<double>(v)));
  std::vector<double> errors;
  std::size_t lit = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const std::uint32_t t = ids[static_cast<std::size_t>(y) * kWidth + x];
      if (t == render::kNoTriangle || !usable[t]) continue;
      lit += rays[mesh.indices[3 * t]] == 1.0f;
      double e = 0.0;
      for (int c = 0; c < 3; ++c)
        e = std::max(e, std::abs(gpu.at(x, y, c) - cpu.at(x, y, c)) / std::max(std::abs(double(cpu.at(x, y, c))), 0.02 * largest));
      errors.push_back(e);
    }
  std::sort(errors.begin(), errors.end());
  REQUIRE(errors.size() > static_cast<std::size_t>(kWidth * kHeight / 20));
  const double p99 = errors[errors.size() * 99 / 100], median = errors[errors.size() / 2];
  std::printf("deferred pass on the lion: %zu pixels on uniform triangles (%zu lit), relative error median %.2g, 99th "
              "percentile %.2g, largest %.2g\n", errors.size(), lit, median, p99, errors.back());
  CHECK(lit > errors.size() / 4);
  CHECK(p99 <= 1e-3);
  CHECK(smallest_channel(gpu) >= 0.0);
}

TEST_CASE("glossy render with a sun equals the split glossy shading with the BRDF evaluated exactly", "[render][gl][sun][glossy]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  const mesh::Mesh mesh = box_on_floor();
  renderer.set_mesh(mesh);
  const light::Disc sun = test_sun();
  const trace::Scene scene(mesh);
  const std::vector<float> rays = shade::disc_visibility(mesh, sun, scene);
  const char* specs[] = {"phong:exponent=20,ks=0.5,kd=0.4", "ggx:roughness=0.4,f0=0.9/0.6/0.3,albedo=0.2/0.3/0.4",
                         "blinn:exponent=30,ks=0.6,kd=0.3", "gltf:basecolor=0.8/0.5/0.3,metallic=0.3,roughness=0.5"};
  for (const char* spec : specs) {
    SECTION(spec) {
      const transfer::TransferData transfer = bake_transfer(mesh, transfer::Kind::glossy_interreflected, 3, spec);
      REQUIRE(!transfer.bounce_only.empty());
      const brdf::Brdf surface = brdf::parse_brdf(spec);
      const brdf::BrdfMatrix b = brdf::project(surface, 3);
      const sh::RgbCoefficients sky = test_lighting(3);
      const GlossyFrame f = render_glossy_with_sun(renderer, renderer.add_transfer(transfer, "test"), surface, b, sky, sun);
      const std::vector<std::uint32_t>& ids = f.ids;

      // CPU: O of the sky through the full transfer plus O of the disc's SH through the bounce-only
      // part (as shade_glossy_split), evaluated toward the eye per pixel, plus the disc's direct light
      // with brdf::eval_cosine at the pixel in the face's frame, visibility from the corners' rays.
      std::vector<glm::vec3> outgoing = shade::glossy_outgoing_coefficients(transfer, b, sky);
      transfer::TransferData bounce = transfer;
      bounce.values = transfer.bounce_only;
      const std::vector<glm::vec3> disc_o = shade::glossy_outgoing_coefficients(bounce, b, light::disc_coefficients(3, sun));
      for (std::size_t i = 0; i < outgoing.size(); ++i) outgoing[i] += disc_o[i];
      const render::ViewMatrices& view = renderer.last_view();
      const glm::dvec3 eye = view.eye;  // no object rotation: mesh coordinates are world coordinates
      const image::Image cpu = per_pixel_on_cpu(mesh, renderer.last_model_view_projection(), ids, kWidth, kHeight, [&](const PixelPoint& p) {
        const glm::dvec3 v = glm::normalize(eye - p.position);
        // Split shading clamps each channel at 0 (the disc's bounce light through the glossy bounce-only
        // matrices, 3 bands of a small cap, rings below zero).
        return glm::max(glossy_prt_at(mesh, outgoing, 3, p, v) +
                            glossy_direct(surface, sun, glm::dvec3(mesh.normals[p.corner[0]]), v, rays[p.corner[0]]),
                        glm::dvec3(0.0));
      });
      check_uniform(f, cpu, mesh, rays, 2e-3);
    }
  }
}

// One BRDF per vertex (Renderer::set_brdfs, a --brdf mesh bake): each vertex's O through its own BRDF's
// matrix, and the disc's direct light of each corner's BRDF blended with the pixel's barycentrics.
TEST_CASE("glossy render with one BRDF per vertex and a sun equals the split shading of each vertex's BRDF",
          "[render][gl][sun][glossy][materials]") {
  SunScene box;
  render::Renderer& renderer = box.renderer;
  const mesh::Mesh& mesh = box.mesh;
  brdf::VertexBrdfs brdfs;
  for (const char* spec : {"gltf:basecolor=0.8/0.5/0.3,metallic=0,roughness=0.3", "gltf:basecolor=0.6/0.6/0.7,metallic=0.6,roughness=0.8",
                           "phong:exponent=20,ks=0.5,kd=0.4"})
    brdfs.table.push_back(brdf::parse_brdf(spec));
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) brdfs.vertex.push_back(std::uint32_t((v * 7 / 3) % 3));
  const transfer::TransferData transfer = bake_transfer(mesh, transfer::Kind::glossy_interreflected, 3, "phong:exponent=8,kd=0.5,ks=0.3");
  const sh::RgbCoefficients sky = test_lighting(3);
  const int index = renderer.add_transfer(transfer, "test");
  renderer.set_brdfs(index, brdfs);
  renderer.set_lighting(sky, nullptr);
  renderer.set_discs({box.sun});
  const render::FrameSettings settings = frame(index, render::Camera{-120.0, 40.0, 0.0});
  renderer.render(settings, kWidth, kHeight);
  const GlossyFrame f{renderer.read_radiance(), renderer.read_triangle_ids(), renderer.shadow_visibility(settings, 0)};
  // CPU: each BRDF's O for every vertex (as shade_glossy_vertex_brdfs), each vertex keeping its own.
  transfer::TransferData bounce = transfer;
  bounce.values = transfer.bounce_only;
  std::vector<glm::vec3> outgoing(mesh.vertex_count() * 9);
  for (std::size_t b = 0; b < brdfs.table.size(); ++b) {
    const brdf::BrdfMatrix matrix = brdf::project(brdfs.table[b], 3);
    std::vector<glm::vec3> o = shade::glossy_outgoing_coefficients(transfer, matrix, sky);
    const std::vector<glm::vec3> disc_o = shade::glossy_outgoing_coefficients(bounce, matrix, light::disc_coefficients(3, box.sun));
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
      if (brdfs.vertex[v] == b)
        for (std::size_t k = 0; k < 9; ++k) outgoing[v * 9 + k] = o[v * 9 + k] + disc_o[v * 9 + k];
  }
  const glm::dvec3 eye = renderer.last_view().eye;
  const image::Image cpu = per_pixel_on_cpu(mesh, renderer.last_model_view_projection(), f.ids, kWidth, kHeight, [&](const PixelPoint& p) {
    const glm::dvec3 v = glm::normalize(eye - p.position);
    glm::dvec3 direct(0.0);
    for (int c = 0; c < 3; ++c)
      direct += p.weight[c] * glossy_direct(brdfs.table[brdfs.vertex[p.corner[c]]], box.sun, glm::dvec3(mesh.normals[p.corner[0]]), v,
                                            box.rays[p.corner[0]]);
    return glm::max(glossy_prt_at(mesh, outgoing, 3, p, v) + direct, glm::dvec3(0.0));
  });
  check_uniform(f, cpu, mesh, box.rays, 2e-3);
}

TEST_CASE("glossy CPCA render with a sun: per-vertex PRT of the model plus the disc's direct light per pixel", "[render][gl][sun][glossy][compress]") {
  SunScene box;
  render::Renderer& renderer = box.renderer;
  const mesh::Mesh& mesh = box.mesh;
  const light::Disc& sun = box.sun;
  const std::vector<float>& rays = box.rays;
  const char* spec = "phong:exponent=20,ks=0.5,kd=0.4";
  const transfer::TransferData baked = bake_transfer(mesh, transfer::Kind::glossy_interreflected, 3, spec);
  const compress::CompressedTransfer model = compress::compress_transfer(baked, {24, 4}, transfer::Scalar::float32, "test");
  REQUIRE(model.bounce);
  const brdf::Brdf surface = brdf::parse_brdf(spec);
  const brdf::BrdfMatrix b = brdf::project(surface, 3);
  const sh::RgbCoefficients sky = test_lighting(3);
  const GlossyFrame f = render_glossy_with_sun(renderer, renderer.add_compressed(model, "test"), surface, b, sky, sun);
  const std::vector<std::uint32_t>& ids = f.ids;

  // CPU: the decompressed model's PRT toward the eye AT THE VERTICES (the CPCA pass is per vertex: sky
  // through the transfer plus the disc's SH through the bounce-only part), interpolated, plus the
  // disc's direct light at the pixel as in the uncompressed case above; clamped at 0.
  const transfer::TransferData approximate = compress::decompress(model);
  transfer::TransferData bounce = approximate;
  bounce.values = approximate.bounce_only;
  const glm::vec3 eye(renderer.last_view().eye);
  std::vector<glm::vec3> vertex = shade::shade_glossy_eye(approximate, b, sky, mesh.positions, mesh.normals, eye);
  const std::vector<glm::vec3> vertex_bounce =
      shade::shade_glossy_eye(bounce, b, light::disc_coefficients(3, sun), mesh.positions, mesh.normals, eye);
  for (std::size_t v = 0; v < vertex.size(); ++v) vertex[v] += vertex_bounce[v];
  const image::Image cpu = per_pixel_on_cpu(mesh, renderer.last_model_view_projection(), ids, kWidth, kHeight, [&](const PixelPoint& p) {
    glm::dvec3 prt(0.0);
    for (int k = 0; k < 3; ++k) prt += p.weight[k] * glm::dvec3(vertex[p.corner[k]]);
    const glm::dvec3 v = glm::normalize(glm::dvec3(eye) - p.position);
    return glm::max(prt + glossy_direct(surface, sun, glm::dvec3(mesh.normals[p.corner[0]]), v, rays[p.corner[0]]), glm::dvec3(0.0));
  });
  check_uniform(f, cpu, mesh, rays, 2e-3);
}

TEST_CASE("shadow-map visibility at the vertices agrees with Embree's disc rays", "[render][gl][sun]") {
  render::HeadlessContext context;
  struct Case {
    const char* name;
    mesh::Mesh mesh;
    glm::dvec3 direction;
  };
  std::vector<Case> cases;
  cases.push_back({"box on a floor", box_on_floor(), {0.6, 0.7, 0.35}});
  cases.push_back({"box on a floor, low sun", box_on_floor(), {-0.8, 0.3, 0.2}});
  cases.push_back({"lion (guardian_lion_10k)", mesh::load_mesh(PRT_SOURCE_DIR "/assets/meshes/guardian_lion_10k.ply", nullptr, true),
                   {0.3, 0.8, -0.5}});
  for (const Case& c : cases) {
    SECTION(c.name) {
      render::Renderer renderer;
      renderer.set_mesh(c.mesh);
      const int index = renderer.add_transfer(unshadowed_transfer(c.mesh, 2, 1, glm::vec3(0.8f)), "test");
      light::Disc sun = test_sun();
      sun.direction = glm::normalize(c.direction);
      renderer.set_discs({sun});
      const std::vector<float> map = renderer.shadow_visibility(frame(index, render::Camera{}), 0);
      const std::vector<float> rays = shade::disc_visibility(c.mesh, sun, trace::Scene(c.mesh));
      std::size_t facing = 0, shadowed = 0;
      const double differ = disagreement(c.mesh, sun, map, rays, facing);
      for (std::size_t v = 0; v < rays.size(); ++v)
        shadowed += rays[v] < 0.5f && glm::dot(glm::dvec3(c.mesh.normals[v]), sun.direction) > 0.0;
      std::printf("shadow map vs rays, %s: %.3f%% of the %zu vertices facing the disc disagree (%zu of them in shadow)\n", c.name,
                  100.0 * differ, facing, shadowed);
      CHECK(shadowed > facing / 20);  // the shadow is a real test
      if (std::getenv("PRT_DEBUG_SUN")) for (std::size_t v = 0, shown = 0; v < rays.size() && shown < 40; ++v)
        if (glm::dot(glm::dvec3(c.mesh.normals[v]), sun.direction) > 0.0 && (map[v] >= 0.5f) != (rays[v] >= 0.5f)) {
          ++shown;
          std::printf("  v%zu p %.3f %.3f %.3f n %.2f %.2f %.2f map %.3f rays %.3f\n", v, c.mesh.positions[v].x, c.mesh.positions[v].y,
                      c.mesh.positions[v].z, c.mesh.normals[v].x, c.mesh.normals[v].y, c.mesh.normals[v].z, map[v], rays[v]);
        }
      CHECK(differ <= 0.01);
    }
  }
}

TEST_CASE("shadow maps are redrawn when the lighting changes and only then", "[render][gl][sun]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  const mesh::Mesh mesh = box_on_floor();
  renderer.set_mesh(mesh);
  const int index = renderer.add_transfer(bake_transfer(mesh, transfer::Kind::shadowed, 2), "test");
  renderer.set_lighting(test_lighting(2), nullptr);
  renderer.set_discs({test_sun()});
  render::FrameSettings settings = frame(index, render::Camera{});
  renderer.render(settings, 64, 48);
  CHECK(renderer.shadow_map_updates() == 1);
  settings.camera.azimuth_degrees = 50.0;  // the camera alone: no redraw
  renderer.render(settings, 64, 48);
  renderer.render(settings, 64, 48);
  CHECK(renderer.shadow_map_updates() == 1);
  const image::Image before = renderer.read_radiance();
  settings.environment_rotation = sh::rotation_from_yaw_pitch_roll(40.0, 0.0, 0.0);
  renderer.render(settings, 64, 48);  // redrawn within this frame
  CHECK(renderer.shadow_map_updates() == 2);
  settings.object_rotation = sh::rotation_from_yaw_pitch_roll(0.0, 10.0, 0.0);
  renderer.render(settings, 64, 48);
  CHECK(renderer.shadow_map_updates() == 3);
  renderer.set_discs({test_sun()});
  renderer.render(settings, 64, 48);
  CHECK(renderer.shadow_map_updates() == 4);
  settings.sun = false;  // the sun off: no map needed
  renderer.render(settings, 64, 48);
  CHECK(renderer.shadow_map_updates() == 4);
  CHECK(before.width == 64);
}

TEST_CASE("prt render --sun none --window none reproduces the pre-sun image bit for bit", "[render][gl][sun][cli]") {
  // tests/render/data/golden_sun_none.exr: `prt render mesh.ply transfer.prt --env env.exr --size 64x48`
  // on the files of write_fixture_files, by the prt binary of commit b33d0aa (before discs and windows;
  // see tests/render/data/README.md).
  const std::string dir = test::fresh_temp_dir("render_sun_golden");
  write_fixture_files(dir);
  const std::string out = dir + "/none.exr";
  const test::RunResult r = test::run_prt("render " + dir + "/mesh.ply " + dir + "/transfer.prt --env " + dir +
                                          "/env.exr --size 64x48 --sun none --window none -q -o " + out);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const image::Image got = image::read_rgb(out);
  const image::Image golden = image::read_rgb(PRT_SOURCE_DIR "/tests/render/data/golden_sun_none.exr");
  REQUIRE(got.width == golden.width);
  REQUIRE(got.height == golden.height);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < got.pixels.size(); ++i) differ += std::memcmp(&got.pixels[i], &golden.pixels[i], sizeof(float)) != 0;
  CHECK(differ == 0);
}

TEST_CASE("prt render and view: a malformed --sun or --window is a one-line error", "[render][sun][cli]") {
  const std::string dir = test::fresh_temp_dir("render_sun_errors");
  write_fixture_files(dir);
  const std::string base = "render " + dir + "/mesh.ply " + dir + "/transfer.prt --env " + dir + "/env.exr --size 32x24 -o " + dir + "/x.exr ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {base + "--sun 1,2", "--sun: expected auto, none"},
      {base + "--sun 0,1,0,1,1,1,0", "--sun: the angular radius must lie in (0, 45]"},
      {base + "--sun 0,1,0,-1,1,1,1", "--sun: the irradiance R,G,B must be >= 0"},
      {base + "--sun 0,0,0,1,1,1,1", "--sun: the direction must be finite and not zero"},
      {base + "--window sinc", "--window"},
      {"view " + dir + "/mesh.ply " + dir + "/transfer.prt --env " + dir + "/env.exr --sun 0,1,0,1,1,1,90 --frames 1", "--sun: the angular radius"},
  };
  for (const auto& [arguments, expected] : cases) {
    const test::RunResult r = test::run_prt(arguments);
    INFO(arguments << "\n" << r.output);
    CHECK(test::fails_in_one_line(r, expected));
  }
  std::error_code error;
  CHECK(!std::filesystem::exists(dir + "/x.exr", error));
}
