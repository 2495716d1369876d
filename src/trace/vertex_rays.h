#pragma once
// The loop every per-vertex hemisphere pass runs (the bake's shadowed, interreflection and glossy
// passes, the probes' surface passes): vertices in a given order, split over threads in chunks of 64;
// each chunk first finds its vertices' Scene::spawn_point(p, n) (one point query each, in a row: 1.5-3%
// of a pass cheaper than one before each vertex's rays, Cornell box 437k vertices and blob class, paired
// per block), then each vertex traces the same local sample directions turned into its own frame
// sh::vertex_frame(n, seed, v), from its spawn point, in batches of up to
// kDefaultBatchCapacity rays, robust mode where the scene's contact rule asks for it and for every
// closest-hit query (trace/scene.h, ROBUST MODE). What a pass does with the hits is its worker's business.
// With a footprint (VertexRays::footprints) the rays of a vertex leave from mesh::footprint_point_count(S)
// points of its one-ring instead of the vertex itself (docs/conventions.md "Vertex footprint"), each
// with a run of consecutive directions.
// The "vertices" may be other surface sample points (a lightmap's texel samples): VertexRays::positions
// and ::normals then replace the mesh's, and the index v names a sample point.
// THE TRUE-SURFACE RULE (trace/true_surface.h) is applied here, for every pass alike: where a ray leaves
// from a point on one triangle (a footprint point, or a sample point with a geometric normal), a ray
// below that triangle's plane is blocked after the query (RayBatch::block: occluded, no hit), so the
// direct passes count it occluded and the bounce passes gather nothing along it. Rays from a mesh
// vertex itself are left as traced.
#include <algorithm>
#include <cassert>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "core/hash.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "mesh/mesh.h"
#include "mesh/vertex_footprint.h"
#include "sh/sampling.h"
#include "trace/scene.h"
#include "trace/true_surface.h"

