// The GPU's glossy PRT pass computes what the CPU does: headless renders of glossy transfers against
// prt::shade::glossy_outgoing_coefficients (the O of `prt shade`) evaluated on the CPU, pixel by pixel,
// with the same camera convention: for the point p the CPU's own ray through the pixel centre meets
// (cpu_raster.h, barycentrics b), the view v = normalize(eye - p) in mesh coordinates, and
// sum_i b_i sum_k O_i[k] Y_k(F_i^T v) in each corner's own frame (renderer.h, prt_glossy). At a vertex
// that is exactly prt shade's radiance toward the eye.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

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

// The GPU frame `gpu` (drawn with `settings`) against glossy_on_cpu of `outgoing`: the largest error
// over the interior pixels relative to max(|cpu|, 2% of the CPU image's largest value); `covered`: how
// many pixels were compared.
double error_against_cpu(const mesh::Mesh& mesh, const image::Image& gpu, const std::vector<glm::vec3>& outgoing, int out_bands,
                         const render::FrameSettings& settings, std::size_t& covered) {
  glm::dvec3 eye_object;
  const std::vector<PixelHit> hits = cast_pixels(mesh, settings.camera.azimuth_degrees, settings.camera.elevation_degrees,
                                                 settings.camera.distance, settings.object_rotation, kWidth, kHeight, &eye_object);
  const image::Image cpu = glossy_on_cpu(mesh, outgoing, out_bands, eye_object, hits);
  double largest = 0.0;
  for (float v : cpu.pixels) largest = std::max(largest, std::abs(static_cast<double>(v)));
  return max_relative_error_interior(gpu, cpu, hits, 0.02 * largest, covered);
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
      std::size_t covered = 0;
      const double worst = error_against_cpu(mesh, gpu, outgoing, c.bands_out, settings, covered);
      INFO("compared pixels " << covered << ", max error relative to max(|cpu|, 2% of the largest) " << worst);
      CHECK(covered > static_cast<std::size_t>(kWidth * kHeight / 20));
      CHECK(worst <= kGlossyTolerance);
    }
  }
}

// One BRDF per vertex (Renderer::set_brdfs, a --brdf mesh bake): each vertex's O is prt shade's with its
// own BRDF (shade_glossy_vertex_brdfs keeps, per vertex, glossy_outgoing_coefficients of that BRDF's
// matrix); vertices of one triangle with different BRDFs blend as any corners do.
TEST_CASE("headless glossy render with one BRDF per vertex equals prt shade's outgoing coefficients of each vertex's BRDF",
          "[render][gl][glossy][materials]") {
  render::HeadlessContext context;
  render::Renderer renderer;
  const mesh::Mesh mesh = bumpy_sphere(16, 32, glm::vec3(0.2f, -0.1f, 0.1f));
  renderer.set_mesh(mesh);
  brdf::VertexBrdfs brdfs;
  for (const char* spec : {"gltf:basecolor=0.8/0.5/0.3,metallic=0,roughness=0.3", "ggx:roughness=0.4,f0=0.9/0.6/0.3,albedo=0.2/0.3/0.4",
                           "phong:exponent=20,ks=0.5,kd=0.4"})
    brdfs.table.push_back(brdf::parse_brdf(spec));
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) brdfs.vertex.push_back(std::uint32_t(v % 7 < 3 ? 0 : v % 7 < 5 ? 1 : 2));
  const transfer::TransferData transfer =
      glossy_transfer(mesh, transfer::Kind::glossy_interreflected, 4, 4, "phong:exponent=8,kd=0.5,ks=0.3");
  const int index = renderer.add_transfer(transfer, "test");
  renderer.set_brdfs(index, brdfs);
  const sh::RgbCoefficients lighting = test_lighting(4);
  renderer.set_lighting(lighting, nullptr);
  render::FrameSettings settings = black_frame(index, 0, {40, 10, 0}, {0, 0, 0});
  settings.camera = render::Camera{35.0, 25.0, 4.0};
  renderer.render(settings, kWidth, kHeight);
  const image::Image gpu = renderer.read_radiance();

  const sh::RgbCoefficients seen = sh::Rotation(lighting.bands, settings.environment_rotation).apply(lighting);
  std::vector<glm::vec3> outgoing(mesh.vertex_count() * 16);
  for (std::size_t b = 0; b < brdfs.table.size(); ++b) {
    const std::vector<glm::vec3> o = shade::glossy_outgoing_coefficients(transfer, brdf::project(brdfs.table[b], 4), seen);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
      if (brdfs.vertex[v] == b) std::copy(o.begin() + long(v * 16), o.begin() + long(v * 16 + 16), outgoing.begin() + long(v * 16));
  }
  std::size_t covered = 0;
  const double worst = error_against_cpu(mesh, gpu, outgoing, 4, settings, covered);
  INFO("compared pixels " << covered << ", max error relative to max(|cpu|, 2% of the largest) " << worst);
  CHECK(covered > static_cast<std::size_t>(kWidth * kHeight / 20));
  // Corners of different BRDFs differ by up to a few times their value, so the radiance changes steeply
  // across such a triangle: the rasteriser's sub-pixel snapping (1/256 pixel on llvmpipe) of the point
  // the GPU evaluates, against the CPU's exact pixel centre, moves it by up to about 1e-4 of those
  // differences (with one BRDF everywhere this test passes at kGlossyTolerance). A vertex read with
  // another BRDF's matrix is off by tens of percent.
  CHECK(worst <= 1e-3);
  // A table whose vertex indices do not fit the mesh is refused.
  brdf::VertexBrdfs wrong = brdfs;
  wrong.vertex.pop_back();
  CHECK_THROWS_WITH(renderer.set_brdfs(index, wrong), Catch::Contains("vertex indices for"));
  wrong = brdfs;
  wrong.vertex[0] = 3;
  CHECK_THROWS_WITH(renderer.set_brdfs(index, wrong), Catch::Contains("BRDF index 3 is not below the table's 3"));
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

