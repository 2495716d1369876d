// `prt reference --image` against `prt render` (built with PRT_BUILD_GL; EGL surfaceless, no display):
// the same camera covers the same pixels, and the path-traced image of a convex mesh agrees with the
// headless render of its unshadowed bake under the same band-limited lighting.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "image/image.h"
#include "light/environment.h"
#include "mesh/writers.h"
#include "support/run_prt.h"
#include "support/shapes.h"

using namespace prt;

namespace {

std::size_t line_count(const std::string& text) {
  std::size_t lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

// An ellipsoid (a UV sphere scaled by 1.3, 0.8, 1.0): convex, so shadowed and unshadowed transfer agree,
// and not symmetric, so a wrong object or environment rotation shows. Written without normals: both
// tools compute the same area-weighted ones on load.
void write_ellipsoid(const std::string& path, int rings, int segments) {
  mesh::Mesh m = test::uv_sphere(rings, segments);
  for (glm::vec3& p : m.positions) p *= glm::vec3(1.3f, 0.8f, 1.0f);
  mesh::write_ply(path, m.positions, {}, m.indices);
}

// A bright sky with a warm broad lobe over a darker ground (equirect 128 x 64): positive everywhere,
// also after truncation to 5 bands, so every covered pixel of a black-background image is > 0.
void write_sky(const std::string& path) {
  image::Image im(128, 64, 3);
  const glm::dvec3 sun = glm::normalize(glm::dvec3(0.6, 0.7, -0.4));
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const glm::dvec3 d = light::equirect_direction((x + 0.5) / im.width, (y + 0.5) / im.height);
      glm::dvec3 v = d.y > 0 ? glm::dvec3(0.5, 0.6, 0.8) : glm::dvec3(0.35, 0.3, 0.25);
      v += glm::dvec3(2.0, 1.6, 1.0) * std::exp(4.0 * (glm::dot(d, sun) - 1.0));
      for (int c = 0; c < 3; ++c) im.at(x, y, c) = static_cast<float>(v[c]);
    }
  image::write(path, im);
}

bool covered(const image::Image& im, int x, int y) {
  return im.at(x, y, 0) != 0.0f || im.at(x, y, 1) != 0.0f || im.at(x, y, 2) != 0.0f;
}

// Whether pixel (x, y) of `im` has an uncovered 8-neighbour or is itself uncovered: on a silhouette.
bool on_silhouette(const image::Image& im, int x, int y) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int u = x + dx, v = y + dy;
      if (u < 0 || v < 0 || u >= im.width || v >= im.height || !covered(im, u, v)) return true;
    }
  return false;
}

}  // namespace

