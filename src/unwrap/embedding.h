#pragma once
// Whether a flattened chart is one-to-one, so that no texel of it can hold two surface points:
//   FOLDS: a triangle whose signed UV area is at most kMinAreaRatio of its 3D area (both in the
//     chart's area-normalised units, lscm.h) is folded over (negative) or crushed (near zero);
//   BORDER: two border edges of the chart (edges whose triangle across is not in the chart) that
//     cross or touch, other than at a shared welded vertex, mean the chart overlaps itself;
//   WRAP: a border vertex whose UV corner angles add up to 2 pi or more (less kAngleSlack) has its
//     chart wrapped around it onto itself (the two border edges there overlap, which BORDER skips).
// A map without folds whose border does not cross itself covers its image once (a disc-like chart
// whose border is a simple curve). Edges are bucketed in a uniform grid of about one edge length.
#include "unwrap/charts.h"
#include "unwrap/lscm.h"

namespace prt::unwrap {

/// A triangle whose UV area is below this share of its 3D area counts as folded (UV and 3D areas in
/// the same units: a chart's total UV area equals its 3D area).
inline constexpr double kMinAreaRatio = 1e-3;

/// Folded triangles of the chart (count).
std::size_t count_folds(const mesh::Mesh& mesh, const FlatChart& chart);

/// True if two border edges of the chart cross or touch away from a shared vertex.
bool border_crosses(const Surface& surface, const FlatChart& chart);

/// Slack of the WRAP test, radians.
inline constexpr double kAngleSlack = 1e-6;

/// True if some border vertex's UV angles add up to at least 2 pi - kAngleSlack.
bool wraps_around_vertex(const Surface& surface, const FlatChart& chart);

/// No folds, no border crossing, no wrap.
bool is_embedding(const mesh::Mesh& mesh, const Surface& surface, const FlatChart& chart);

}  // namespace prt::unwrap
