// Lightmaps against the path-traced reference: the box on a two-triangle floor (texel shadowed and
// interreflected transfer vs `prt reference --texels`, band-limited lighting), the seams of a split
// cube, and contact (boxes resting on and intersecting the floor). Runs the real prt binary.
#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include <glm/geometric.hpp>

#include "image/image.h"
#include "lightmap/rasterize.h"
#include "mesh/writers.h"
#include "light/environment.h"
#include "reference/environment_sampler.h"
#include "reference/reference.h"
#include "lightmap/lightmap_scenes.h"
#include "support/run_prt.h"
#include "transfer/transfer_file.h"

namespace prt {

namespace {

struct Errors {
  double rel_rms = 0.0;
  std::size_t texels = 0, black_where_lit = 0;
};

// Over covered texels: rel_rms of a against the reference b (all channels), and how many texels read
// below 5% of a reference that is lit (> 10% of its mean).
Errors compare_covered(const image::Image& a, const image::Image& b, const std::vector<std::uint8_t>& coverage) {
  double err = 0.0, norm = 0.0, mean = 0.0;
  Errors e;
  for (std::size_t t = 0; t < coverage.size(); ++t) {
    if (coverage[t] != transfer::kTexelCovered) continue;
    ++e.texels;
    for (int c = 0; c < 3; ++c) {
      const double d = double(a.pixels[3 * t + c]) - double(b.pixels[3 * t + c]);
      err += d * d;
      norm += double(b.pixels[3 * t + c]) * double(b.pixels[3 * t + c]);
      mean += double(b.pixels[3 * t + c]);
    }
  }
  mean /= 3.0 * double(std::max<std::size_t>(e.texels, 1));
  for (std::size_t t = 0; t < coverage.size(); ++t) {
    if (coverage[t] != transfer::kTexelCovered) continue;
    const double ref = (b.pixels[3 * t] + b.pixels[3 * t + 1] + b.pixels[3 * t + 2]) / 3.0;
    const double got = (a.pixels[3 * t] + a.pixels[3 * t + 1] + a.pixels[3 * t + 2]) / 3.0;
    if (ref > 0.1 * mean && got < 0.05 * ref) ++e.black_where_lit;
  }
  e.rel_rms = std::sqrt(err / std::max(norm, 1e-300));
  return e;
}

struct Scene {
  std::string dir, mesh, sky;
  Scene(const std::string& name, const mesh::Mesh& m) : dir(test::fresh_temp_dir(name)), mesh(dir + "/scene.obj"), sky(dir + "/sky.exr") {
    test::write_obj_with_uv(mesh, m);
    test::write_test_sky(sky);
  }
  // Bakes, shades (band-limited: --sun none --window none) and path-traces the reference at the texels.
  Errors run(const std::string& bake, const std::string& reference, const std::string& name) const {
    const std::string lm = dir + "/" + name + ".prt", lit = dir + "/" + name + "_lit.exr", ref = dir + "/" + name + "_ref.exr";
    const test::RunResult b = test::run_prt("bake " + mesh + " --quiet " + bake + " -o " + lm);
    INFO(b.output);
    REQUIRE(b.exit_code == 0);
    REQUIRE(test::run_prt("shade " + mesh + " " + lm + " --env " + sky + " --sun none --window none --lightmap -o " + lit).exit_code == 0);
    REQUIRE(test::run_prt("reference " + mesh + " --env " + sky + " --band-limit 5 --quiet " + reference + " --texels " + lm + " -o " + ref)
                .exit_code == 0);
    return compare_covered(image::read_rgb(lit), image::read_rgb(ref), transfer::read_transfer(lm).coverage);
  }
};

}  // namespace

TEST_CASE("lightmap: box on a two-triangle floor, shadowed texels vs prt reference --texels: rel_rms <= 1%", "[lightmap][slow]") {
  const mesh::Mesh m = test::floor_and_box(true);
  const Scene scene("lightmap_box_reference", m);
  const Errors e = scene.run("--lightmap 48 --transfer shadowed --samples 2048", "--bounces 0 --samples 1024", "shadowed");
  INFO("texels " << e.texels << " rel_rms " << e.rel_rms);
  CHECK(e.texels > 1000);
  CHECK(e.rel_rms <= 0.01);
  CHECK(e.black_where_lit == 0);
  // The per-vertex bake of the same mesh, interpolated at the same texel sample points as a renderer
  // interpolates vertex colours: the floor has four vertices and cannot show the box's shadow.
  const std::string transfer = scene.dir + "/vertex.prt", shaded = scene.dir + "/vertex.ply";
  REQUIRE(test::run_prt("bake " + scene.mesh + " --quiet --transfer shadowed --samples 2048 --footprint vertex -o " + transfer).exit_code == 0);
  REQUIRE(test::run_prt("shade " + scene.mesh + " " + transfer + " --env " + scene.sky + " --sun none --window none -o " + shaded).exit_code == 0);
  const mesh::ColourPly vertex = mesh::read_ply_colours(shaded);
  const lightmap::TexelSamples samples = lightmap::rasterize(m, std::vector<glm::vec3>(m.vertex_count(), glm::vec3(0.8f)), 48, 48);
  image::Image interpolated(48, 48, 3);
  for (const lightmap::TexelSample& t : samples.samples)
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c)
        interpolated.pixels[3 * t.texel + c] += t.barycentric[k] * vertex.colours[m.indices[3 * t.triangle + k]][c];
  const Errors v = compare_covered(interpolated, image::read_rgb(scene.dir + "/shadowed_ref.exr"), samples.coverage);
  WARN("box on floor, rel_rms against the reference at the texel sample points: lightmap " << e.rel_rms << ", per-vertex bake "
                                                                                           << v.rel_rms);
  CHECK(v.rel_rms > 10.0 * e.rel_rms);
}

