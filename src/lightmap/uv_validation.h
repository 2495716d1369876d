#pragma once
// Checks of a mesh's lightmap UVs before baking (docs/conventions.md, "Lightmap texels"): UVs
// outside [0, 1], UV triangles of zero area, and overlapping charts (rasterize.h, OVERLAP).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "lightmap/rasterize.h"
#include "mesh/mesh.h"

namespace prt::lightmap {

/// A UV triangle has zero area when twice its area is at most this times its longest edge squared
/// (float UVs of collinear points leave about 1e-7 relative).
inline constexpr double kZeroAreaRelative = 1e-6;

struct UvProblems {
  std::size_t outside = 0;    ///< triangles with a UV component outside [0, 1] (or not finite)
  std::size_t zero_area = 0;  ///< triangles whose UV triangle has zero area
  std::vector<std::uint32_t> outside_examples, zero_area_examples;  ///< up to 3 triangle indices each
  std::size_t overlapping_texels = 0;  ///< from rasterize
  std::vector<std::pair<std::uint32_t, std::uint32_t>> overlap_examples;
  bool ok() const { return outside == 0 && zero_area == 0 && overlapping_texels == 0; }
  /// One line naming every problem with its count and example triangles, e.g. "lightmap UVs: 2
  /// triangles have UVs outside [0,1] (e.g. triangles 4, 9); ...".
  std::string message() const;
};

/// True if UV triangle (a, b, c) has zero area by the rule above.
bool uv_zero_area(const glm::vec2& a, const glm::vec2& b, const glm::vec2& c);

/// The range and zero-area checks of every triangle (the mesh must have lightmap UVs).
UvProblems check_uvs(const mesh::Mesh& mesh);

}  // namespace prt::lightmap
