#pragma once
// Ray queries on a triangle mesh: occlusion ("does anything lie on this segment?") and closest hit
// (which triangle, where, how far), in batches, on Embree 3. This is the only module that includes
// Embree; its types stay in scene.cpp.
//
// HOW TO TRACE (the baker's loop):
//   Scene scene(mesh, options);                         // BVH build, once
//   parallel_for(order.size(), 64, threads, [&](size_t begin, size_t end) {
//     RayBatch batch;                                   // 256 rays, one per chunk, reused: no per-ray allocation
//     for vertex i in order[begin, end):
//       SpawnPoint s = scene.spawn_point(positions[i], normals[i]);   // origin, robust (ROBUST MODE)
//       for each group of 256 directions d:
//         batch.clear(); batch.set_robust(s.robust);
//         for each d: batch.push(s.origin, d);          // tnear 0, tfar infinity
//         scene.occluded(batch);                        // rtcOccluded1M, INCOHERENT
//         ... batch.is_occluded(k) ...
//   });
// `occluded` and `intersect` are const and may run concurrently from any number of threads, each with
// its own batch. They set flush-to-zero / denormals-are-zero for the duration of the call.
//
// RAY OFFSET. A ray that starts on the surface at p with unit vertex normal n (pointing to the side the
// rays leave from) starts at origin = p + n eps, eps = Scene::ray_offset() = 2^-18 M, with tnear = 0,
// where M is the largest |coordinate| of any vertex (32..64 float ulps of M): large enough to clear float
// rounding, small enough that rays leaving concave creases do not escape. The derivation and the leak and
// self-hit figures behind it: docs/conventions.md, "Ray offset" (tests/trace/test_offset.cpp).
//
// ROBUST MODE (RTC_SCENE_FLAG_ROBUST: watertight tests, hits at exactly t = tnear count). A scene built
// without it (SceneOptions::robust = false, the bakes' choice) still traces robust the rays of points whose
// lifted origin lies on another surface (a block standing on a floor, an unwelded concave edge):
//   spawn_point(p, n): origin o = p + n eps; robust iff o lies within eps/16 of any triangle (an Embree
//   point query of radius eps/16, exact point-triangle distance in double);
//   RayBatch::set_robust(true) then sends the point's batches to a second, robust BVH of the same mesh,
//   built on first use (never for a mesh without such points; BATCH SIZE AND CALLS).
// The per-vertex loop (vertex_rays.h) traces every closest-hit query robust; the interreflected bakes
// replace their scene by a robust one before the first bounce pass (bake/passes.h, use_robust_scene).
// Why, with the measurements: docs/conventions.md, "Robust mode (contact rule)".
//
// DETERMINISM. For a fixed mesh, rays and options, every result (occluded flags, prim_id, t, u, v) is
// bit-identical across runs, thread counts, the order in which batches are traced and
// SceneOptions::build_threads (tests/trace/test_determinism.cpp): Embree 3's MEDIUM-quality builder, used
// here, is deterministic for any thread count (the HIGH-quality spatial-split builder is not).
//
// BATCH SIZE AND CALLS. A batch is one rtcOccluded1M / rtcIntersect1M call of up to kDefaultBatchCapacity
// = 256 rays, traced INCOHERENT. Contact batches (RayBatch::set_robust in a scene built without robust
// mode) are traced one rtcOccluded1 per ray: in robust mode rtcOccluded1M is pathologically slow on rays
// that start in a surface (up to 280x). The measurements behind both: docs/performance.md, "Ray batches".
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace prt::trace {

/// +infinity, the tfar of a ray without an end.
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();
/// prim_id of a ray that hit nothing (Embree's RTC_INVALID_GEOMETRY_ID).
inline constexpr std::uint32_t kNoHit = 0xFFFFFFFFu;
/// Rays per RayBatch unless a capacity is given (see BATCH SIZE AND CALLS).
inline constexpr std::size_t kDefaultBatchCapacity = 256;

/// Where and how the rays leaving one surface point are traced (Scene::spawn_point).
struct SpawnPoint {
  glm::vec3 origin{0.0f};  ///< p + n * Scene::ray_offset(); tnear = 0
  bool robust = false;     ///< trace this point's batches with RayBatch::set_robust(true) (p touches another surface)
};

/// One ray, laid out exactly as Embree's RTCRay (48 bytes, 16-byte aligned; checked in scene.cpp).
/// The ray is the segment origin + t * dir, t in [tnear, tfar]; dir need not be unit length (t is then
/// in units of |dir|).
struct alignas(16) Ray {
  float org_x, org_y, org_z, tnear;
  float dir_x, dir_y, dir_z, time;  ///< time: motion blur time, always 0 here
  float tfar;                       ///< after Scene::occluded: -infinity if occluded
  std::uint32_t mask, id, flags;    ///< mask: all bits; id: the ray's index; flags: 0
};

/// One hit record, laid out exactly as Embree's RTCHit (32 bytes).
struct alignas(16) Hit {
  float ng_x, ng_y, ng_z;  ///< geometric normal: towards the front (counter-clockwise) side, |ng| = 2 area
  float u, v;              ///< barycentrics: point = (1-u-v) p0 + u p1 + v p2 of the triangle's indices
  std::uint32_t prim_id;   ///< triangle index (indices[3 prim_id ..]), kNoHit if nothing was hit
  std::uint32_t geom_id;   ///< 0 if hit, kNoHit if not
  std::uint32_t inst_id;   ///< always kNoHit (no instancing)
};

/// Embree's RTCRayHit (80 bytes): a ray followed by its hit record.
struct alignas(16) RayHit {
  Ray ray;
  Hit hit;
};

/// Closest-hit result of one ray.
struct HitResult {
  std::uint32_t prim_id = kNoHit;  ///< triangle index or kNoHit
  float t = kInfinity;             ///< distance along the ray in units of |dir|; kInfinity if no hit
  float u = 0.0f, v = 0.0f;        ///< barycentrics of the hit point (see Hit)
  glm::vec3 ng{0.0f};              ///< geometric normal of the hit triangle (see Hit), unnormalised
  bool hit() const { return prim_id != kNoHit; }
};

/// A reusable, fixed-capacity array of rays whose storage is handed to Embree as is. Keep one per
/// worker (or per parallel_for chunk) and refill it for every query: a query overwrites tfar and the hit
/// records. Not thread-safe; cheap to construct (one allocation of 80 bytes per ray of capacity).
class RayBatch {
 public:
  /// Capacity in rays, >= 1.
  explicit RayBatch(std::size_t capacity = kDefaultBatchCapacity);

  std::size_t capacity() const { return rays_.size(); }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == rays_.size(); }
  /// Forgets all rays (capacity is kept); the robust flag stays.
  void clear() { size_ = 0; }
  /// Whether Scene::occluded / intersect trace this batch with RTC_SCENE_FLAG_ROBUST even in a scene built
  /// without it (SpawnPoint::robust; a scene built with it always uses it). Default false.
  void set_robust(bool robust) { robust_ = robust; }
  bool robust() const { return robust_; }

  /// Appends the ray origin + t dir, t in [tnear, tfar] (0 <= tnear <= tfar, tfar may be kInfinity) and
  /// returns its index. Precondition: !full() (checked with assert only: this is the hot loop).
  std::size_t push(const glm::vec3& origin, const glm::vec3& dir, float tnear = 0.0f, float tfar = kInfinity);

  /// After Scene::occluded: whether ray i met any triangle within [tnear, tfar].
  bool is_occluded(std::size_t i) const { return !(rays_[i].ray.tfar >= 0.0f); }
  /// After Scene::occluded: how many of the size() rays were occluded.
  std::size_t occluded_count() const;
  /// After Scene::intersect: the closest hit of ray i.
  HitResult hit(std::size_t i) const;
  /// After Scene::intersect: whether ray i hit anything (hit(i).hit() without building the result).
  bool is_hit(std::size_t i) const { return rays_[i].hit.geom_id != kNoHit; }
  /// After Scene::intersect: whether ray i's closest hit is a FRONT face: the ray runs against the
  /// geometric normal, which points to the side from which the corners run counter-clockwise (the side
  /// of (p1 - p0) x (p2 - p0)). False for a miss.
  bool is_front_hit(std::size_t i) const {
    const RayHit& r = rays_[i];
    return r.hit.geom_id != kNoHit && r.hit.ng_x * r.ray.dir_x + r.hit.ng_y * r.ray.dir_y + r.hit.ng_z * r.ray.dir_z < 0.0f;
  }
  /// The direction ray i was pushed with.
  glm::vec3 direction(std::size_t i) const { return glm::vec3(rays_[i].ray.dir_x, rays_[i].ray.dir_y, rays_[i].ray.dir_z); }

  /// After a query: ray i carries no light (the true-surface rule, trace/true_surface.h): from now on
  /// is_occluded(i) is true and is_hit(i), is_front_hit(i), hit(i).hit() are false.
  void block(std::size_t i) {
    rays_[i].ray.tfar = -kInfinity;
    rays_[i].hit.geom_id = kNoHit;
    rays_[i].hit.prim_id = kNoHit;
  }

  /// After Scene::intersect: the number of the size() rays that hit a triangle; with `rows` given, also
  /// prefetches rows + prim_id * `row_bytes` (every 64-byte cache line it touches) of every hit triangle into the
  /// cache, for callers that next read per-triangle data in hit order (random reads otherwise).
  std::size_t hit_count(const void* rows = nullptr, std::size_t row_bytes = 0) const;

  /// Raw Embree-layout records [0, size()) (for Scene and for callers that fill rays themselves).
  RayHit* data() { return rays_.data(); }
  const RayHit* data() const { return rays_.data(); }

 private:
  std::vector<RayHit> rays_;  // capacity() records, all 16-byte aligned
  std::size_t size_ = 0;
  bool robust_ = false;
};

