// Base colour lookups (mesh/texture.h) against closed forms on a checker texture over a unit quad:
// texel values and bilinear values at known points, each wrap mode, KHR_texture_transform (the
// extension's own worked example), per-square averages of the bilinear checker, and per-vertex albedo as
// the exact hat-weighted footprint average.
#include <cmath>
#include <cstring>

#include <catch2/catch.hpp>

#include "mesh/texture.h"

using namespace prt::mesh;

namespace {

const glm::vec3 kA(0.9f, 0.2f, 0.5f), kB(0.1f, 0.6f, 0.3f);

// A w x h checker: texel (x, y) is kA where x + y is even, else kB.
Texture checker(int w, int h) {
  Texture t;
  t.width = w;
  t.height = h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec3 c = (x + y) % 2 == 0 ? kA : kB;
      t.rgb.insert(t.rgb.end(), {c.x, c.y, c.z});
    }
  return t;
}

// The unit quad in z = 0, triangles (0, 1, 2) and (0, 2, 3), base colour UV = (x, y) at each corner.
Mesh quad(const Texture& texture, const TextureRef& ref, glm::vec3 factor = glm::vec3(1.0f)) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.normals.assign(4, glm::vec3(0, 0, 1));
  m.indices = {0, 1, 2, 0, 2, 3};
  m.materials = {Material{"checker", factor, ref}};
  m.triangle_material = {0, 0};
  for (std::uint32_t i : m.indices) m.base_color_uv.emplace_back(m.positions[i].x, m.positions[i].y);
  m.textures = {texture};
  return m;
}

TextureRef linear_ref(Wrap wrap = Wrap::repeat) {
  TextureRef ref;
  ref.image = 0;
  ref.wrap_s = ref.wrap_t = wrap;
  return ref;
}

void check_close(const glm::vec3& got, const glm::vec3& want, double tolerance) {
  for (int c = 0; c < 3; ++c) CHECK(double(got[c]) == Approx(double(want[c])).margin(tolerance));
}

// Barycentrics (b1, b2) of the quad point (u, v): triangle 0 (v <= u) has uv = (b1 + b2, b2), triangle 1
// has uv = (b1, b1 + b2).
glm::dvec2 bary(int triangle, double u, double v) { return triangle == 0 ? glm::dvec2(u - v, v) : glm::dvec2(u, v - u); }

}  // namespace

TEST_CASE("texel centres give the texel, midpoints the mean of neighbours", "[mesh][texture]") {
  const Texture t = checker(4, 4);
  const TextureRef ref = linear_ref();
  check_close(sample_texture(t, ref, {0.125f, 0.125f}), kA, 1e-6);  // texel (0, 0)'s centre
  check_close(sample_texture(t, ref, {0.375f, 0.125f}), kB, 1e-6);  // texel (1, 0)
  check_close(sample_texture(t, ref, {0.25f, 0.125f}), 0.5f * (kA + kB), 1e-6);
  // A quarter of the way from centre (1, 1) to centre (2, 2): weights 9/16 (1,1), 3/16 each (2,1),(1,2), 1/16 (2,2).
  check_close(sample_texture(t, ref, {0.4375f, 0.4375f}), (10.0f * kA + 6.0f * kB) / 16.0f, 1e-6);
  TextureRef nearest = ref;
  nearest.filter = Filter::nearest;
  check_close(sample_texture(t, nearest, {0.49f, 0.01f}), kB, 0.0);
  check_close(sample_texture(t, nearest, {0.51f, 0.01f}), kA, 0.0);
}

