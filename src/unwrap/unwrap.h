#pragma once
// Lightmap UV generation (`prt unwrap`, `prt bake --uv auto`; docs/conventions.md, "Generated
// lightmap UVs"): charts (charts.h) -> least-squares conformal maps (lscm.h), checked one-to-one
// (embedding.h) -> packing (pack.h). A chart whose map folds or overlaps itself is cut in two at the
// median of its triangles' centroids along its longest axis, each half split into connected pieces
// and flattened again; a piece of at most kPlanarPiece triangles whose LSCM fails is tried by planar
// projection first, and a single triangle is always flattened exactly. Charts are flattened in
// parallel (each writes only its own result) and packed in one thread: byte-identical UVs for any
// thread count.
#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "mesh/mesh.h"

namespace prt::unwrap {

/// Pieces of at most this many triangles whose LSCM fails try planar projection before being cut.
inline constexpr std::size_t kPlanarPiece = 64;

struct UnwrapOptions {
  int width = 1024, height = 1024;  ///< the lightmap the UVs are packed for, texels (1..16384)
  int padding = 2;                  ///< empty texels around every chart (pack.h), 0..64
  double chart_angle = 60.0;  ///< chart normal cone half-angle (charts.h), (0, 89]
  int threads = 0;                  ///< 0 = all cores; the UVs do not depend on it
  std::string mesh_path;            ///< names the mesh in the error when its charts do not fit; empty: none
};

struct UnwrapReport {
  std::size_t charts = 0;          ///< charts packed
  std::size_t grown_charts = 0;    ///< charts from region growing, before any cut
  std::size_t cut_charts = 0;      ///< pieces cut because their map folded or overlapped itself
  std::size_t planar_pieces = 0;   ///< pieces flattened by planar projection
  double texels_per_unit = 0.0;    ///< texel density (texels per world unit of length)
  double fill = 0.0;               ///< share of the lightmap inside UV triangles
  double seconds = 0.0;
};

/// Throws prt::OptionError for options out of range (what unwrap checks first).
void check_options(const UnwrapOptions& options);

/// Lightmap UVs for `mesh` (which needs one normal per vertex, as load_mesh gives): one per triangle
/// corner (Mesh::lightmap_uv's layout and v-down convention), in [0, 1]. Throws prt::OptionError for
/// options out of range and prt::Error ("<mesh_path>: N charts do not fit ...") when the charts do not fit the lightmap.
std::vector<glm::vec2> unwrap(const mesh::Mesh& mesh, const UnwrapOptions& options, UnwrapReport* report = nullptr);

}  // namespace prt::unwrap