inline std::size_t RayBatch::push(const glm::vec3& origin, const glm::vec3& dir, float tnear, float tfar) {
  assert(size_ < rays_.size());
  RayHit& r = rays_[size_];
  r.ray = Ray{origin.x,
              origin.y,
              origin.z,
              tnear,
              dir.x,
              dir.y,
              dir.z,
              0.0f,
              tfar,
              0xFFFFFFFFu,
              static_cast<std::uint32_t>(size_),
              0u};
  return size_++;
}

/// How Scene::occluded / intersect hand a batch to Embree.
enum class BatchCall {
  stream,  ///< one rtcOccluded1M / rtcIntersect1M call per batch (INCOHERENT): the fastest, the default
  single,  ///< a loop of rtcOccluded1 / rtcIntersect1 over the batch (kept to measure the difference)
};

/// How a Scene is built.
struct SceneOptions {
  /// Threads for the BVH build (Embree device "threads="); 0 = all hardware threads. Queries run on the
  /// calling threads whatever this is.
  int build_threads = 0;
  /// RTC_SCENE_FLAG_ROBUST: watertight triangle tests that also count hits at exactly t = tnear, 1.2-1.35x
  /// the cost of a ray. Where a vertex lies exactly on another surface (a block standing on a floor,
  /// both at y = 0), its rays into that surface start exactly in its plane and hit it at t = 0; without
  /// the flag Embree misses them (Cornell box: 4.8% of all vertex rays, leak under the blocks). On by
  /// default (callers that trace from their own origins); off in the bakes, which trace through
  /// spawn_point and RayBatch::set_robust: the contact rule (ROBUST MODE above) keeps robust mode's
  /// answers for the points that need it.
  bool robust = true;
  /// How batches are traced (see BatchCall); the results are bit-identical either way (tested).
  BatchCall batch_call = BatchCall::stream;
  /// In a scene without robust mode: whether Scene::spawn_point sends the rays of points that touch
  /// another surface through robust mode (a second BVH, built on first use; ROBUST MODE at the top of
  /// this header). Off only to measure what the rule buys (tests/trace/test_robust.cpp).
  bool contact_rule = true;
  /// More Embree device configuration, appended to "threads=N," as is (e.g. "isa=sse4.2" pins the code
  /// path Embree would otherwise pick for the CPU; the tests compare paths with it). Empty: none.
  std::string device_config = {};
};