TEST_CASE("wrap modes at and beyond the image's edges", "[mesh][texture]") {
  const Texture t = checker(4, 4);  // texel (3, 0) is kB, (0, 0) kA
  // u = 0 on the centre row of texel row 0: halfway between texel -1 and texel 0.
  check_close(sample_texture(t, linear_ref(Wrap::repeat), {0.0f, 0.125f}), 0.5f * (kA + kB), 1e-6);  // -1 -> 3 (kB)
  check_close(sample_texture(t, linear_ref(Wrap::clamp_to_edge), {0.0f, 0.125f}), kA, 1e-6);        // -1 -> 0
  check_close(sample_texture(t, linear_ref(Wrap::mirrored_repeat), {0.0f, 0.125f}), kA, 1e-6);      // -1 -> 0
  // Far outside: repeat by whole images, clamp to the last texel, mirror every other image.
  check_close(sample_texture(t, linear_ref(Wrap::repeat), {2.375f, 0.125f}), kB, 1e-5);            // texel 1
  check_close(sample_texture(t, linear_ref(Wrap::clamp_to_edge), {7.0f, -3.0f}), kB, 1e-6);         // texel (3, 0)
  check_close(sample_texture(t, linear_ref(Wrap::mirrored_repeat), {1.125f, 0.125f}), kB, 1e-6);    // texel 3
  check_close(sample_texture(t, linear_ref(Wrap::mirrored_repeat), {-0.375f, 0.125f}), kB, 1e-6);   // texel 1
  CHECK(wrap_texel(-1, 4, Wrap::repeat) == 3);
  CHECK(wrap_texel(-5, 4, Wrap::mirrored_repeat) == 3);
  CHECK(wrap_texel(9, 4, Wrap::mirrored_repeat) == 1);
  CHECK(wrap_texel(-100, 4, Wrap::clamp_to_edge) == 0);
}

TEST_CASE("KHR_texture_transform: the extension's example takes the lower left quadrant", "[mesh][texture]") {
  // "offset [0, 1], rotation pi/2, scale [0.5, 0.5]: the lower left quadrant of the image, rotated".
  TextureTransform t;
  t.offset = {0.0f, 1.0f};
  t.rotation = float(M_PI / 2);
  t.scale = {0.5f, 0.5f};
  const glm::vec2 expected[4][2] = {{{0, 0}, {0, 1}}, {{1, 0}, {0, 0.5f}}, {{1, 1}, {0.5f, 0.5f}}, {{0, 1}, {0.5f, 1}}};
  for (const auto& [uv, want] : expected) {
    const glm::vec2 got = transform_uv(t, uv);
    CHECK(got.x == Approx(want.x).margin(1e-6));
    CHECK(got.y == Approx(want.y).margin(1e-6));
  }
  // Through base_color: a 2 x 2 checker seen through the example's transform at the quad's corners.
  TextureRef ref = linear_ref(Wrap::clamp_to_edge);
  ref.filter = Filter::nearest;
  ref.transform = t;
  const Mesh m = quad(checker(2, 2), ref, glm::vec3(0.5f));
  // Quad point (0.9, 0.1) -> uv' = (0.05, 0.55): texel (0, 1), kB; (0.1, 0.9) -> (0.45, 0.95): texel (0, 1).
  check_close(base_color(m, 0, 0.8, 0.1), 0.5f * kB, 1e-6);
  check_close(base_color(m, 1, 0.1, 0.8), 0.5f * kB, 1e-6);
  // Quad point (0.9, 0.9) -> uv' = (0.45, 0.55): texel (0, 1) as well; (0.1, 0.1) -> (0.05, 0.95): (0, 1).
  // The other texels appear only with u' > 0.5, which the example never reaches.
  check_close(base_color(m, 0, 0.0, 0.9), 0.5f * kB, 1e-6);
}