TEST_CASE("lightmap: interreflected texels (1 bounce, bilinear gathering) vs prt reference --texels --bounces 1", "[lightmap][slow]") {
  const Scene scene("lightmap_box_bounce", test::floor_and_box(true));
  const Errors e = scene.run("--lightmap 48 --transfer interreflected --bounces 1 --samples 2048", "--bounces 1 --samples 2048", "bounce");
  INFO("texels " << e.texels << " rel_rms " << e.rel_rms);
  CHECK(e.rel_rms <= 0.015);
  CHECK(e.black_where_lit == 0);
}

namespace {

// The lit lightmap of `name` in `scene` (bake + shade --lightmap with the band-limited sky).
image::Image lit_lightmap(const Scene& scene, const std::string& bake, const std::string& name) {
  const std::string lm = scene.dir + "/" + name + ".prt", lit = scene.dir + "/" + name + "_lit.exr";
  const test::RunResult b = test::run_prt("bake " + scene.mesh + " --quiet " + bake + " -o " + lm);
  INFO(b.output);
  REQUIRE(b.exit_code == 0);
  REQUIRE(test::run_prt("shade " + scene.mesh + " " + lm + " --env " + scene.sky + " --sun none --window none --lightmap -o " + lit).exit_code == 0);
  return image::read_rgb(lit);
}

double luminance(const image::Image& im, const glm::vec2& uv) {
  return (test::bilinear(im, uv, 0) + test::bilinear(im, uv, 1) + test::bilinear(im, uv, 2)) / 3.0;
}

}  // namespace