TEST_CASE("prt reference --image agrees with prt render of an unshadowed bake: same pixels, same radiance",
          "[reference][image][gl][cli]") {
  const std::string dir = test::fresh_temp_dir("reference_image_vs_render");
  const std::string mesh = dir + "/ellipsoid.ply", sky = dir + "/sky.exr", transfer = dir + "/t.prt";
  write_ellipsoid(mesh, 48, 96);
  write_sky(sky);
  const std::string view = " --size 160x120 --camera 35,20,auto --rotate 40,10,0 --object-rotate 25,0,15 "
                           "--background black -q";
  REQUIRE(test::run_prt("bake " + mesh + " --transfer unshadowed --bands 5 --albedo 0.8,0.6,0.4 -q -o " + transfer)
              .exit_code == 0);
  const test::RunResult rendered = test::run_prt("render " + mesh + " " + transfer + " --env " + sky + view +
                                                 " -o " + dir + "/render.exr");
  INFO(rendered.output);
  REQUIRE(rendered.exit_code == 0);
  const test::RunResult traced = test::run_prt("reference " + mesh + " --env " + sky + view +
                                               " --image --band-limit 5 --albedo 0.8,0.6,0.4 --spp 256 -o " + dir +
                                               "/reference.exr");
  INFO(traced.output);
  REQUIRE(traced.exit_code == 0);
  const image::Image r = image::read_rgb(dir + "/render.exr"), t = image::read_rgb(dir + "/reference.exr");
  REQUIRE(r.width == t.width);
  REQUIRE(r.height == t.height);

  // Camera agreement: the covered masks are equal except on silhouettes, where a pixel centre within
  // rounding of a boundary edge may fall either way in the rasteriser and in Embree.
  std::size_t covered_render = 0, both = 0, mismatched = 0, mismatched_inside = 0;
  double sum_sq = 0.0, reference_sq = 0.0, sum_render = 0.0, sum_reference = 0.0;
  for (int y = 0; y < r.height; ++y)
    for (int x = 0; x < r.width; ++x) {
      const bool in_r = covered(r, x, y), in_t = covered(t, x, y);
      covered_render += in_r;
      if (in_r != in_t) {
        ++mismatched;
        if (!on_silhouette(in_r ? r : t, x, y)) ++mismatched_inside;
        continue;
      }
      if (!in_r) continue;
      ++both;
      for (int c = 0; c < 3; ++c) {
        const double a = r.at(x, y, c), b = t.at(x, y, c);
        sum_sq += (a - b) * (a - b);
        reference_sq += b * b;
        sum_render += a;
        sum_reference += b;
      }
    }
  INFO("covered by render " << covered_render << ", by both " << both << ", mismatched " << mismatched);
  CHECK(covered_render > 2500);
  CHECK(mismatched_inside == 0);
  CHECK(mismatched <= covered_render / 200);  // measured: 0 of 2953

  // Radiance over the pixels both cover. The reference evaluates each pixel's own surface point; the
  // render interpolates the vertices' radiance linearly across each triangle. For lighting of 5 bands
  // the interpolation error is about (h^2 / 8) l (l + 1) of the band-l part, h = pi / 48 the cell size:
  // 5e-4 l (l + 1), at most ~3e-3 of the l = 2 part, which is a fraction of the whole radiance. The
  // rest is the reference's Monte Carlo noise, which falls as 1 / paths here (stratified first bounce).
  // Measured rel_rms: 0.0095 at 64 paths per pixel, 0.0023 at 256, 0.00057 at 1024: the interpolation
  // error is below 6e-4. Bounds at 256 paths: rel_rms <= 0.5%, means equal within 0.1% (measured 2e-4;
  // a bias, e.g. from a wrong rotation or albedo, would show there first).
  const double rel_rms = std::sqrt(sum_sq / reference_sq);
  INFO("rel_rms " << rel_rms << ", mean ratio " << sum_render / sum_reference);
  CHECK(rel_rms <= 0.005);
  CHECK(sum_render / sum_reference == Approx(1.0).epsilon(0.001));

  // The same through `prt compare` (all pixels, background included: black in both).
  const test::RunResult compared = test::run_prt("compare " + dir + "/render.exr " + dir + "/reference.exr --heatmap " +
                                                 dir + "/heat.png");
  INFO(compared.output);
  CHECK(compared.exit_code == 0);
  CHECK(line_count(compared.output) == 1);
  CHECK(compared.output.find("pixels=19200") != std::string::npos);
  CHECK(test::entries_in(dir) == 6);  // mesh, sky, transfer, two images, heatmap
}

TEST_CASE("prt reference --image shows the environment behind the mesh as prt render --background env does",
          "[reference][image][gl][cli]") {
  // With --band-limit the reference lights with the band-limited environment but shows the image as
  // loaded, as prt render shows the image and lights with its projection: background pixels equal up
  // to the precision of the GPU's bilinear weights (GPUs interpolate with as few as 8 fractional bits:
  // 1/256 of a step between texels, at most ~1e-3 on this sky). Measured on llvmpipe: 2.1e-4.
  const std::string dir = test::fresh_temp_dir("reference_image_background");
  const std::string mesh = dir + "/ellipsoid.ply", sky = dir + "/sky.exr", transfer = dir + "/t.prt";
  write_ellipsoid(mesh, 12, 24);
  write_sky(sky);
  const std::string view = " --size 64x48 --camera -60,-10,5 --rotate 70,20,0 -q";
  REQUIRE(test::run_prt("bake " + mesh + " --transfer unshadowed --bands 3 -q -o " + transfer).exit_code == 0);
  REQUIRE(test::run_prt("render " + mesh + " " + transfer + " --env " + sky + view + " -o " + dir + "/render.exr").exit_code == 0);
  REQUIRE(test::run_prt("reference " + mesh + " --env " + sky + view + " --image --band-limit 3 --spp 4 --albedo 0,0,0 -o " +
                        dir + "/reference.exr").exit_code == 0);
  const image::Image r = image::read_rgb(dir + "/render.exr"), t = image::read_rgb(dir + "/reference.exr");
  std::size_t background = 0;
  double worst = 0.0;
  for (int y = 0; y < r.height; ++y)
    for (int x = 0; x < r.width; ++x) {
      if (!covered(t, x, y)) continue;  // the black (albedo 0) mesh
      ++background;
      for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::fabs(r.at(x, y, c) - t.at(x, y, c))));
    }
  INFO("background pixels " << background << ", largest difference " << worst);
  CHECK(background > 1500);
  CHECK(worst < 5e-3);
}
