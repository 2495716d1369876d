#pragma once
// Texel sample points of a lightmap: conservative rasterization of the mesh's lightmap UVs
// (docs/conventions.md, "Lightmap texels").
//
// COVERAGE. A texel (i, j) is covered when a triangle's UV triangle, in texel units (u W, v H),
// overlaps the texel's square [i, i+1] x [j, j+1] with positive area (touching only along an edge
// or at a corner does not count). Every covered texel gets exactly one sample.
//
// SAMPLE POINT. Of the triangles overlapping a texel, the one whose UV triangle is nearest to the
// texel centre owns it: distance 0 when the centre is inside, else the distance to the triangle's
// part inside the texel's square; ties go to the lower triangle index. The sample is that nearest
// point: the centre itself when it is inside, else a point of the triangle's boundary clipped to the
// texel (an edge texel samples the nearest point inside the triangle, and stays in its texel). Position, normal (normalised) and albedo are interpolated barycentrically from that
// triangle's corners at the sample's barycentrics; on a textured mesh the albedo is the base colour
// there (mesh::base_color), the texel receiver's albedo of docs/conventions.md "Albedo and textures".
//
// OVERLAP. Two triangles whose UV triangles both contain a texel centre strictly inside (every
// barycentric above kInsideEpsilon) overlap at that texel: the charts overlap. Adjacent triangles of
// one chart share an edge and never both contain a centre strictly.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/mesh.h"

namespace prt::lightmap {

/// Barycentric margin of the strict inside test used for overlaps.
inline constexpr double kInsideEpsilon = 1e-6;

struct TexelSample {
  std::uint32_t texel = 0;     ///< i + j * width
  std::uint32_t triangle = 0;  ///< the owning triangle (mesh triangle index)
  glm::vec3 barycentric{0.0f}; ///< of the sample in the triangle's corners 0, 1, 2 (sum 1, each >= 0)
  glm::vec3 position{0.0f};    ///< interpolated (before any repair, sample_repair.h)
  glm::vec3 normal{0.0f, 1.0f, 0.0f};  ///< interpolated vertex normals, unit
  glm::vec3 albedo{0.0f};      ///< interpolated per-vertex albedo; textured meshes: the base colour at the point
};

struct TexelSamples {
  int width = 0, height = 0;
  std::vector<std::uint8_t> coverage;  ///< width x height, transfer::kTexelEmpty or kTexelCovered
  std::vector<TexelSample> samples;    ///< one per covered texel, in row-major texel order
  std::size_t overlapping_texels = 0;  ///< texels whose centre lies strictly inside two or more triangles (each counted once)
  std::vector<std::pair<std::uint32_t, std::uint32_t>> overlap_examples;  ///< up to 3 triangle pairs
};

/// Rasterizes the triangles of `mesh` (which must have lightmap UVs) into a width x height grid
/// (1..16384 each). `albedo` has one entry per vertex. Triangles whose UV triangle has zero area
/// (uv_validation.h) are skipped, and so are those `skip` (one per triangle, if given) marks 1; UVs
/// outside [0, 1] are clamped to the grid. Deterministic, parallel over rows on `threads` threads (0 = all).
TexelSamples rasterize(const mesh::Mesh& mesh, const std::vector<glm::vec3>& albedo, int width, int height, int threads = 0,
                       const std::vector<std::uint8_t>* skip = nullptr);

}  // namespace prt::lightmap