TEST_CASE("lightmap seams: across the UV seam of every face of a split, unwelded cube the lit values agree to 2%", "[lightmap][slow]") {
  const mesh::Mesh cube = test::split_cube_on_floor();
  const Scene scene("lightmap_seams", cube);
  const image::Image lit = lit_lightmap(scene, "--lightmap 128 --transfer interreflected --bounces 1 --samples 2048", "cube");
  double worst = 0.0;
  // Triangles 2 + 2f and 3 + 2f are face f's halves (A = corners 0,1,2 and B = corners 0,2,3 of its
  // quad): the seam runs from quad corner 0 (A0, B0) to quad corner 2 (A2, B1).
  for (int f = 0; f < 6; ++f) {
    const glm::vec2* a = &cube.lightmap_uv[3 * (2 + 2 * f)];
    const glm::vec2* b = &cube.lightmap_uv[3 * (3 + 2 * f)];
    for (int k = 1; k < 10; ++k) {
      const float s = 0.1f * float(k);
      const double va = luminance(lit, a[0] + s * (a[2] - a[0])), vb = luminance(lit, b[0] + s * (b[1] - b[0]));
      const double relative = std::abs(va - vb) / (0.5 * (va + vb));
      INFO("face " << f << " s " << s << ": " << va << " vs " << vb);
      CHECK(va > 0.0);
      CHECK(relative <= 0.02);
      worst = std::max(worst, relative);
    }
  }
  WARN("seams: largest relative difference " << worst);
}

namespace {

// Floor texels of the floor_and_box chart ([0.01, 0.59]^2 <-> x, z in [-1, 1]) that are partly outside
// the box footprint |x|, |z| < 0.3 and within 2 texels of its border: the texel and the floor point of
// its square farthest outside the box (a visible point).
struct VisibleTexel {
  std::size_t texel;
  glm::vec3 point;
};

std::vector<VisibleTexel> visible_contact_texels(int size) {
  std::vector<VisibleTexel> out;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      glm::vec3 best(0.0f);
      float best_norm = -1.0f, nearest_norm = 1e9f;
      for (int c = 0; c < 4; ++c) {
        const float u = float(i + (c & 1)) / float(size), v = float(j + (c >> 1)) / float(size);
        const float x = std::clamp(-1.0f + 2.0f * (u - 0.01f) / 0.58f, -1.0f, 1.0f), z = std::clamp(1.0f - 2.0f * (v - 0.01f) / 0.58f, -1.0f, 1.0f);
        const float norm = std::max(std::abs(x), std::abs(z));
        nearest_norm = std::min(nearest_norm, norm);
        if (norm > best_norm) best_norm = norm, best = glm::vec3(x, 0.0f, z);
      }
      const float texel_world = 2.0f / 0.58f / float(size);
      if (best_norm > 0.3f + 1e-4f && nearest_norm < 0.3f + 2.0f * texel_world && (i + 0.5f) / float(size) < 0.59f &&
          (j + 0.5f) / float(size) < 0.59f)
        out.push_back({std::size_t(i + j * size), best});
    }
  return out;
}

}  // namespace

TEST_CASE("lightmap contact: boxes resting on and intersecting the floor leave no black texel where the reference is lit",
          "[lightmap][slow]") {
  constexpr int kSize = 64;
  const std::vector<VisibleTexel> texels = visible_contact_texels(kSize);
  REQUIRE(texels.size() > 50);
  for (float bottom : {0.0f, -0.15f}) {
    const mesh::Mesh m = test::floor_and_box(true, bottom);
    const Scene scene("lightmap_contact", m);
    const reference::EnvironmentSampler sampler(reference::band_limited_environment(light::load_environment(scene.sky), 5));
    std::vector<reference::PointSample> points;
    for (const VisibleTexel& t : texels) points.push_back({t.point, glm::vec3(0, 1, 0), glm::vec3(0.8f)});
    reference::ReferenceOptions options;
    options.samples = 256;
    const std::vector<glm::vec3> ref = reference::point_radiance(m, sampler, options, points);
    for (bool repair : {true, false}) {
      const image::Image lit =
          lit_lightmap(scene, "--lightmap 64 --transfer shadowed --samples 512" + std::string(repair ? "" : " --no-sample-repair"), "c");
      std::size_t black = 0;
      for (std::size_t k = 0; k < texels.size(); ++k) {
        const double r = (ref[k].x + ref[k].y + ref[k].z) / 3.0;
        const float* p = &lit.pixels[3 * texels[k].texel];
        const double got = (p[0] + p[1] + p[2]) / 3.0;
        if (r > 0.05 && got < 0.2 * r) ++black;
      }
      INFO("bottom " << bottom << (repair ? " with" : " without") << " sample repair: " << black << " of " << texels.size()
                     << " visible contact texels read black");
      if (repair)
        CHECK(black == 0);
      else
        CHECK(black > 0);  // the same test catches the unrepaired samples
    }
  }
}