// Through the binary: an OBJ floor and wall with two MTL materials whose Pr / Pm differ (--brdf mesh, the
// default of glossy bakes: two BRDFs, floor and wall sharing no vertex). prt render of that one file
// shows, at each pixel, what the same file rendered with the floor's BRDF for all vertices shows, or
// what it rendered with the wall's shows: each triangle in its own material's BRDF, discs included.
TEST_CASE("prt render of a --brdf mesh bake shows each material's own BRDF", "[render][gl][glossy][cli][materials]") {
  const std::string dir = test::fresh_temp_dir("render_glossy_materials");
  write_fixture_files(dir);  // env.exr
  std::ofstream(dir + "/two.mtl") << "newmtl floor\nKd 0.8 0.5 0.3\nPr 0.3\nPm 0\nnewmtl wall\nKd 0.6 0.6 0.7\nPr 0.8\nPm 0.6\n";
  std::ofstream obj(dir + "/two.obj");
  obj << "mtllib two.mtl\nvn 0 1 0\nvn 0 0 1\n";
  const int n = 6;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) obj << "v " << -1.0 + 2.0 * i / (n - 1) << " 0 " << -1.0 + 2.0 * j / (n - 1) << '\n';
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) obj << "v " << -1.0 + 2.0 * i / (n - 1) << ' ' << 1.2 * j / (n - 1) << " -0.3\n";
  for (int part = 0; part < 2; ++part) {
    obj << (part == 0 ? "usemtl floor\n" : "usemtl wall\n");
    auto corner = [&](int i, int j) { return std::to_string(1 + part * n * n + j * n + i) + "//" + std::to_string(part + 1) + " "; };
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i) {
        const bool floor_winding = part == 0;  // counter-clockwise seen from the normal's side
        obj << "f " << corner(i, j) << (floor_winding ? corner(i, j + 1) + corner(i + 1, j + 1) : corner(i + 1, j) + corner(i + 1, j + 1)) << '\n';
        obj << "f " << corner(i, j) << (floor_winding ? corner(i + 1, j + 1) + corner(i + 1, j) : corner(i + 1, j + 1) + corner(i, j + 1)) << '\n';
      }
  }
  obj.close();
  const std::string mesh = dir + "/two.obj", prt_file = dir + "/two.prt";
  REQUIRE(test::run_prt("bake " + mesh + " --transfer glossy-interreflected --bands 3 --bounces 1 --samples 64 -q -o " + prt_file).exit_code == 0);
  const std::string view = " --env " + dir + "/env.exr --sun 0.3,1,0.5,4,4,4,2 --camera 30,35,auto --size 96x72 --background black -q -o " + dir + "/";
  const char* floor_spec = "gltf:basecolor=0.8/0.5/0.3,metallic=0,roughness=0.3";
  const char* wall_spec = "gltf:basecolor=0.6/0.6/0.7,metallic=0.6,roughness=0.8";
  for (const std::string& arguments : {std::string(view + "mesh.exr"), " --brdf " + std::string(floor_spec) + view + "floor.exr",
                                       " --brdf " + std::string(wall_spec) + view + "wall.exr"}) {
    const test::RunResult r = test::run_prt("render " + mesh + " " + prt_file + arguments);
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
  }
  const image::Image both = image::read_rgb(dir + "/mesh.exr"), floor = image::read_rgb(dir + "/floor.exr"),
                     wall = image::read_rgb(dir + "/wall.exr");
  auto same = [](const image::Image& a, const image::Image& b, int x, int y) {
    for (int c = 0; c < 3; ++c)
      if (std::abs(a.at(x, y, c) - b.at(x, y, c)) > 1e-5f * std::max(1.0f, std::abs(b.at(x, y, c)))) return false;
    return true;
  };
  int floor_pixels = 0, wall_pixels = 0, neither = 0;
  for (int y = 0; y < both.height; ++y)
    for (int x = 0; x < both.width; ++x) {
      const bool f = same(both, floor, x, y), w = same(both, wall, x, y);
      floor_pixels += f && !w;
      wall_pixels += w && !f;
      neither += !f && !w;
    }
  INFO("pixels as the floor's BRDF only " << floor_pixels << ", as the wall's only " << wall_pixels << ", as neither " << neither);
  CHECK(floor_pixels > 500);
  CHECK(wall_pixels > 500);
  CHECK(neither == 0);
}
