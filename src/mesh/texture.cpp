#include "mesh/texture.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/parallel.h"
#include "core/srgb.h"
#include "mesh/vertex_footprint.h"

namespace prt::mesh {

namespace {

// Texel coordinates beyond this are clamped before the integer conversion (far beyond any image).
constexpr double kMaxTexelCoordinate = 1e15;

// The linear RGB at value index i (3 per texel) of a texture held as floats, or as 8-bit sRGB codes.
struct FloatTexels {
  const float* rgb;
  [[gnu::always_inline]] glm::vec3 operator()(std::size_t i) const { return glm::vec3(rgb[i], rgb[i + 1], rgb[i + 2]); }
};
struct CodeTexels {
  const std::uint8_t* codes;
  const float* decode;
  [[gnu::always_inline]] glm::vec3 operator()(std::size_t i) const {
    return glm::vec3(decode[codes[i]], decode[codes[i + 1]], decode[codes[i + 2]]);
  }
};

// The bilinear blend of the texels a (top-left), b (top-right), c (bottom-left), d at fractions fx, fy.
// One out-of-line copy for both forms of Texture: the compiler may fuse multiply-adds differently where
// it inlines, and both forms must give the same floats.
[[gnu::noinline]] glm::vec3 bilinear(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, float fx, float fy) {
  const glm::vec3 top = (1.0f - fx) * a + fx * b, bottom = (1.0f - fx) * c + fx * d;
  return (1.0f - fy) * top + fy * bottom;
}

template <class Texels>
[[gnu::always_inline]] inline glm::vec3 texel(const Texture& texture, const TextureRef& ref, Texels texels, std::int64_t x,
                                              std::int64_t y) {
  return texels((std::size_t(wrap_texel(y, texture.height, ref.wrap_t)) * std::size_t(texture.width) +
                 std::size_t(wrap_texel(x, texture.width, ref.wrap_s))) * 3);
}

// Where sample_texture reads for `uv`: texel (x0, y0) (before wrapping) and, bilinear, its right and
// lower neighbours with the fractions fx, fy (nearest: 0).
struct Spot {
  std::int64_t x0 = 0, y0 = 0;
  float fx = 0.0f, fy = 0.0f;
};
Spot locate(const Texture& texture, Filter filter, glm::vec2 uv) {
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = glm::vec2(0.0f);
  const double x = std::clamp(double(uv.x) * texture.width, -kMaxTexelCoordinate, kMaxTexelCoordinate);
  const double y = std::clamp(double(uv.y) * texture.height, -kMaxTexelCoordinate, kMaxTexelCoordinate);
  if (filter == Filter::nearest) return {std::int64_t(std::floor(x)), std::int64_t(std::floor(y))};
  const double fx0 = std::floor(x - 0.5), fy0 = std::floor(y - 0.5);
  return {std::int64_t(fx0), std::int64_t(fy0), float(x - 0.5 - fx0), float(y - 0.5 - fy0)};
}

// sample_texture at the spot locate() found, on texels read by `texels`.
template <class Texels>
glm::vec3 sample(const Texture& texture, const TextureRef& ref, Filter filter, Texels texels, const Spot& s) {
  if (filter == Filter::nearest) return texel(texture, ref, texels, s.x0, s.y0);
  return bilinear(texel(texture, ref, texels, s.x0, s.y0), texel(texture, ref, texels, s.x0 + 1, s.y0),
                  texel(texture, ref, texels, s.x0, s.y0 + 1), texel(texture, ref, texels, s.x0 + 1, s.y0 + 1), s.fx, s.fy);
}

// sample_texture at a located spot, from either form of the texture.
glm::vec3 sample_spot(const Texture& texture, const TextureRef& ref, Filter filter, const Spot& s) {
  if (texture.codes.empty()) return sample(texture, ref, filter, FloatTexels{texture.rgb.data()}, s);
  return sample(texture, ref, filter, CodeTexels{texture.codes.data(), srgb8_decode().data()}, s);
}

// Asks the CPU to load the rows sample() will read at spot `s` into the cache (the bakers' hits read
// textures at random: each lookup otherwise waits for memory in turn).
void prefetch_texels(const Texture& texture, const TextureRef& ref, const Spot& s) {
  const std::size_t column = std::size_t(wrap_texel(s.x0, texture.width, ref.wrap_s));
  const std::size_t rows[2] = {std::size_t(wrap_texel(s.y0, texture.height, ref.wrap_t)),
                               std::size_t(wrap_texel(s.y0 + 1, texture.height, ref.wrap_t))};
  for (std::size_t row : rows) {
    const std::size_t i = (row * std::size_t(texture.width) + column) * 3;
    const void* address = texture.codes.empty() ? static_cast<const void*>(texture.rgb.data() + i)
                                                : static_cast<const void*>(texture.codes.data() + i);
#if defined(__x86_64__) || defined(__i386__)
    // GCC 12 deletes __builtin_prefetch here (it finds the address otherwise unused); the instruction
    // itself stays.
    asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(address)));
#else
    __builtin_prefetch(address);
#endif
  }
}

