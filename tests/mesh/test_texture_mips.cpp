// Mip levels of base colour textures (mesh/texture_mips.h) and what reads them (mesh/texture.h): the
// levels against the closed-form block means of a linear ramp, the level a footprint picks against the
// texel density worked out by hand, and per-vertex albedo of quads whose UVs span many texels (the
// quadrature's mip path) against the exact footprint average, integrated here in one dimension.
#include <cmath>

#include <catch2/catch.hpp>

#include "mesh/texture.h"
#include "mesh/texture_mips.h"

using namespace prt::mesh;

namespace {

// A w x h texture with value x + 100 y + 1000 c in channel c of texel (x, y) (floats).
Texture ramp(int w, int h) {
  Texture t;
  t.width = w;
  t.height = h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) t.rgb.push_back(float(x + 100 * y + 1000 * c));
  return t;
}

float value(const Texture& t, int x, int y, int c) { return t.rgb[std::size_t((y * t.width + x) * 3 + c)]; }

// The unit quad in z = 0, triangles (0, 1, 2) and (0, 2, 3), base colour UV = (su x, sv y) at corner (x, y).
Mesh quad(const Texture& texture, Filter filter, float su, float sv) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.normals.assign(4, glm::vec3(0, 0, 1));
  m.indices = {0, 1, 2, 0, 2, 3};
  TextureRef ref;
  ref.image = 0;
  ref.filter = filter;
  m.materials = {Material{"tex", glm::vec3(1.0f), ref}};
  m.triangle_material = {0, 0};
  for (std::uint32_t i : m.indices) m.base_color_uv.emplace_back(su * m.positions[i].x, sv * m.positions[i].y);
  m.textures = {texture};
  return m;
}

}  // namespace

TEST_CASE("mip levels are the block means of the level above", "[mesh][texture][mips]") {
  // 8 x 4: level k's texel (X, Y) covers level-0 columns [2^k X, 2^k (X + 1)), whose mean is
  // 2^k X + (2^k - 1) / 2, and rows likewise (the ramp is linear, so the block mean is its centre's value).
  const Texture t = ramp(8, 4);
  const TextureMips mips(t);
  REQUIRE(mips.level_count() == 4);  // 8x4, 4x2, 2x1, 1x1
  CHECK(&mips.level(0) == &t);
  const int widths[4] = {8, 4, 2, 1}, heights[4] = {4, 2, 1, 1};
  for (int k = 1; k < 4; ++k) {
    const Texture& level = mips.level(k);
    REQUIRE(level.width == widths[k]);
    REQUIRE(level.height == heights[k]);
    const double bx = 8.0 / widths[k], by = 4.0 / heights[k];  // level-0 texels per texel
    for (int y = 0; y < level.height; ++y)
      for (int x = 0; x < level.width; ++x)
        for (int c = 0; c < 3; ++c)
          CHECK(double(value(level, x, y, c)) == Approx(bx * x + (bx - 1) / 2 + 100.0 * (by * y + (by - 1) / 2) + 1000.0 * c));
  }
  // Odd sizes: 5 x 3 halves to 2 x 1 with column blocks [0, 2) and [2, 5) and all 3 rows.
  const Texture odd = ramp(5, 3);
  const TextureMips odd_mips(odd);
  REQUIRE(odd_mips.level_count() == 3);  // 5x3, 2x1, 1x1
  CHECK(value(odd_mips.level(1), 0, 0, 0) == Approx(0.5 + 100.0));
  CHECK(value(odd_mips.level(1), 1, 0, 0) == Approx(3.0 + 100.0));
  CHECK(value(odd_mips.level(2), 0, 0, 0) == Approx((0.5 + 3.0) / 2 + 100.0));  // the mean of level 1's two
}

TEST_CASE("mip levels of 8-bit codes average the decoded linear values", "[mesh][texture][mips]") {
  Texture t;
  t.width = 2;
  t.height = 1;
  t.codes = {0, 128, 255, 255, 64, 0};
  const TextureMips mips(t);
  const auto& decode = srgb8_decode();
  CHECK(value(mips.level(1), 0, 0, 0) == Approx((decode[0] + decode[255]) / 2));
  CHECK(value(mips.level(1), 0, 0, 1) == Approx((decode[128] + decode[64]) / 2));
  CHECK(value(mips.level(1), 0, 0, 2) == Approx((decode[255] + decode[0]) / 2));
}

