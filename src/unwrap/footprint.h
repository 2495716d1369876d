#pragma once
// The texels a flattened chart touches at a given scale, as the packer needs them (docs/conventions.md,
// "Generated lightmap UVs"): per column of the chart's padded box, the lowest and highest row that its
// padded footprint occupies. A texel is touched when its square comes within kTouchSlack texels of one
// of the chart's UV triangles (a conservative rasterization, so float rounding of the final UVs cannot
// touch a texel the packer did not count); the padded footprint is every texel within Chebyshev
// distance `padding` of a touched one.
#include <vector>

#include <glm/vec2.hpp>

namespace prt::unwrap {

/// Slack, in texels, of the touch test above.
inline constexpr double kTouchSlack = 1e-3;

/// A chart's padded footprint as column profiles over its padded box, columns 0 .. width - 1:
/// column c holds rows [bottom[c], top[c]) (rows grow with v), or nothing when bottom[c] >= top[c].
/// The packer treats each column's range as full (holes inside a column are not reused).
struct ColumnProfile {
  int width = 0, height = 0;     ///< the padded box, in texels
  std::vector<int> bottom, top;  ///< width entries each; 0 <= bottom, top <= height where non-empty
};

/// The profile of the chart whose triangles have texel-space corners `corners` (3 per triangle, every
/// coordinate in [padding, padding + inner.x] x [padding, padding + inner.y], inner > 0), in a padded
/// box of ceil(inner) + 2 padding texels each way. Preconditions: padding >= 0; corners finite.
ColumnProfile column_profile(const std::vector<glm::dvec2>& corners, glm::dvec2 inner, int padding);

}  // namespace prt::unwrap
