#pragma once
// Gutters: dilation of a lightmap's charts so that bilinear filtering and mip-mapping across a chart
// border never read an empty texel (docs/conventions.md, "Lightmap texels").
//
// RULE. `passes` rounds; in each, every texel that is still empty and has at least one filled
// (covered, or gutter from an earlier round) texel among its 8 neighbours becomes a gutter texel
// holding the mean of those filled neighbours' values. After N rounds every texel within Chebyshev
// distance N of a covered texel is filled. Deterministic (each round reads only the previous rounds).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace prt::lightmap {

/// Default gutter width in texels (`prt bake --gutter`).
inline constexpr int kDefaultGutter = 2;

/// Marks the gutter texels of `coverage` (width x height, transfer::Coverage) for `passes` rounds:
/// returns the texels to fill, round by round, in row-major order within a round. Covered texels
/// are untouched; coverage gains kTexelGutter.
std::vector<std::vector<std::uint32_t>> grow_gutter(std::vector<std::uint8_t>& coverage, int width, int height, int passes);

/// The rounds grow_gutter produced (with `passes`, the bake's gutter) for an already grown mask (a
/// texel file's coverage): gutter texels by Chebyshev distance to the covered ones.
std::vector<std::vector<std::uint32_t>> gutter_rounds(const std::vector<std::uint8_t>& coverage, int width, int height, int passes);

/// Fills the gutter texels listed by grow_gutter in `values` (`stride` floats per texel, row-major):
/// each the mean of its neighbours filled before its round. `coverage` is the grown mask.
void fill_gutter(std::vector<float>& values, std::size_t stride, const std::vector<std::uint8_t>& coverage,
                 const std::vector<std::vector<std::uint32_t>>& rounds, int width, int height);

}  // namespace prt::lightmap
