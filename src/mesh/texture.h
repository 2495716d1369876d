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
#include "mesh/texture_mips.h"

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
  /// `mips`: the pyramids of the mesh's textures (build_mips), for the filtered lookups below; null,
  /// or a null entry for this triangle's texture: every lookup reads level 0.
  TriangleColour(const Mesh& mesh, std::uint32_t triangle, const MeshMips* mips = nullptr);
  /// A placeholder to assign to: at() is (1, 1, 1), as for a mesh without materials or colours.
  TriangleColour() = default;

  /// The base colour at barycentrics (b1, b2), the point (1 - b1 - b2) p0 + b1 p1 + b2 p2: the texture
  /// at the transformed interpolated UV (1 if untextured) x the factor x the interpolated vertex colour
  /// (1 if none), clamped to [0, 1] (NaN: 0). (1, 1, 1) for a mesh without materials or colours (the
  /// caller's default albedo applies there: albedo_source none).
  /// With `level` > 0: at(request(b1, b2, level)), the filtered lookup below.
  glm::vec3 at(double b1, double b2, int level = 0) const;

  /// at(b1, b2) in two steps, for a loop over many lookups (a ray batch's hits): request() works out
  /// where the lookup reads and starts loading those texels into the CPU's cache; at(request) finishes
  /// it. Requesting every lookup first waits for memory once rather than once per lookup, and each
  /// lookup is located once. at(request(b1, b2)) == at(b1, b2), bit for bit.
  struct Request {
    double b1 = 0.0, b2 = 0.0;
    std::int64_t x0 = 0, y0 = 0;  // the texel (before wrapping) at or left-above the UV
    float fx = 0.0f, fy = 0.0f;   // bilinear fractions (nearest: 0)
    int level = 0;                // the mip level read (level_for)
  };
  /// With `level` > 0 (level_for's; precondition: < the pyramid's level_count()), the lookup reads that
  /// mip level of the texture, bilinearly whatever the sampler's filter, with the sampler's wrap modes:
  /// the texture's mean over about one level-`level` texel around the UV.
  Request request(double b1, double b2, int level = 0) const;
  glm::vec3 at(const Request& request) const;

  /// The mip level for a lookup standing for a disc of diameter `width` (world units, >= 0) on this
  /// triangle: the coarsest level whose texel is at most as many texels wide as the disc spans along
  /// the triangle's direction of fewest texels per unit length (so the filter never blurs beyond the
  /// disc in any direction; where the UV map stretches the texture unevenly, the disc spans more texels
  /// along the other direction than the level averages); 0 without a pyramid, for an untextured or
  /// degenerate triangle, and where the disc spans less than 2 level-0 texels.
  int level_for(double width) const;

  /// The length in texels of mip level `level` (< level_count()) of the transformed UV segment between
  /// the points with barycentrics a and b; 0 for an untextured triangle.
  double texel_length(const glm::dvec2& a, const glm::dvec2& b, int level = 0) const;

  /// The mip levels this triangle's lookups can read: its pyramid's level_count(), 1 without one.
  int level_count() const { return mips_ ? mips_->level_count() : 1; }

 private:
  Request locate_at(double b1, double b2, int level) const;  // request() without the prefetch
  const Texture& level_texture(int level) const { return level == 0 ? *texture_ : mips_->level(level); }
  Filter filter(int level) const { return level == 0 ? ref_->filter : Filter::linear; }

  glm::vec3 factor_{1.0f};
  const Texture* texture_ = nullptr;
  const TextureRef* ref_ = nullptr;
  glm::dvec2 uv0_{0.0}, du1_{0.0}, du2_{0.0};  // transformed UV = uv0 + b1 du1 + b2 du2
  const glm::vec3* colours_[3] = {nullptr, nullptr, nullptr};
  const TextureMips* mips_ = nullptr;  // the texture's pyramid, if built
  double texels_per_length_ = 0.0;     // level-0 texels per world unit, along the sparsest direction
};

/// TriangleColour(mesh, triangle).at(b1, b2), for a single lookup.
glm::vec3 base_color(const Mesh& mesh, std::uint32_t triangle, double b1, double b2);

/// The quadrature of the averages below splits a region of a triangle into n x n similar sub-triangles
/// and takes the base colour at each one's centroid. Level 0: n = ceil(kQuadraturePerTexel x the
/// region's longest edge in texels of its texture, after the transform), at least kMinQuadrature:
/// sub-triangle edges of at most 1/2 texel, for regions up to kMaxQuadrature / 2 = 16 texels across
/// (untextured regions use kMinQuadrature: the base colour is linear there, up to the clamp). Larger
/// regions take n = kMaxQuadrature on the finest box-filtered mip level (TextureMips) whose texels
/// their longest edge spans at most kMaxQuadrature of (sub-triangles of at most one texel there), read
/// bilinearly: at most 32^2 lookups per region however many texels it covers (O(triangles) per mesh; a
/// cap of 512 at level 0 made a spider.obj load 1.4 s). Error bound beyond level 0: the mip level's mean
/// is the texture's mean for detail that repeats within one of its texels (2^L level-0 texels, 1/32 to
/// 1/16 of the longest edge), but texels outside the region blend in within about 1.5 of its texels of
/// the region's edges (an atlas chart's neighbour: at most the texture's contrast times the share of the
/// region that band covers), and 32 centroids across a jump in the texture miss its place by up to 1/32
/// of the region. Measured (tests/mesh/test_texture_mips.cpp, against the exact hat-weighted average
/// integrated by brute force): stripes of contrast 0.6 three repeats across a quad, 768 texels long,
/// 2.2e-3 (0.5%); a hundred repeats, 1.1e-3. Checkers at level 0 within 0.2% (test_texture.cpp).
inline constexpr int kQuadraturePerTexel = 2;
inline constexpr int kMinQuadrature = 4;
inline constexpr int kMaxQuadrature = 32;

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