namespace {

// Whether the ray p + t d (t > 0) meets the box [lo, hi] (slab test).
bool hits_box(const glm::dvec3& p, const glm::dvec3& d, const glm::dvec3& lo, const glm::dvec3& hi) {
  double t0 = 1e-9, t1 = 1e30;
  for (int a = 0; a < 3; ++a) {
    const double inv = 1.0 / d[a];
    double near = (lo[a] - p[a]) * inv, far = (hi[a] - p[a]) * inv;
    if (near > far) std::swap(near, far);
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
  }
  return t0 <= t1;
}

}  // namespace

TEST_CASE("lightmap: prt shade --lightmap shades a sun disc per texel, with shadow rays: (albedo/pi) E (n.d) or 0",
          "[lightmap][slow]") {
  const Scene scene("lightmap_sun", test::floor_and_box(true));
  const std::string lm = scene.dir + "/sun.prt";
  REQUIRE(test::run_prt("bake " + scene.mesh + " --quiet --lightmap 64 --transfer shadowed --samples 256 -o " + lm).exit_code == 0);
  const std::string shade = "shade " + scene.mesh + " " + lm + " --env " + scene.sky + " --window none --lightmap -o ";
  REQUIRE(test::run_prt(shade + scene.dir + "/lit_sky.exr --sun none").exit_code == 0);
  REQUIRE(test::run_prt(shade + scene.dir + "/lit_sun.exr --sun 0.6,0.5,0.3,4,3,2,0.5").exit_code == 0);
  const image::Image sky = image::read_rgb(scene.dir + "/lit_sky.exr"), sun = image::read_rgb(scene.dir + "/lit_sun.exr");
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.6, 0.5, 0.3)), irradiance(4, 3, 2);
  const glm::dvec3 lo(-0.3, 0.0, -0.3), hi(0.3, 0.6, 0.3);
  const double disc_margin = 0.02;  // the disc's 0.5 degree radius, and texel extents, near the shadow's edge
  std::size_t lit = 0, shadowed = 0;
  // Floor texels (chart [0.01, 0.59]^2) away from the box's footprint and from the shadow's edge.
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      const double u = (i + 0.5) / 64.0, v = (j + 0.5) / 64.0;
      if (u < 0.03 || u > 0.57 || v < 0.03 || v > 0.57) continue;
      const glm::dvec3 p(-1.0 + 2.0 * (u - 0.01) / 0.58, 0.0, 1.0 - 2.0 * (v - 0.01) / 0.58);
      if (std::max(std::abs(p.x), std::abs(p.z)) < 0.3 + 0.06) continue;
      bool any = false, all = true;
      for (const glm::dvec3& o : {glm::dvec3(0), glm::dvec3(disc_margin, 0, 0), glm::dvec3(-disc_margin, 0, 0),
                                  glm::dvec3(0, 0, disc_margin), glm::dvec3(0, 0, -disc_margin)}) {
        const bool blocked = hits_box(p + o, d, lo, hi);
        any = any || blocked;
        all = all && blocked;
      }
      if (any != all) continue;
      const std::size_t t = std::size_t(i + 64 * j);
      for (int c = 0; c < 3; ++c) {
        const double direct = double(sun.pixels[3 * t + c]) - double(sky.pixels[3 * t + c]);
        const double expected = all ? 0.0 : 0.8 / M_PI * irradiance[c] * d.y;
        INFO("texel " << i << "," << j << " channel " << c << (all ? " (in the box's shadow)" : " (lit)"));
        CHECK(std::abs(direct - expected) <= 0.005 * 0.8 / M_PI * irradiance[c] * d.y);
      }
      (all ? shadowed : lit) += 1;
    }
  CHECK(lit > 300);
  CHECK(shadowed > 30);
}

}  // namespace prt