// The material of a textured triangle, else null.
const Material* textured_material(const Mesh& mesh, std::uint32_t triangle) {
  if (mesh.materials.empty() || mesh.base_color_uv.empty()) return nullptr;
  const Material& material = mesh.materials[mesh.triangle_material[triangle]];
  return material.textured() ? &material : nullptr;
}

// The fewest texels per world unit along any direction in `triangle`'s plane: the smaller singular
// value of the linear map from the triangle's edges p1 - p0, p2 - p0 to the texel-space edges d1, d2,
// the square root of the smaller root of det(D - lambda E) = 0 for the Gram matrices E of the world
// edges and D of the texel edges. 0 for a triangle degenerate in world space.
double sparsest_texel_density(const Mesh& mesh, std::uint32_t triangle, const glm::dvec2& d1, const glm::dvec2& d2) {
  const std::uint32_t* v = &mesh.indices[3 * std::size_t(triangle)];
  const glm::dvec3 p0(mesh.positions[v[0]]), e1 = glm::dvec3(mesh.positions[v[1]]) - p0, e2 = glm::dvec3(mesh.positions[v[2]]) - p0;
  const double e11 = glm::dot(e1, e1), e12 = glm::dot(e1, e2), e22 = glm::dot(e2, e2);
  const double t11 = glm::dot(d1, d1), t12 = glm::dot(d1, d2), t22 = glm::dot(d2, d2);
  const double a = e11 * e22 - e12 * e12, b = t11 * e22 + t22 * e11 - 2.0 * t12 * e12, c = t11 * t22 - t12 * t12;
  if (!(a > 0.0) || !std::isfinite(b) || !std::isfinite(c)) return 0.0;
  // The smaller root, written to avoid cancellation: 2c / (b + sqrt(b^2 - 4ac)).
  const double root = b + std::sqrt(std::max(0.0, b * b - 4.0 * a * c));
  return root > 0.0 ? std::sqrt(std::max(0.0, 2.0 * c / root)) : 0.0;
}

// The quadrature's split n and mip level for a region with barycentric corners `corners` (texture.h).
struct Quadrature {
  int n = kMinQuadrature, level = 0;
};

// The region's longest edge in texels of mip level `level` of the colour's texture.
double longest_edge(const TriangleColour& colour, const glm::dvec2 corners[3], int level) {
  return std::max({colour.texel_length(corners[0], corners[1], level), colour.texel_length(corners[1], corners[2], level),
                   colour.texel_length(corners[2], corners[0], level)});
}

// Level 0's n for the region, or 0 where it would exceed kMaxQuadrature (the region needs a mip level).
int quadrature_split(const TriangleColour& colour, const glm::dvec2 corners[3]) {
  const double n = std::ceil(kQuadraturePerTexel * longest_edge(colour, corners, 0));
  return n <= kMaxQuadrature ? std::max(kMinQuadrature, int(n)) : 0;
}

