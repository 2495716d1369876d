#pragma once
// Base colour lookups: the base colour of a mesh at a point of a triangle (texture x factor x vertex
// colour, mesh.h "MATERIALS AND BASE COLOUR"), the texture filter with the glTF wrap modes, averages
// over regions of a triangle, and the per-vertex albedo of textured meshes. Shared by the loaders
// (Mesh::albedo), the bakers' and the reference's hit lookups, and the renderer's texture upload.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "mesh/material.h"
#include "mesh/mesh.h"

namespace prt::mesh {

/// The linear values of the 256 8-bit sRGB codes, exactly as prt's image decoder makes them from an
/// 8-bit sRGB file: float(srgb_to_linear(float(code) * (1.0f / 255))) (core/srgb.h); strictly increasing.
const std::array<float, 256>& srgb8_decode();

/// Replaces texture->rgb by texture->codes when every value is, bit for bit, an entry of
/// srgb8_decode() (lookups then return the same floats); otherwise leaves the texture as it is.
/// Precondition: texture->codes empty.
void pack_srgb8(Texture* texture);

/// The texture's linear RGB, width * height * 3 floats as Texture::rgb lays them out, from either form.
std::vector<float> texture_rgb(const Texture& texture);

/// `uv` through the KHR_texture_transform `transform` (material.h).
glm::vec2 transform_uv(const TextureTransform& transform, glm::vec2 uv);

/// Texel index `i` (any integer) of an axis of `n` >= 1 texels, wrapped into [0, n): repeat, i mod n;
/// clamp_to_edge, clamped to [0, n - 1]; mirrored_repeat, reflected every n texels (n - 1 ... 0 0 ...
/// n - 1 n - 1 ... 0 around the image, as glTF / OpenGL MIRRORED_REPEAT).
int wrap_texel(std::int64_t i, int n, Wrap mode);

/// The texture at `uv` (already transformed; u right, v down, (0, 0) the image's top-left corner).
/// linear: bilinear between the 4 texel centres around uv (texel (x, y)'s centre is at ((x + 1/2) /
/// width, (y + 1/2) / height)), each index wrapped with the ref's wrap modes; nearest: texel
/// (floor(u width), floor(v height)), wrapped. A non-finite uv reads texel (0, 0). Both forms of Texture
/// give the same result bit for bit. Precondition: width, height >= 1 and width * height * 3 values in
/// rgb or codes.
glm::vec3 sample_texture(const Texture& texture, const TextureRef& ref, glm::vec2 uv);

/// The base colour over one triangle, set up once for many lookups on it (the quadratures below, a
/// renderer's or a baker's loop over hits): the material's factor, texture and sampler, the affine map
/// from barycentrics to transformed UVs (KHR_texture_transform is affine), and the vertex colours.
/// Holds pointers into the mesh (which must outlive it). Preconditions: triangle < triangle_count();
/// the mesh as load_mesh makes it (the vectors' sizes of mesh.h).
class TriangleColour {
 public:
  TriangleColour(const Mesh& mesh, std::uint32_t triangle);
  /// A placeholder to assign to: at() is (1, 1, 1), as for a mesh without materials or colours.
  TriangleColour() = default;

  /// The base colour at barycentrics (b1, b2), the point (1 - b1 - b2) p0 + b1 p1 + b2 p2: the texture
  /// at the transformed interpolated UV (1 if untextured) x the factor x the interpolated vertex colour
  /// (1 if none), clamped to [0, 1] (NaN: 0). (1, 1, 1) for a mesh without materials or colours (the
  /// caller's default albedo applies there: albedo_source none).
  glm::vec3 at(double b1, double b2) const;

  /// at(b1, b2) in two steps, for a loop over many lookups (a ray batch's hits): request() works out
  /// where the lookup reads and starts loading those texels into the CPU's cache; at(request) finishes
  /// it. Requesting every lookup first waits for memory once rather than once per lookup, and each
  /// lookup is located once. at(request(b1, b2)) == at(b1, b2), bit for bit.
  struct Request {
    double b1 = 0.0, b2 = 0.0;
    std::int64_t x0 = 0, y0 = 0;  // the texel (before wrapping) at or left-above the UV
    float fx = 0.0f, fy = 0.0f;   // bilinear fractions (nearest: 0)
  };
  Request request(double b1, double b2) const;
  glm::vec3 at(const Request& request) const;

  /// The length in texels of the transformed UV segment between the points with barycentrics a and b;
  /// 0 for an untextured triangle.
  double texel_length(const glm::dvec2& a, const glm::dvec2& b) const;

 private:
  glm::vec3 factor_{1.0f};
  const Texture* texture_ = nullptr;
  const TextureRef* ref_ = nullptr;
  glm::dvec2 uv0_{0.0}, du1_{0.0}, du2_{0.0};  // transformed UV = uv0 + b1 du1 + b2 du2
  const glm::vec3* colours_[3] = {nullptr, nullptr, nullptr};
};

/// TriangleColour(mesh, triangle).at(b1, b2), for a single lookup.
glm::vec3 base_color(const Mesh& mesh, std::uint32_t triangle, double b1, double b2);

/// The quadrature of the averages below splits a region of a triangle into n x n similar sub-triangles
/// and takes the base colour at each one's centroid. n = ceil(kQuadraturePerTexel x the region's longest
/// edge in texels of its texture, after the transform), clamped to [kMinQuadrature, kMaxQuadrature]:
/// sub-triangle edges of at most 1/2 texel for regions up to 256 texels across, coarser beyond (the cap
/// bounds a triangle's cost at 512^2 lookups: a fuzzed 12-triangle glTF whose UVs span thousands of texels
/// took 24 s under AddressSanitizer at a cap of 2048); untextured regions use kMinQuadrature (the base
/// colour is linear there, up to the clamp). tests/mesh/test_texture.cpp bounds the error on checker
/// textures.
inline constexpr int kQuadraturePerTexel = 2;
inline constexpr int kMinQuadrature = 4;
inline constexpr int kMaxQuadrature = 512;

/// The mean base colour over the part of `triangle` whose corners have barycentrics (b1, b2) =
/// corners[0], corners[1], corners[2] (the whole triangle: (0,0), (1,0), (0,1)), by the quadrature
/// above, summed in double in a fixed order. Preconditions: as base_color; the corners inside the
/// triangle.
glm::vec3 region_average(const Mesh& mesh, std::uint32_t triangle, const glm::dvec2 corners[3]);

/// Per-vertex albedo from textures: for each vertex whose footprint (VertexFootprints) holds a corner
/// of a textured triangle, the footprint's hat-weighted mean base colour, sum over its corners (t, k)
/// of the integral of base colour x barycentric weight k over triangle t, divided by the sum of area(t)
/// / 3 (the quadrature above, over whole triangles); other entries of `albedo` are left as they are.
/// Triangles run in parallel on `threads` threads (0: all), each writing its own sums, so the result
/// does not depend on the thread count. Preconditions: albedo->size() == vertex_count(); normals set.
void texture_albedo(const Mesh& mesh, int threads, std::vector<glm::vec3>* albedo);

}  // namespace prt::mesh
