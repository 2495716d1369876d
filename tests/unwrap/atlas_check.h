#pragma once
// An independent check of lightmap UVs (shares no code with src/unwrap or src/lightmap): conservative
// rasterization of every UV triangle into the texel grid by the separating axis test (a triangle
// touches a texel when their interiors overlap by more than kTouchEpsilon texels on every axis), and
// charts as the connected components of triangles sharing a vertex index (prt unwrap's GLB splits
// vertices by UV, so two charts never share one).
#include <cstddef>
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace prt::test {

struct AtlasCheck {
  std::size_t charts = 0;
  std::size_t triangles_without_texel = 0;  ///< UV triangles touching no texel
  std::size_t shared_texels = 0;            ///< texels touched by two charts
  std::size_t padding_violations = 0;       ///< texels within 2 * padding (Chebyshev) of another chart's texel
  std::size_t double_centres = 0;           ///< texel centres strictly inside two triangles of one chart
  std::size_t outside = 0;                  ///< UV components outside [0, 1]
  std::size_t touched = 0;                  ///< texels touched by some triangle
  double p95_over_mean = 0.0;               ///< world area per texel: 95th percentile (over texels) / mean
};

/// Checks `mesh`'s lightmap UVs for a width x height lightmap with the stated `padding`.
AtlasCheck check_atlas(const mesh::Mesh& mesh, int width, int height, int padding);

}  // namespace prt::test