TEST_CASE("a footprint reads the coarsest mip level whose texels fit in it", "[mesh][texture][mips]") {
  // A 64 x 64 texture over the unit quad, UVs scaled by (4, 1): 256 texels per unit along x, 64 along y.
  // The sparsest direction (y) decides: a disc of width w spans 64 w texels there, and level k's texel is
  // 2^k texels, so the level is floor(log2(64 w)) from 64 w >= 2 on, capped at the 1 x 1 level 6.
  const Mesh m = quad(ramp(64, 64), Filter::linear, 4.0f, 1.0f);
  const MeshMips mips = build_mips(m.textures, {true}, 1);
  const TriangleColour colour(m, 0, &mips);
  CHECK(colour.level_count() == 7);
  CHECK(colour.level_for(1.9 / 64) == 0);
  CHECK(colour.level_for(2.0 / 64) == 1);
  CHECK(colour.level_for(3.99 / 64) == 1);
  CHECK(colour.level_for(4.01 / 64) == 2);
  CHECK(colour.level_for(40.0 / 64) == 5);
  CHECK(colour.level_for(1e6) == 6);
  CHECK(TriangleColour(m, 0).level_for(1.0) == 0);  // no pyramid: level 0
}

// Vertex 0 = (0, 0) of the quad has hat 1 - x on triangle 0 ({y <= x}) and 1 - y on triangle 1, so over
// the column at x its hat integrates to g(x) = x (1 - x) + (1 - x)^2 / 2, and integral g = 1/3. A texture
// that varies with u only gives vertex 0 the albedo 3 integral g(x) f(su x) dx: integrated here by the
// midpoint rule on a grid of 2^20 columns (each texel column of the texture gets many whole cells).
double exact_vertex0_average(double (*f)(double), double su) {
  const int n = 1 << 20;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) / n;
    sum += (x * (1 - x) + 0.5 * (1 - x) * (1 - x)) * f(su * x);
  }
  return 3.0 * sum / n;
}

// 256 texel columns: the left half 0.2, the right 0.8, each alternating +-0.1 column by column (a detail
// a point-sampled mip would alias), read with NEAREST; f(u) its value at u (repeat).
double stripes(double u) {
  const int column = int(std::floor((u - std::floor(u)) * 256));
  return (column < 128 ? 0.2 : 0.8) + (column % 2 == 0 ? 0.1 : -0.1);
}
Texture stripe_texture() {
  Texture t;
  t.width = 256;
  t.height = 2;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 256; ++x) {
      const float v = float(stripes((x + 0.5) / 256));
      t.rgb.insert(t.rgb.end(), {v, v, v});
    }
  return t;
}

TEST_CASE("per-vertex albedo of triangles spanning many texels or repeats is the exact footprint average",
          "[mesh][texture][albedo][mips]") {
  // su = 3: the longest edges span 3 x 256 = 768 texels; level 0 would need n = 1536 > 32, so the
  // quadrature runs on level 5 (8 x 1 texels: 768 / 32 = 24 <= 32, level 4's 48 is not), where the
  // 0.2 | 0.8 halves are 4 texels each and the +-0.1 columns average out. su = 100: 100 repeats, the 1 x 1
  // level, the texture's mean 0.5, while the exact average is 1.1e-3 below it (the repeats that the
  // edges cut). Tolerance 3e-3 (0.6% of the value; measured 2.2e-3 at su = 3, 1.1e-3 at su = 100): the
  // quadrature's error, n = 32 centroids across jumps of 0.6 (texture.h). A point-sampled pyramid (each
  // texel its block's first column, +0.1) is 0.1 off; level 0 at n = 32 alone reads every texel column
  // at a fixed phase.
  for (double su : {3.0, 100.0}) {
    const Mesh m = quad(stripe_texture(), Filter::nearest, float(su), 1.0f);
    std::vector<glm::vec3> albedo(4, glm::vec3(-1.0f));
    texture_albedo(m, 1, &albedo);
    const double want = exact_vertex0_average(stripes, su);
    INFO("su " << su << " exact " << want << " got " << albedo[0].x);
    CHECK(double(albedo[0].x) == Approx(want).margin(3e-3));
    if (su == 100.0) CHECK(want == Approx(0.5).margin(2e-3));  // many repeats: the texture's mean
  }
}
