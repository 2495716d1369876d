// Conservative rasterization (src/lightmap/rasterize.h) against an analytic one: each texel square
// clipped against each UV triangle (Sutherland-Hodgman) and its exact overlap area; gutters against a
// brute-force Chebyshev distance; gutter values and the UV checks.
#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include <catch2/catch.hpp>
#include <glm/geometric.hpp>

#include "bake/bake.h"
#include "lightmap/gutter.h"
#include "lightmap/lightmap_scenes.h"
#include "lightmap/rasterize.h"
#include "lightmap/texel_bake.h"
#include "lightmap/uv_validation.h"
#include "transfer/transfer_file.h"

namespace prt {

namespace {

using Polygon = std::vector<glm::dvec2>;

// Keeps the part of `poly` with dot(p, axis) * sign <= limit * sign.
Polygon clip(const Polygon& poly, int axis, double limit, double sign) {
  Polygon out;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const glm::dvec2 a = poly[k], b = poly[(k + 1) % poly.size()];
    const double da = sign * (a[axis] - limit), db = sign * (b[axis] - limit);
    if (da <= 0) out.push_back(a);
    if ((da < 0 && db > 0) || (da > 0 && db < 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

double area(const Polygon& poly) {
  double a = 0.0;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const glm::dvec2 p = poly[k], q = poly[(k + 1) % poly.size()];
    a += p.x * q.y - p.y * q.x;
  }
  return std::abs(a) / 2.0;
}

// Exact area of triangle (texel units) inside texel (i, j).
double overlap(const glm::dvec2 (&tri)[3], int i, int j) {
  Polygon poly(tri, tri + 3);
  poly = clip(poly, 0, i, -1.0);
  poly = clip(poly, 0, i + 1, 1.0);
  poly = clip(poly, 1, j, -1.0);
  poly = clip(poly, 1, j + 1, 1.0);
  return poly.size() < 3 ? 0.0 : area(poly);
}

// A few triangles of assorted shapes and orientations in one chart layout (no overlaps).
mesh::Mesh few_triangles() {
  mesh::Mesh m;
  const glm::vec2 uv[][3] = {{{0.05f, 0.05f}, {0.45f, 0.1f}, {0.2f, 0.4f}},     // ccw in uv
                             {{0.55f, 0.05f}, {0.6f, 0.45f}, {0.95f, 0.2f}},    // cw in uv
                             {{0.1f, 0.6f}, {0.9f, 0.62f}, {0.12f, 0.66f}},     // thin sliver
                             {{0.3f, 0.7f}, {0.7f, 0.95f}, {0.3f, 0.95f}},      // axis-aligned edges
                             {{0.75f, 0.7f}, {0.76f, 0.71f}, {0.755f, 0.72f}},  // smaller than a texel
                             {{0.5f, 0.5f}, {0.5625f, 0.5f}, {0.5f, 0.5625f}}};  // edges on texel lines (32 x 32)
  for (const auto& t : uv) {
    const std::uint32_t base = std::uint32_t(m.positions.size());
    for (int k = 0; k < 3; ++k) {
      m.positions.emplace_back(t[k].x * 2.0f, 0.0f, t[k].y * 2.0f + 0.1f * float(k));
      m.normals.emplace_back(0.0f, 1.0f, 0.0f);
      m.indices.push_back(base + std::uint32_t(k));
      m.lightmap_uv.push_back(t[k]);
    }
  }
  return m;
}

}  // namespace

TEST_CASE("lightmap rasterization: covered texels equal an analytic rasterization, one sample each, inside its triangle",
          "[lightmap]") {
  const mesh::Mesh m = few_triangles();
  const std::vector<glm::vec3> albedo(m.vertex_count(), glm::vec3(0.5f));
  for (const auto& [w, h] : std::vector<std::pair<int, int>>{{32, 32}, {50, 37}}) {
    const lightmap::TexelSamples s = lightmap::rasterize(m, albedo, w, h, 2);
    std::vector<std::uint8_t> expected(std::size_t(w) * h, 0);
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
      glm::dvec2 tri[3];
      for (int k = 0; k < 3; ++k) tri[k] = glm::dvec2(m.lightmap_uv[3 * t + k]) * glm::dvec2(w, h);
      for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
          if (overlap(tri, i, j) > 1e-9) expected[std::size_t(i + j * w)] = 1;
    }
    INFO(w << "x" << h);
    CHECK(s.coverage == expected);
    CHECK(s.overlapping_texels == 0);
    std::set<std::uint32_t> texels;
    for (const lightmap::TexelSample& sample : s.samples) {
      texels.insert(sample.texel);
      REQUIRE(expected[sample.texel] == 1);
      // Inside the owning triangle: barycentrics in [0, 1]; the position is the barycentric mix.
      CHECK(sample.barycentric.x >= 0.0f);
      CHECK(sample.barycentric.y >= 0.0f);
      CHECK(sample.barycentric.z >= 0.0f);
      CHECK(std::abs(sample.barycentric.x + sample.barycentric.y + sample.barycentric.z - 1.0f) < 1e-5f);
      const std::uint32_t* idx = &m.indices[3 * sample.triangle];
      const glm::vec3 p = sample.barycentric.x * m.positions[idx[0]] + sample.barycentric.y * m.positions[idx[1]] +
                          sample.barycentric.z * m.positions[idx[2]];
      CHECK(glm::length(p - sample.position) < 1e-5f);
      // A centre inside the owning triangle is sampled at the centre itself.
      const glm::vec2 uv = sample.barycentric.x * m.lightmap_uv[3 * sample.triangle] +
                           sample.barycentric.y * m.lightmap_uv[3 * sample.triangle + 1] +
                           sample.barycentric.z * m.lightmap_uv[3 * sample.triangle + 2];
      const glm::vec2 centre((float(sample.texel % w) + 0.5f) / float(w), (float(sample.texel / w) + 0.5f) / float(h));
      const glm::vec2 texel_size(1.0f / float(w), 1.0f / float(h));
      CHECK(std::abs(uv.x - centre.x) <= 0.5f * texel_size.x + 1e-6f);  // the nearest point stays within the texel
      CHECK(std::abs(uv.y - centre.y) <= 0.5f * texel_size.y + 1e-6f);
    }
    CHECK(texels.size() == s.samples.size());
    CHECK(s.samples.size() == std::size_t(std::count(expected.begin(), expected.end(), 1)));
  }
}

TEST_CASE("lightmap gutters: every texel within N of a chart is filled, with a mean of filled neighbours", "[lightmap]") {
  const mesh::Mesh m = few_triangles();
  bake::BakeOptions options;
  options.kind = transfer::Kind::unshadowed;
  options.bands = 2;
  lightmap::LightmapOptions l;
  l.width = l.height = 40;
  for (int gutter : {0, 1, 2, 3}) {
    l.gutter = gutter;
    const transfer::TransferData data = lightmap::bake_lightmap(m, options, l);
    const lightmap::TexelSamples s = lightmap::rasterize(m, std::vector<glm::vec3>(m.vertex_count(), glm::vec3(0.8f)), 40, 40);
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 40; ++i) {
        int distance = 1 << 20;
        for (int y = 0; y < 40; ++y)
          for (int x = 0; x < 40; ++x)
            if (s.coverage[std::size_t(x + 40 * y)]) distance = std::min(distance, std::max(std::abs(x - i), std::abs(y - j)));
        const std::size_t t = std::size_t(i + 40 * j);
        const std::uint8_t expected = distance == 0 ? 1 : distance <= gutter ? 2 : 0;
        INFO("gutter " << gutter << " texel " << i << "," << j);
        REQUIRE(data.coverage[t] == expected);
        // Unshadowed, grey, upward normals: every filled texel holds the same vector, empty ones zero.
        const float expected_c0 = expected ? data.values[s.samples[0].texel * 4] : 0.0f;
        CHECK(data.values[t * 4] == Approx(expected_c0).margin(1e-7));
      }
  }
}

TEST_CASE("lightmap UV checks: outside [0,1], zero area and overlaps, counted with example triangles", "[lightmap]") {
  mesh::Mesh m = few_triangles();
  CHECK(lightmap::check_uvs(m).ok());
  m.lightmap_uv[1].x = 1.25f;          // triangle 0 outside
  m.lightmap_uv[3 * 3 + 2] = m.lightmap_uv[3 * 3];  // triangle 3 collapsed
  const lightmap::UvProblems p = lightmap::check_uvs(m);
  CHECK(p.outside == 1);
  CHECK(p.outside_examples == std::vector<std::uint32_t>{0});
  CHECK(p.zero_area == 1);
  CHECK(p.zero_area_examples == std::vector<std::uint32_t>{3});
  CHECK(p.message(m).find("1 triangle has UVs outside [0,1] (e.g. triangle 0)") != std::string::npos);
  CHECK(p.message(m).find("collapsed to zero UV area (e.g. triangle 3)") != std::string::npos);
  // Overlap: triangle 1's UVs copied onto triangle 2's: every centre inside either is inside both.
  mesh::Mesh o = few_triangles();
  for (int k = 0; k < 3; ++k) o.lightmap_uv[3 * 2 + k] = o.lightmap_uv[3 * 1 + k];
  const lightmap::TexelSamples s = lightmap::rasterize(o, std::vector<glm::vec3>(o.vertex_count(), glm::vec3(0.8f)), 32, 32);
  // Counted once per texel: the centres strictly inside triangle 1 (its own edge test here).
  const glm::vec2* t1 = &o.lightmap_uv[3];
  std::size_t inside = 0;
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) {
      const glm::dvec2 c((i + 0.5) / 32.0, (j + 0.5) / 32.0);
      double e[3];
      for (int k = 0; k < 3; ++k) {
        const glm::dvec2 a(t1[k]), b(t1[(k + 1) % 3]);
        e[k] = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
      }
      inside += (e[0] > 1e-9 && e[1] > 1e-9 && e[2] > 1e-9) || (e[0] < -1e-9 && e[1] < -1e-9 && e[2] < -1e-9);
    }
  CHECK(inside > 10);
  CHECK(s.overlapping_texels == inside);
  REQUIRE(!s.overlap_examples.empty());
  CHECK(s.overlap_examples[0] == std::make_pair(std::uint32_t(1), std::uint32_t(2)));
  // A third copy stacked on them: still one count per texel (a share of the covered texels, never above 1).
  for (int k = 0; k < 3; ++k) o.lightmap_uv[3 * 3 + k] = o.lightmap_uv[3 * 1 + k];
  CHECK(lightmap::rasterize(o, std::vector<glm::vec3>(o.vertex_count(), glm::vec3(0.8f)), 32, 32).overlapping_texels == inside);
  // Two triangles of one chart sharing an edge do not overlap.
  const mesh::Mesh floor = test::floor_and_box(false);
  CHECK(lightmap::rasterize(floor, std::vector<glm::vec3>(floor.vertex_count(), glm::vec3(0.8f)), 64, 64).overlapping_texels == 0);
}

}  // namespace prt
