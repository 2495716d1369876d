#pragma once
// Robust texel sample points: samples buried inside geometry (under a wall, inside an object that
// rests on or intersects the surface, in an unwelded crease) are moved out, the way production
// lightmappers use a back-face tolerance (docs/conventions.md, "Lightmap texels").
//
// RULE. From each sample (position p, unit normal n; rays start at Scene::offset_origin(p, n)) trace
// kProbeRays closest-hit rays over the cosine-weighted hemisphere about n (an Owen-scrambled Sobol
// set, in the frame sh::vertex_frame(n, seed, texel)), each of length r = kProbeRange x the world
// size of one texel on the sample's triangle (sqrt(world area / area in texels)). The sample is
// BURIED when at least kBuriedFraction of them hit a back face (ray against the geometric normal's
// side) within r. A buried sample moves: to the nearest such back-face hit h, pushed out along that
// face's unit geometric normal ng by max(4 ray_offset, 1e-3 r), then projected along n onto the plane
// through p with normal n (the sample stays on its surface's plane, within about r of where it was).
// The moved sample is tested again; if it is still buried the original point is kept and the sample
// counts as UNRECOVERABLE.
#include <cstddef>
#include <cstdint>

#include "lightmap/rasterize.h"
#include "mesh/mesh.h"
#include "trace/scene.h"

namespace prt::lightmap {

inline constexpr int kProbeRays = 32;
inline constexpr float kProbeRange = 1.5f;
inline constexpr float kBuriedFraction = 0.1f;

struct RepairReport {
  std::size_t moved = 0;          ///< samples found buried and moved out
  std::size_t unrecoverable = 0;  ///< buried samples that stayed buried after the move (kept)
  std::uint64_t rays = 0;
};

/// World length of one texel on triangle t of `mesh` for a width x height lightmap.
float texel_world_size(const mesh::Mesh& mesh, std::uint32_t t, int width, int height);

/// Whether the sample at (p, n) is buried by the rule above, and if so the moved point.
/// `range` is r; `index` the texel (for the frame's rotation).
bool probe_buried(const trace::Scene& scene, const glm::vec3& p, const glm::vec3& n, float range, std::uint32_t seed,
                  std::uint32_t index, glm::vec3* moved);

/// Applies the rule to every sample of `samples` (positions replaced where moved). Deterministic,
/// parallel on `threads` threads.
RepairReport repair_samples(const mesh::Mesh& mesh, const trace::Scene& scene, TexelSamples& samples, std::uint32_t seed,
                            int threads);

}  // namespace prt::lightmap
