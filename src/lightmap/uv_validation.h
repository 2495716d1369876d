#pragma once
// Checks of a mesh's lightmap UVs before baking (docs/conventions.md, "Lightmap texels" and "Lightmap
// UV defects"): UVs outside [0, 1], UV triangles of zero area, and overlapping charts (rasterize.h,
// OVERLAP). A few defects are tolerated:
//   - a UV component at most kUvHair outside [0, 1] is clamped into it (the rasterizer clamps);
//   - a triangle with a UV further outside (or not finite) and a triangle of zero UV area are skipped:
//     they get no texel of their own (rays that hit them read the lightmap at their UVs, clamped);
//   - a texel centre inside two triangles is sampled on one of them (rasterize.h, SAMPLE POINT).
// The UVs are refused when the skipped triangles cover more than kMaxDefectShare of the surface (3D
// area) or the overlapping texels are more than kMaxDefectShare of the covered texels. Skipped
// triangles covering more than that share with UVs outside [0, 1] are named tiling texture UVs.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "lightmap/rasterize.h"
#include "mesh/mesh.h"

namespace prt::lightmap {

/// A UV triangle has zero area when twice its area is at most this times its longest edge squared
/// (float UVs of collinear points leave about 1e-7 relative).
inline constexpr double kZeroAreaRelative = 1e-6;
/// UV components within this of [0, 1] are clamped (repaired), not refused: 1/1000 of the square.
inline constexpr float kUvHair = 1e-3f;
/// Largest share of the surface (skipped triangles) or of the covered texels (overlaps) tolerated.
inline constexpr double kMaxDefectShare = 0.01;
/// Example triangles kept per kind of defect (the summary names them all up to this many).
inline constexpr std::size_t kMaxExamples = 20;

struct UvProblems {
  std::size_t clamped = 0;    ///< triangles with a UV component at most kUvHair outside [0, 1]
  std::size_t outside = 0;    ///< triangles with a UV component further outside [0, 1] (or not finite)
  std::size_t zero_area = 0;  ///< triangles whose UV triangle has zero area (and no UV outside)
  std::vector<std::uint32_t> clamped_examples, outside_examples, zero_area_examples;  ///< up to kMaxExamples each
  double outside_area = 0.0, zero_area_area = 0.0, total_area = 0.0;  ///< 3D areas of those triangles, of the mesh
  glm::vec2 uv_lo{0.0f}, uv_hi{0.0f};  ///< range of the finite UV components
  std::size_t overlapping_texels = 0;  ///< from rasterize
  std::size_t covered_texels = 0;      ///< from rasterize
  std::vector<std::pair<std::uint32_t, std::uint32_t>> overlap_examples;
  /// No defect of any kind.
  bool ok() const { return clamped == 0 && outside == 0 && zero_area == 0 && overlapping_texels == 0; }
  /// Share of the surface (3D area) in skipped triangles.
  double skipped_share() const;
  /// True when the defects are beyond what is repaired or skipped (the rule above).
  bool refused() const;
  /// True when the triangles outside [0, 1] alone cover more than kMaxDefectShare of the surface.
  bool tiling() const;
  /// The refusal: one line naming every problem with its count and example triangles (mesh triangle
  /// indices, or glTF node/mesh/primitive and triangle), the shares and what to do, e.g. "lightmap
  /// UVs: 2 triangles have UVs outside [0,1] (e.g. triangles 4, 9); ...".
  std::string message(const mesh::Mesh& mesh) const;
  /// message() without what to do: why the file's UVs were not used when prt generates its own.
  std::string problems(const mesh::Mesh& mesh) const;
  /// What is tolerated, one line per kind (empty when ok()): counts, shares and every example triangle.
  std::vector<std::string> summary(const mesh::Mesh& mesh) const;
  /// Per triangle: 1 when it is skipped (outside or zero area), for rasterize.
  std::vector<std::uint8_t> skipped_triangles(const mesh::Mesh& mesh) const;
};

/// True if UV triangle (a, b, c) has zero area by the rule above.
bool uv_zero_area(const glm::vec2& a, const glm::vec2& b, const glm::vec2& c);

/// The range and zero-area checks of every triangle (the mesh must have lightmap UVs). `exclude` (one
/// per triangle, if given): triangles marked 1 are not checked and count no area (a mixed scene's
/// per-vertex parts, part_choice.h).
UvProblems check_uvs(const mesh::Mesh& mesh, const std::vector<std::uint8_t>* exclude = nullptr);

/// check_uvs of the triangles a texel bake rasterizes: all but `per_vertex`'s (one per triangle, 1: a
/// mixed scene's per-vertex triangle; empty: none); `skip` gets, per triangle, 1 where rasterize leaves
/// it out (skipped_triangles, or per vertex).
UvProblems check_texel_uvs(const mesh::Mesh& mesh, const std::vector<std::uint8_t>& per_vertex, std::vector<std::uint8_t>& skip);

/// check_uvs plus the overlaps and coverage of `samples` (rasterized with skipped_triangles).
void add_raster_checks(UvProblems& problems, const TexelSamples& samples);

}  // namespace prt::lightmap