// texture.h: level 0 where its n fits, else n = kMaxQuadrature on the finest level whose texels the
// region's longest edge spans at most kMaxQuadrature of (the last level if none).
Quadrature quadrature_rule(const TriangleColour& colour, const glm::dvec2 corners[3]) {
  if (const int n = quadrature_split(colour, corners)) return {n, 0};
  int level = 1;
  while (level < colour.level_count() - 1 && !(longest_edge(colour, corners, level) <= kMaxQuadrature)) ++level;
  return {kMaxQuadrature, std::min(level, colour.level_count() - 1)};
}

// Calls f(barycentrics) at the centroid of each of the n x n sub-triangles of the region with
// barycentric corners `corners`, in a fixed order (each sub-triangle has 1 / n^2 of its area).
template <class F>
void for_each_centroid(const glm::dvec2 corners[3], int n, F f) {
  const glm::dvec2 a = corners[0], e1 = (corners[1] - a) / double(n), e2 = (corners[2] - a) / double(n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; i + j < n; ++j) {
      f(a + (i + 1.0 / 3.0) * e1 + (j + 1.0 / 3.0) * e2);
      if (i + j < n - 1) f(a + (i + 2.0 / 3.0) * e1 + (j + 2.0 / 3.0) * e2);
    }
}

double triangle_area(const Mesh& mesh, std::uint32_t triangle) {
  const std::uint32_t* v = &mesh.indices[3 * std::size_t(triangle)];
  const glm::dvec3 a(mesh.positions[v[0]]), b(mesh.positions[v[1]]), c(mesh.positions[v[2]]);
  return 0.5 * glm::length(glm::cross(b - a, c - a));
}

// The integrals over `triangle` of base colour x barycentric weight k, k = 0, 1, 2.
const glm::dvec2 kWholeTriangle[3] = {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}};

std::array<glm::dvec3, 3> hat_moments(const Mesh& mesh, std::uint32_t triangle, const MeshMips& mips) {
  const TriangleColour lookup(mesh, triangle, &mips);
  const Quadrature rule = quadrature_rule(lookup, kWholeTriangle);
  const int n = rule.n;  // (named copies: C++17 lambdas cannot capture structured bindings)
  std::array<glm::dvec3, 3> sums{glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
  for_each_centroid(kWholeTriangle, n, [&](const glm::dvec2& b) {
    const glm::dvec3 colour(lookup.at(b.x, b.y, rule.level));
    sums[0] += (1.0 - b.x - b.y) * colour;
    sums[1] += b.x * colour;
    sums[2] += b.y * colour;
  });
  const double weight = triangle_area(mesh, triangle) / (double(n) * double(n));
  for (glm::dvec3& s : sums) s *= weight;
  return sums;
}

}  // namespace

glm::vec2 transform_uv(const TextureTransform& transform, glm::vec2 uv) {
  const float x = transform.scale.x * uv.x, y = transform.scale.y * uv.y;
  // No rotation (the usual case, looked up per hit by the bakers): cos(+-0) = 1 and sin(+-0) = +-0
  // exactly (C Annex F), so skipping the calls changes no result.
  const float r = transform.rotation;
  const float c = r == 0.0f ? 1.0f : std::cos(r), s = r == 0.0f ? r : std::sin(r);
  return glm::vec2(transform.offset.x + x * c + y * s, transform.offset.y - x * s + y * c);
}

int wrap_texel(std::int64_t i, int n, Wrap mode) {
  if (i >= 0 && i < n) return int(i);  // inside the image: every mode agrees
  switch (mode) {
    case Wrap::clamp_to_edge:
      return int(std::clamp<std::int64_t>(i, 0, n - 1));
    case Wrap::mirrored_repeat: {
      const std::int64_t period = 2 * std::int64_t(n), m = ((i % period) + period) % period;
      return int(m < n ? m : period - 1 - m);
    }
    default:
      return int(((i % n) + n) % n);
  }
}