namespace prt::trace {

/// Vertices per parallel_for chunk of trace_vertex_rays.
inline constexpr std::size_t kVerticesPerChunk = 64;

/// Salt of the hash (core/hash.h) that scrambles a vertex's footprint points.
inline constexpr std::uint32_t kFootprintSalt = 0xf0070000u;

/// The first `count` (<= mesh::kMaxFootprintPoints) ray origins of vertex v with a footprint: point k =
/// footprints.stratified_point(v, k, hash_to_u32(seed, v, kFootprintSalt)), lifted off the surface along the vertex normal n as Scene::offset_origin does (the lift
/// stays above every one-ring face whose normal is within 90 degrees of n).
/// With `triangles` given, also the triangle each point lies on (mesh::kNoTriangle if none).
inline void footprint_origins(const mesh::VertexFootprints& footprints, const Scene& scene, std::uint32_t v,
                              const glm::vec3& n, std::uint32_t seed, std::size_t count, glm::vec3* out,
                              std::uint32_t* triangles = nullptr) {
  const std::uint32_t scramble = hash_to_u32(seed, v, kFootprintSalt);
  for (std::size_t k = 0; k < count; ++k)
    out[k] = scene.offset_origin(
        footprints.stratified_point(v, static_cast<std::uint32_t>(k), scramble, triangles ? triangles + k : nullptr), n);
}

/// After a query on rays first .. first + batch.size() - 1 of a point's `samples` rays, ray s leaving
/// from origin s * rule_count / samples with rules[that origin]: blocks the rays below the origin's
/// triangle (the true-surface rule).
inline void apply_true_surface(RayBatch& batch, const TrueSurface* rules, std::size_t rule_count, std::size_t first,
                               std::size_t samples) {
  for (std::size_t i = 0; i < batch.size(); ++i)
    if (!rules[(first + i) * rule_count / samples].admits(glm::dvec3(batch.direction(i)))) batch.block(i);
}

/// Which query a pass runs on its rays.
enum class Query { occluded, closest_hit };

/// What the loop needs; all pointers must outlive the call.
struct VertexRays {
  const Scene* scene = nullptr;
  const mesh::Mesh* mesh = nullptr;                   ///< unit normals
  const std::vector<std::uint32_t>* order = nullptr;  ///< vertices to visit, in this order (Morton)
  const std::vector<glm::vec3>* directions = nullptr; ///< S local directions about +z (direction_sets x S with direction_set)
  std::uint32_t seed = 0;                             ///< of sh::vertex_frame
  int threads = 0;
  Query query = Query::closest_hit;
  /// Sample points other than the mesh's vertices (both set, same size; `order` indexes them); null:
  /// the mesh's positions and normals.
  const std::vector<glm::vec3>* positions = nullptr;
  const std::vector<glm::vec3>* normals = nullptr;
  /// The positions [order_begin, order_end) of `order` to visit (one rank's share of a distributed run,
  /// dist/partition.h); clipped to order->size(). Default: all of them.
  std::size_t order_begin = 0;
  std::size_t order_end = static_cast<std::size_t>(-1);
  /// The mesh's vertex footprints: rays leave from points of each vertex's one-ring (footprint_origins)
  /// instead of the vertex; the robust-mode choice stays the vertex's. Null: from the points
  /// themselves. With `positions` set: only points v >= footprint_first, which are then mesh vertex
  /// v - footprint_first (a mixed scene's vertices after its texel samples, lightmap/texel_bake.h).
  const mesh::VertexFootprints* footprints = nullptr;
  /// With `positions`: the unit geometric normal of each sample point's triangle (the true-surface
  /// rule's; a zero entry: none). Null: no rule at the sample points.
  const std::vector<glm::vec3>* geometric_normals = nullptr;
  /// Every point's sample frame unturned, sh::turned_frame(n, 0), instead of sh::vertex_frame's hashed
  /// turn (interleaved sample sets, whose strata a turn would scramble).
  bool unturned_frames = false;
  /// With `positions` and `footprints`: the first point that is a mesh vertex (see footprints).
  std::size_t footprint_first = static_cast<std::size_t>(-1);
  /// Per point (indexed like `positions`): which of the direction_sets sets of S = directions->size() /
  /// direction_sets directions it traces, k: directions [k S, (k + 1) S). Null: every point traces all
  /// of `directions` (direction_sets must then be 1).
  const std::vector<std::uint8_t>* direction_set = nullptr;
  std::size_t direction_sets = 1;
};

/// Runs the loop above. `make_worker()` makes one worker per chunk (its state is kept across the
/// chunk's vertices), with
///   void start(std::uint32_t v, const glm::mat3& frame);   before v's first batch
///   void batch(std::uint32_t v, const RayBatch& batch, std::size_t first);
///        after each batch's query and the true-surface rule: the batch holds rays first ..
///        first + batch.size() - 1 of v
///   void finish(std::uint32_t v, const glm::mat3& frame);  after v's last batch
/// `progress` (of order->size() items) advances by each chunk's vertices, scaled by the whole order over
/// the visited share (so a rank's bar estimates the whole job; ranks get equal shares). Returns the rays
/// traced. Deterministic: each vertex's rays and their order do not depend on the thread that runs them.
template <class MakeWorker>
std::uint64_t trace_vertex_rays(const VertexRays& r, Progress& progress, MakeWorker make_worker) {
  const std::vector<glm::vec3>& positions = r.positions ? *r.positions : r.mesh->positions;
  const std::vector<glm::vec3>& normals = r.normals ? *r.normals : r.mesh->normals;
  const std::size_t samples = r.directions->size() / r.direction_sets;
  // Closest hits always go through robust mode (a scene without it builds its robust BVH on first use):
  // without it ~5e-6 of vertex rays name a wrong triangle (trace/scene.h, ROBUST MODE), and a bounce
  // pass reads transfer at the hit. Occlusion takes robust mode only for contact points.
  const bool closest_robust = r.query == Query::closest_hit;
  // Points with footprints: every vertex, or a mixed scene's vertices after footprint_first.
  const std::size_t first_spread = r.footprints == nullptr ? static_cast<std::size_t>(-1) : r.positions == nullptr ? 0 : r.footprint_first;
  const int capped_samples = static_cast<int>(std::min<std::size_t>(samples, INT32_MAX));
  const std::size_t origin_count = static_cast<std::size_t>(mesh::footprint_point_count(capped_samples));
  std::atomic<std::uint64_t> rays{0};
  const std::size_t share_end = std::min(r.order_end, r.order->size()), share_begin = std::min(r.order_begin, share_end);
  const double progress_scale =
      static_cast<double>(r.order->size()) / static_cast<double>(std::max<std::size_t>(1, share_end - share_begin));
  parallel_for(share_end - share_begin, kVerticesPerChunk, r.threads, [&](std::size_t chunk_begin, std::size_t chunk_end) {
    RayBatch batch(std::max<std::size_t>(1, std::min<std::size_t>(samples, kDefaultBatchCapacity)));
    auto worker = make_worker();
    const std::size_t begin = share_begin + chunk_begin, end = share_begin + chunk_end;
    assert(end - begin <= kVerticesPerChunk);  // parallel_for: chunks of at most the grain
    // The chunk's spawn points first (at most kVerticesPerChunk): point queries in a row, in Morton
    // order, find the BVH nodes they share in the cache; between two vertices' rays they miss it.
    SpawnPoint spawns[kVerticesPerChunk];
    glm::vec3 origins[mesh::kMaxFootprintPoints];
    std::uint32_t triangles[mesh::kMaxFootprintPoints];
    TrueSurface rules[mesh::kMaxFootprintPoints];
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t v = (*r.order)[k];
      spawns[k - begin] = r.scene->spawn_point(positions[v], normals[v]);
    }
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t v = (*r.order)[k];
      const glm::mat3 frame = r.unturned_frames ? sh::turned_frame(normals[v], 0.0) : sh::vertex_frame(normals[v], r.seed, v);
      const SpawnPoint& spawn = spawns[k - begin];
      rules[0] = TrueSurface{};
      const bool spread = v >= first_spread;
      if (spread) {
        footprint_origins(*r.footprints, *r.scene, static_cast<std::uint32_t>(v - first_spread), normals[v], r.seed, origin_count,
                          origins, triangles);
        for (std::size_t o = 0; o < origin_count; ++o) rules[o] = true_surface(*r.mesh, triangles[o]);
      } else if (r.geometric_normals) {
        rules[0].geometric_normal = glm::dvec3((*r.geometric_normals)[v]);
      }
      const bool ruled = spread || rules[0].geometric_normal != glm::dvec3(0.0);
      const glm::vec3* local = r.directions->data() + (r.direction_set ? (*r.direction_set)[v] * samples : 0);
      worker.start(v, frame);
      for (std::size_t first = 0; first < samples; first += batch.capacity()) {
        const std::size_t count = std::min(batch.capacity(), samples - first);
        batch.clear();
        batch.set_robust(spawn.robust || closest_robust);
        for (std::size_t s = first; s < first + count; ++s)
          batch.push(spread ? origins[s * origin_count / samples] : spawn.origin, frame * local[s]);
        if (r.query == Query::occluded) r.scene->occluded(batch);
        else r.scene->intersect(batch);
        if (ruled) apply_true_surface(batch, rules, spread ? origin_count : 1, first, samples);
        worker.batch(v, batch, first);
      }
      worker.finish(v, frame);
    }
    rays += static_cast<std::uint64_t>(end - begin) * samples;
    progress.advance(static_cast<std::size_t>(static_cast<double>(end - begin) * progress_scale + 0.5));
  });
  progress.finish();
  return rays.load();
}

}  // namespace prt::trace