/// What building the scene measured.
struct SceneStats {
  double build_seconds = 0.0;         ///< wall time of the BVH build (rtcCommitScene)
  std::size_t embree_bytes = 0;       ///< bytes Embree holds now (BVH + its own buffers)
  std::size_t embree_peak_bytes = 0;  ///< most bytes Embree held at once (during the build)
  std::size_t geometry_bytes = 0;     ///< bytes of vertex/index data held by the Scene itself
  bool shares_positions = false;      ///< vertex buffer is the Mesh's own storage (no copy)
};

/// An Embree device and a scene with one static triangle geometry built from a mesh.
///
/// Buffers: the index buffer is always the mesh's own `indices` storage; the vertex buffer is the mesh's
/// `positions` storage when its capacity exceeds its size (Embree reads 16 bytes at the last vertex, so
/// 4 bytes of slack must follow it; `positions.reserve(size + 1)` guarantees that), else a padded copy.
/// Therefore the Mesh must outlive the Scene and its positions/indices must not change or reallocate
/// while the Scene exists.
class Scene {
 public:
  /// Builds the BVH. Throws prt::Error("trace: <problem>") for: index count not a multiple of 3, an
  /// index >= positions.size(), a non-finite position, or any Embree error (its message included).
  /// A mesh without triangles gives a scene where every ray misses.
  explicit Scene(const mesh::Mesh& mesh, const SceneOptions& options = {});
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;
  Scene(Scene&&) noexcept;
  Scene& operator=(Scene&&) noexcept;

