#pragma once
// Seam stitching of texel transfer (docs/conventions.md, "Lightmap charts, denoising and seams"): where one smooth surface
// edge appears twice in the lightmap UVs (a UV seam between two charts, or two chart borders), a
// bilinear lookup on the two sides reads different texels and the lit values jump. The stitch moves
// the texels those lookups read so that both sides agree, as little as it can, for every coefficient at
// once (so it holds under every lighting):
//   minimise  sum_t d_t |x_t - x0_t|^2  +  pull * sum_s |B_a(s) x - B_b(s) x|^2
// over the texels t that the lookups read, where x0 is the baked (or denoised) transfer, d_t = 1 for a
// covered texel and `gutter_weight` for a gutter texel (its value is only ever read by such lookups),
// and s runs over points along every seam edge (`samples_per_texel` per texel of the edge's longer UV
// side, at t = (k + 1/2)/N), B_a(s), B_b(s) the bilinear lookups there (texel centres at
// ((i + 1/2)/W, (j + 1/2)/H), clamped to the grid: the GPU's clamp-to-edge). The normal equations
// (D + pull A^T A) x = D x0 have one matrix for every coefficient: one sparse LDLT factorisation
// (Eigen), one solve per coefficient column. Deterministic (no threads).
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "mesh/mesh.h"

namespace prt::lightmap {

/// One seam edge: the same 3D edge (bit-identical end positions) in two triangles with different
/// lightmap UVs, whose vertex normals agree at both ends (a smooth edge; a hard edge is no seam: its
/// two sides may differ). uv_a[k] and uv_b[k] map the same 3D end point.
struct SeamEdge {
  std::uint32_t triangle_a = 0, triangle_b = 0;
  glm::vec2 uv_a[2], uv_b[2];
};

/// The seam edges of `mesh` (which must have lightmap UVs): every edge shared by exactly two
/// triangles (by position) whose UVs differ at an end and whose normals there have a dot product of at
/// least `smooth_cos`. Ordered by the first triangle's index, then its edge. Deterministic.
std::vector<SeamEdge> find_seams(const mesh::Mesh& mesh, float smooth_cos = 0.99f);

struct StitchOptions {
  double pull = 1e6;         ///< weight of the seams' agreement against staying close to the bake; > 0
  double gutter_weight = 0.05;  ///< d_t of a gutter texel (covered texels 1); > 0
  int samples_per_texel = 8;    ///< points per texel of seam edge (at least 4 per edge); 1..16
};

struct StitchReport {
  std::size_t seams = 0;        ///< seam edges
  std::size_t constraints = 0;  ///< seam points whose lookups read only filled texels
  std::size_t texels = 0;       ///< texels the stitch moved (unknowns)
};

/// Stitches `values` (and `bounce_only` unless empty; the same layout): `stride` floats per texel of
/// a width x height grid with `coverage` (transfer::Coverage, gutters already filled). Seam points whose
/// lookup reads an empty texel are left out. Throws prt::OptionError for options out of range.
StitchReport stitch_seams(std::vector<float>& values, std::vector<float>& bounce_only, std::size_t stride,
                          const std::vector<std::uint8_t>& coverage, int width, int height, const std::vector<SeamEdge>& seams,
                          const StitchOptions& options = {});

}  // namespace prt::lightmap