const std::array<float, 256>& srgb8_decode() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int code = 0; code < 256; ++code) t[std::size_t(code)] = float(srgb_to_linear(float(code) * (1.0f / 255)));
    return t;
  }();
  return table;
}

void pack_srgb8(Texture* texture) {
  const std::array<float, 256>& decode = srgb8_decode();
  std::vector<std::uint8_t> codes(texture->rgb.size());
  for (std::size_t i = 0; i < codes.size(); ++i) {
    const float v = texture->rgb[i];
    // The last code whose value is <= v, by a branch-free binary search (the table is increasing).
    std::size_t code = 0;
    for (std::size_t step = 128; step > 0; step /= 2) code += decode[code + step] <= v ? step : 0;
    // == alone would take -0 for +0 (a float file's); the sign bit keeps the packing bit-exact.
    if (!(decode[code] == v) || std::signbit(v)) return;
    codes[i] = std::uint8_t(code);
  }
  texture->codes = std::move(codes);
  texture->rgb = std::vector<float>();
}

std::vector<float> texture_rgb(const Texture& texture) {
  if (texture.codes.empty()) return texture.rgb;
  const std::array<float, 256>& decode = srgb8_decode();
  std::vector<float> rgb(texture.codes.size());
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = decode[texture.codes[i]];
  return rgb;
}

glm::vec3 sample_texture(const Texture& texture, const TextureRef& ref, glm::vec2 uv) {
  return sample_spot(texture, ref, ref.filter, locate(texture, ref.filter, uv));
}

TriangleColour::TriangleColour(const Mesh& mesh, std::uint32_t triangle, const MeshMips* mips) {
  if (!mesh.materials.empty()) factor_ = mesh.materials[mesh.triangle_material[triangle]].base_color_factor;
  if (const Material* material = textured_material(mesh, triangle)) {
    texture_ = &mesh.textures[std::size_t(material->base_color.image)];
    ref_ = &material->base_color;
    const glm::vec2* uv = &mesh.base_color_uv[3 * std::size_t(triangle)];
    const glm::dvec2 t0(transform_uv(ref_->transform, uv[0])), t1(transform_uv(ref_->transform, uv[1])),
        t2(transform_uv(ref_->transform, uv[2]));
    uv0_ = t0;
    du1_ = t1 - t0;
    du2_ = t2 - t0;
    const std::size_t image = std::size_t(material->base_color.image);
    if (mips && image < mips->size()) mips_ = (*mips)[image].get();
    if (mips_) texels_per_length_ = sparsest_texel_density(mesh, triangle, du1_ * glm::dvec2(texture_->width, texture_->height),
                                                           du2_ * glm::dvec2(texture_->width, texture_->height));
  }
  if (!mesh.vertex_color.empty())
    for (int k = 0; k < 3; ++k) colours_[k] = &mesh.vertex_color[mesh.indices[3 * std::size_t(triangle) + std::size_t(k)]];
}

TriangleColour::Request TriangleColour::locate_at(double b1, double b2, int level) const {
  if (!texture_) return Request{b1, b2};
  const Texture& texture = level_texture(level);
  const Spot s = locate(texture, filter(level), glm::vec2(uv0_ + b1 * du1_ + b2 * du2_));
  return Request{b1, b2, s.x0, s.y0, s.fx, s.fy, level};
}

TriangleColour::Request TriangleColour::request(double b1, double b2, int level) const {
  const Request r = locate_at(b1, b2, level);
  if (texture_) prefetch_texels(level_texture(level), *ref_, Spot{r.x0, r.y0, r.fx, r.fy});
  return r;
}

glm::vec3 TriangleColour::at(double b1, double b2, int level) const { return at(locate_at(b1, b2, level)); }

int TriangleColour::level_for(double width) const {
  const double texels = width * texels_per_length_;
  if (!mips_ || !(texels >= 2.0)) return 0;
  // The coarsest level whose texel (level 0 texels per level texel, along each axis) fits in `texels`.
  int level = std::min(std::ilogb(texels), mips_->level_count() - 1);
  const Texture& base = *texture_;
  for (; level > 0; --level) {
    const Texture& t = mips_->level(level);
    if (double(base.width) <= texels * t.width && double(base.height) <= texels * t.height) break;
  }
  return level;
}