  /// Any-hit query for batch rays [0, size()) with one rtcOccluded1M call (INCOHERENT; see BatchCall; a
  /// contact batch, robust in a scene without robust mode: one rtcOccluded1 per ray, BATCH SIZE AND
  /// CALLS): afterwards batch.is_occluded(i) tells whether ray i meets a triangle (either side) within
  /// [tnear, tfar].
  void occluded(RayBatch& batch) const;

  /// Closest-hit query for batch rays [0, size()) with one rtcIntersect1M call (INCOHERENT; see
  /// BatchCall): afterwards batch.hit(i) gives the nearest triangle in [tnear, tfar] (either side), its
  /// distance, barycentrics and normal recomputed in double from the triangle (trace/hit_refine.h: the
  /// same bits whatever ISA Embree runs).
  void intersect(RayBatch& batch) const;

  /// eps of the ray offset rule (see the top of this header), in mesh units.
  float ray_offset() const { return ray_offset_; }
  /// p + n * ray_offset(): where a ray leaving the surface point p with unit normal n starts.
  glm::vec3 offset_origin(const glm::vec3& p, const glm::vec3& n) const { return p + n * ray_offset_; }
  /// Where the rays leaving surface point p (unit normal n) start, and whether they need robust mode:
  /// true only in a scene built without it (SceneOptions::contact_rule) where p touches another surface
  /// (ROBUST MODE at the top of this header). Costs one Embree point query in such a scene (about a
  /// microsecond); call it once per point, not per ray.
  SpawnPoint spawn_point(const glm::vec3& p, const glm::vec3& n) const;
  /// Whether the lifted origin offset_origin(p, n) lies within contact_distance() of a triangle (exact
  /// point-triangle distance in double): another surface touches p (a block standing on a floor, the
  /// neighbouring face at an unwelded concave edge), or p's own faces meet n at grazing angles
  /// (n.n_f < 1/16).
  bool origin_touches_surface(const glm::vec3& p, const glm::vec3& n) const;
  /// ray_offset() / 16 (2-4 float ulps of M): how close a lifted origin must come to another surface to
  /// touch it.
  float contact_distance() const { return std::ldexp(ray_offset_, -4); }

  /// Bounding box of the mesh's referenced and unreferenced vertices (zero box for an empty mesh).
  glm::vec3 bounds_lo() const { return lo_; }
  glm::vec3 bounds_hi() const { return hi_; }
  std::size_t triangle_count() const { return triangle_count_; }
  const SceneStats& stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  float ray_offset_ = 0.0f;
  bool contact_rule_ = false;
  glm::vec3 lo_{0.0f}, hi_{0.0f};
  std::size_t triangle_count_ = 0;
};

/// eps of the ray offset rule for vertices `positions`: 2^-18 * the largest |coordinate| of any vertex (0
/// for no vertices). Scene::ray_offset() is this value for the mesh's positions.
float ray_offset_for(const std::vector<glm::vec3>& positions);

/// A permutation of [0, positions.size()) visiting the vertices in Morton (Z-curve) order: each
/// coordinate is quantised to 10 bits over the bounding box, the 30-bit interleaved codes are sorted
/// stably (equal codes keep index order). Deterministic. Tracing vertices in this order keeps
/// consecutive vertices' rays in the same BVH nodes: 1.25x faster than file order on the Stanford
/// dragon (measured once, bench_trace), 1.05-1.15x on the bench blob, whose subdivision order is already coherent.
std::vector<std::uint32_t> morton_order(const std::vector<glm::vec3>& positions);

/// The 30-bit Morton code of p quantised over [lo, hi] (10 bits per axis, x in the highest bit of each
/// triple). Points outside the box are clamped to it.
std::uint32_t morton_code(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi);

}  // namespace prt::trace