TEST_CASE("per-square averages of a bilinear checker are exact", "[mesh][texture]") {
  // 1D: over texel i the bilinear interpolant averages t(i-1)/8 + 3 t(i)/4 + t(i+1)/8; in 2D the
  // product of those weights gives (5 own + 3 other) / 8 with repeat; with clamp to edge, neighbours
  // outside repeat the edge texel (7/8, 1/8 along that axis): (11 own + 5 other) / 16 in an edge square,
  // (25 own + 7 other) / 32 in a corner one. Tolerance 1e-3: the quadrature's (texture.h) error.
  for (Wrap wrap : {Wrap::repeat, Wrap::clamp_to_edge}) {
    const Mesh m = quad(checker(4, 4), linear_ref(wrap));
    for (int sy = 0; sy < 4; ++sy)
      for (int sx = 0; sx < 4; ++sx) {
        const double u0 = sx / 4.0, v0 = sy / 4.0, u1 = u0 + 0.25, v1 = v0 + 0.25;
        const int t = sx > sy ? 0 : 1;  // squares off the diagonal lie in one triangle
        if (sx == sy) continue;         // (diagonal squares: checked below, half in each triangle)
        const glm::dvec2 lower[3] = {bary(t, u0, v0), bary(t, u1, v0), bary(t, u1, v1)};
        const glm::dvec2 upper[3] = {bary(t, u0, v0), bary(t, u1, v1), bary(t, u0, v1)};
        const glm::vec3 own = (sx + sy) % 2 == 0 ? kA : kB, other = (sx + sy) % 2 == 0 ? kB : kA;
        const bool corner = (sx == 0 || sx == 3) && (sy == 0 || sy == 3);
        const glm::vec3 want = wrap == Wrap::clamp_to_edge && corner ? (25.0f * own + 7.0f * other) / 32.0f
                               : wrap == Wrap::clamp_to_edge && (sx == 0 || sx == 3 || sy == 0 || sy == 3)
                                   ? (11.0f * own + 5.0f * other) / 16.0f  // edge: (7/8, 1/8) x (1/8, 3/4, 1/8)
                                   : (5.0f * own + 3.0f * other) / 8.0f;
        check_close(0.5f * (region_average(m, std::uint32_t(t), lower) + region_average(m, std::uint32_t(t), upper)), want, 1e-3);
      }
    // A diagonal square: the checker is symmetric about the diagonal, so each half has the square's mean.
    const glm::dvec2 half[3] = {bary(0, 0.25, 0.25), bary(0, 0.5, 0.25), bary(0, 0.5, 0.5)};
    check_close(region_average(m, 0, half), (5.0f * kA + 3.0f * kB) / 8.0f, 1e-3);
  }
}

TEST_CASE("per-vertex albedo is the exact footprint average of a nearest checker", "[mesh][texture][albedo]") {
  // An 8 x 8 image of 4 x 4-texel squares: a 2 x 2 checker of kA (top-left, bottom-right) and kB.
  Texture t;
  t.width = t.height = 8;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const glm::vec3 c = (x / 4 + y / 4) % 2 == 0 ? kA : kB;
      t.rgb.insert(t.rgb.end(), {c.x, c.y, c.z});
    }
  TextureRef ref = linear_ref();
  ref.filter = Filter::nearest;
  const Mesh m = quad(t, ref);
  std::vector<glm::vec3> albedo(4, glm::vec3(-1.0f));
  texture_albedo(m, 1, &albedo);
  // Vertex (0,0) has hat 1 - x on triangle 0 ({y <= x}) and 1 - y on triangle 1. Over triangle 0 the kA
  // part is {y <= x <= 1/2} (integral of (1 - x) x over [0, 1/2] = 1/12) plus {1/2 <= y <= x} (1/48):
  // 5/48 of the triangle's 1/6; the same on triangle 1 by symmetry: (5 kA + 3 kB) / 8. Vertex (1,0)
  // lies on triangle 0 only, hat x - y: 1/48 on each kA square of 1/6 in all: (kA + 3 kB) / 4. Vertices
  // (1,1) and (0,1) mirror them.
  const glm::vec3 corner = (5.0f * kA + 3.0f * kB) / 8.0f, side = (kA + 3.0f * kB) / 4.0f;
  check_close(albedo[0], corner, 0.01 * 0.3);
  check_close(albedo[2], corner, 0.01 * 0.3);
  check_close(albedo[1], side, 0.01 * 0.3);
  check_close(albedo[3], side, 0.01 * 0.3);
}

TEST_CASE("per-vertex texture albedo is the same bits for any thread count", "[mesh][texture][albedo]") {
  // A 24 x 24 grid of quads (1152 triangles, many parallel chunks) under a 16 x 16 bilinear checker.
  const int n = 24;
  Mesh m;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) m.positions.emplace_back(float(x) / n, float(y) / n, 0.0f);
  m.normals.assign(m.positions.size(), glm::vec3(0, 0, 1));
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const std::uint32_t a = std::uint32_t(y * (n + 1) + x), b = a + 1, c = a + n + 2, d = a + n + 1;
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
    }
  m.materials = {Material{"checker", glm::vec3(1.0f), linear_ref()}};
  m.triangle_material.assign(m.indices.size() / 3, 0);
  for (std::uint32_t i : m.indices) m.base_color_uv.emplace_back(m.positions[i].x, m.positions[i].y);
  m.textures = {checker(16, 16)};
  std::vector<glm::vec3> one(m.positions.size(), glm::vec3(-1.0f)), two = one, four = one;
  texture_albedo(m, 1, &one);
  texture_albedo(m, 2, &two);
  texture_albedo(m, 4, &four);
  CHECK(std::memcmp(one.data(), two.data(), one.size() * sizeof(glm::vec3)) == 0);
  CHECK(std::memcmp(one.data(), four.data(), one.size() * sizeof(glm::vec3)) == 0);
  for (const glm::vec3& a : one) REQUIRE(a.x > 0.0f);  // every vertex was written
}