glm::vec3 TriangleColour::at(const Request& r) const {
  const double b1 = r.b1, b2 = r.b2;
  glm::vec3 colour = factor_;
  if (texture_) colour *= sample_spot(level_texture(r.level), *ref_, filter(r.level), Spot{r.x0, r.y0, r.fx, r.fy});
  if (colours_[0])
    colour *= glm::vec3((1.0 - b1 - b2) * glm::dvec3(*colours_[0]) + b1 * glm::dvec3(*colours_[1]) + b2 * glm::dvec3(*colours_[2]));
  for (int c = 0; c < 3; ++c) colour[c] = std::isnan(colour[c]) ? 0.0f : std::clamp(colour[c], 0.0f, 1.0f);
  return colour;
}

double TriangleColour::texel_length(const glm::dvec2& a, const glm::dvec2& b, int level) const {
  if (!texture_) return 0.0;
  const Texture& texture = level_texture(level);
  const glm::dvec2 d = (b.x - a.x) * du1_ + (b.y - a.y) * du2_;
  return glm::length(d * glm::dvec2(texture.width, texture.height));
}

glm::vec3 base_color(const Mesh& mesh, std::uint32_t triangle, double b1, double b2) {
  return TriangleColour(mesh, triangle).at(b1, b2);
}

glm::vec3 region_average(const Mesh& mesh, std::uint32_t triangle, const glm::dvec2 corners[3]) {
  const TriangleColour level0(mesh, triangle);
  MeshMips mips;
  if (!quadrature_split(level0, corners)) {  // beyond kMaxQuadrature at level 0: the pyramid is needed
    std::vector<bool> needed(mesh.textures.size(), false);
    needed[std::size_t(mesh.materials[mesh.triangle_material[triangle]].base_color.image)] = true;
    mips = build_mips(mesh.textures, needed, 1);
  }
  const TriangleColour lookup(mesh, triangle, &mips);
  const Quadrature rule = quadrature_rule(lookup, corners);
  const int n = rule.n;
  glm::dvec3 sum(0.0);
  for_each_centroid(corners, n, [&](const glm::dvec2& b) { sum += glm::dvec3(lookup.at(b.x, b.y, rule.level)); });
  return glm::vec3(sum / (double(n) * double(n)));
}

void texture_albedo(const Mesh& mesh, int threads, std::vector<glm::vec3>* albedo) {
  if (!mesh.textured()) return;
  const std::size_t triangles = mesh.triangle_count();
  // Pyramids only for the textures of triangles that level 0's quadrature cannot take (texture.h).
  std::vector<bool> needed(mesh.textures.size(), false);
  for (std::uint32_t t = 0; t < triangles; ++t)
    if (const Material* material = textured_material(mesh, t))
      if (!quadrature_split(TriangleColour(mesh, t), kWholeTriangle)) needed[std::size_t(material->base_color.image)] = true;
  const MeshMips mips = build_mips(mesh.textures, needed, threads);
  std::vector<std::array<glm::dvec3, 3>> moments(triangles);
  parallel_for(triangles, 16, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) moments[t] = hat_moments(mesh, std::uint32_t(t), mips);
  });
  const VertexFootprints footprints(mesh);
  for (std::uint32_t v = 0; v < mesh.vertex_count(); ++v) {
    glm::dvec3 sum(0.0);
    double weight = 0.0;
    bool touches_texture = false;
    for (std::uint32_t corner : footprints.footprint_corners(v)) {
      const std::uint32_t t = corner / 3;
      touches_texture = touches_texture || textured_material(mesh, t) != nullptr;
      sum += moments[t][corner % 3];
      weight += triangle_area(mesh, t) / 3.0;
    }
    if (touches_texture && weight > 0.0) (*albedo)[v] = glm::vec3(sum / weight);
  }
}

}  // namespace prt::mesh
