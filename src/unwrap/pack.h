#pragma once
// Packing flattened charts into a lightmap of W x H texels (docs/conventions.md, "Generated lightmap
// UVs"):
//   ORIENTATION: each chart is turned so that its smallest-area bounding rectangle (over the edges of
//     its convex hull) is axis-aligned, its longer side horizontal;
//   PLACEMENT: charts sorted by the height, then the width of their padded rectangles (both
//     descending), then chart order. Each chart's padded footprint (footprint.h: the texels it
//     touches grown by `padding`) is held as column profiles, in two turns (as oriented, and half a
//     turn); it rests on the skyline of the charts before it at the lowest position, then the one with
//     the least gap under it, then the leftmost, in whichever turn rests lower. Profiles nest where
//     rectangles cannot (a triangle's slope against its neighbour's); holes under a chart's overhang
//     are not reused;
//   SCALE: s, texels per world unit, one for all charts (the texel density is the same everywhere,
//     LSCM's own area distortion aside): the largest at which rectangles of ceil(ex s + 2 kMargin) x
//     ceil(ey s + 2 kMargin) texels plus `padding` on each side fit the same skyline (bisection, 24
//     steps in log s), then the largest up to twice that at which the profiles fit (7 more steps); the
//     rectangles' layout when the profiles do not fit at the rectangles' scale.
//   A chart's UVs start kMargin texels inside its padded box's inner part, at an integer texel offset.
// So two charts' touched texels are at least 2 * padding texels apart (and `padding` from the image
// border). Deterministic and single-threaded.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "unwrap/lscm.h"

namespace prt::unwrap {

/// Distance, in texels, between a chart's UVs and the edge of its own texels.
inline constexpr double kMargin = 0.01;

struct PackOptions {
  int width = 1024, height = 1024;  ///< lightmap size in texels, 1..16384
  int padding = 2;                  ///< empty texels around each chart's texels, 0..64
};

struct PackResult {
  double texels_per_unit = 0.0;  ///< the scale s
  double fill = 0.0;             ///< share of the atlas inside charts' UV triangles (sum of UV areas / W H)
};

/// Orients, scales and places `charts` (their corner_uv become texel coordinates) and writes
/// uv[3t + k] = the UV in [0, 1] (u = x / W, v = y / H, v down) of corner k of each chart triangle t;
/// `uv` must have 3 entries per mesh triangle. Throws prt::Error when even the smallest scale
/// (each chart one texel plus padding) does not fit ("N charts do not fit a WxH lightmap ...").
PackResult pack_charts(std::vector<FlatChart>& charts, const PackOptions& options, std::vector<glm::vec2>& uv);

}  // namespace prt::unwrap