TEST_CASE("base colour is texture x factor x interpolated vertex colour", "[mesh][texture]") {
  TextureRef ref = linear_ref();
  ref.filter = Filter::nearest;
  Mesh m = quad(checker(2, 2), ref, glm::vec3(0.5f, 1.0f, 0.8f));
  m.vertex_color = {{1, 1, 1}, {0, 1, 1}, {1, 0, 1}, {1, 1, 0}};
  // Triangle 0 at barycentrics (0.2, 0.3): uv = (b1 + b2, b2) = (0.5, 0.3), texel (1, 0) (nearest: u
  // = 0.5 is texel 1's left edge), kB. Vertex colour 0.5 v0 + 0.2 v1 + 0.3 v2 = (0.8, 0.7, 1).
  const glm::vec3 want = kB * glm::vec3(0.5f, 1.0f, 0.8f) * glm::vec3(0.8f, 0.7f, 1.0f);
  check_close(base_color(m, 0, 0.2, 0.3), want, 1e-6);
  check_close(TriangleColour(m, 0).at(0.2, 0.3), want, 0.0);
}

// The two-step lookup of the bakers' hit loops (TriangleColour::request, then at(request)) against the
// bilinear closed form of a checker, over every wrap mode and beyond the image (UVs to 2.5), and bit for
// bit against the one-step at(): it must change no baked byte.
TEST_CASE("a requested lookup is the bilinear closed form and the one-step lookup's bits", "[mesh][texture]") {
  for (Wrap wrap : {Wrap::repeat, Wrap::clamp_to_edge, Wrap::mirrored_repeat}) {
    Mesh m = quad(checker(4, 4), linear_ref(wrap));
    for (glm::vec2& uv : m.base_color_uv) uv *= 2.5f;  // UV 0 .. 2.5: ten texels across a 4-texel image
    const TriangleColour colour(m, 0);
    for (int i = 0; i <= 40; ++i) {
      // Triangle 0 at uv = 2.5 (u, v) with v = u / 2: (b1, b2) = (u - v, v).
      const double u = i / 40.0, v = u / 2, b1 = u - v, b2 = v;
      const glm::vec3 stepped = colour.at(colour.request(b1, b2));
      const glm::vec3 direct = colour.at(b1, b2);
      CHECK(std::memcmp(&stepped, &direct, sizeof stepped) == 0);
      // Closed form: the four texel centres around (x, y) = 4 * 2.5 (u, v) - 1/2, each wrapped by hand.
      const double x = 10.0 * u - 0.5, y = 10.0 * v - 0.5, x0 = std::floor(x), y0 = std::floor(y);
      auto wrapped = [wrap](long k) {
        if (wrap == Wrap::clamp_to_edge) return k < 0 ? 0L : (k > 3 ? 3L : k);
        const long m8 = ((k % 8) + 8) % 8, m4 = ((k % 4) + 4) % 4;
        return wrap == Wrap::repeat ? m4 : (m8 < 4 ? m8 : 7 - m8);
      };
      auto at = [&](long tx, long ty) { return (wrapped(tx) + wrapped(ty)) % 2 == 0 ? kA : kB; };
      const double fx = x - x0, fy = y - y0;
      const long ix = long(x0), iy = long(y0);
      const glm::dvec3 want = (1 - fy) * ((1 - fx) * glm::dvec3(at(ix, iy)) + fx * glm::dvec3(at(ix + 1, iy))) +
                              fy * ((1 - fx) * glm::dvec3(at(ix, iy + 1)) + fx * glm::dvec3(at(ix + 1, iy + 1)));
      check_close(stepped, glm::vec3(want), 1e-5);
    }
  }
}
