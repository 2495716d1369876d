#include "trace/scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <mutex>
#include <numeric>
#include <string>

#include "core/error.h"
#include "core/parallel.h"
#include "trace/hit_refine.h"

namespace prt::trace {

// The batch storage is handed to Embree as RTCRay / RTCRayHit arrays: the layouts must match exactly.
static_assert(sizeof(Ray) == sizeof(RTCRay) && alignof(Ray) == alignof(RTCRay));
static_assert(offsetof(Ray, org_x) == offsetof(RTCRay, org_x) && offsetof(Ray, tnear) == offsetof(RTCRay, tnear));
static_assert(offsetof(Ray, dir_x) == offsetof(RTCRay, dir_x) && offsetof(Ray, time) == offsetof(RTCRay, time));
static_assert(offsetof(Ray, tfar) == offsetof(RTCRay, tfar) && offsetof(Ray, mask) == offsetof(RTCRay, mask));
static_assert(offsetof(Ray, id) == offsetof(RTCRay, id) && offsetof(Ray, flags) == offsetof(RTCRay, flags));
static_assert(sizeof(Hit) == sizeof(RTCHit) && alignof(Hit) == alignof(RTCHit));
static_assert(offsetof(Hit, ng_x) == offsetof(RTCHit, Ng_x) && offsetof(Hit, u) == offsetof(RTCHit, u));
static_assert(offsetof(Hit, v) == offsetof(RTCHit, v) && offsetof(Hit, prim_id) == offsetof(RTCHit, primID));
static_assert(offsetof(Hit, geom_id) == offsetof(RTCHit, geomID) && offsetof(Hit, inst_id) == offsetof(RTCHit, instID));
static_assert(RTC_MAX_INSTANCE_LEVEL_COUNT == 1);
static_assert(sizeof(RayHit) == sizeof(RTCRayHit) && offsetof(RayHit, hit) == offsetof(RTCRayHit, hit));
static_assert(kNoHit == RTC_INVALID_GEOMETRY_ID);

// Named, not anonymous: Scene::Impl holds them.
namespace detail {

// Bytes Embree holds, tracked by the device's memory monitor (called from Embree's build threads).
struct MemoryCounter {
  std::atomic<std::int64_t> now{0};
  std::atomic<std::int64_t> peak{0};
};

// Message of the device's first error, recorded by Embree's error callback.
struct ErrorLog {
  std::mutex mutex;
  std::string message;
};

}  // namespace detail

namespace {

const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_UNKNOWN:
      return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
  }
  return "error";
}


bool monitor_memory(void* user, ssize_t bytes, bool post) {
  auto* counter = static_cast<detail::MemoryCounter*>(user);
  // Allocations are reported before they happen (post == false) and frees after; count both once.
  std::int64_t now = counter->now.fetch_add(bytes) + bytes;
  std::int64_t peak = counter->peak.load();
  while (now > peak && !counter->peak.compare_exchange_weak(peak, now)) {
  }
  return true;
}


void record_error(void* user, RTCError code, const char* text) {
  auto* log = static_cast<detail::ErrorLog*>(user);
  std::lock_guard<std::mutex> lock(log->mutex);
  if (log->message.empty())
    log->message = std::string(error_name(code)) + (text && *text ? std::string(": ") + text : "");
}

}  // namespace

struct Scene::Impl {
  detail::ErrorLog errors;
  detail::MemoryCounter memory;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<float> padded_positions;  // x,y,z per vertex + 1 float of padding; empty when shared
  SceneStats stats;
  BatchCall batch_call = BatchCall::stream;
  const std::vector<glm::vec3>* positions = nullptr;  // the mesh's, for the contact query
  const std::vector<std::uint32_t>* indices = nullptr;

  const void* vertex_data = nullptr;  // the mesh's positions or padded_positions
  bool robust = true;                  // of `scene`
  std::once_flag robust_once;          // builds robust_scene (scenes without robust mode)
  RTCScene robust_scene = nullptr;

  ~Impl() {
    if (robust_scene) rtcReleaseScene(robust_scene);
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  // A committed scene of the mesh (MEDIUM quality, deterministic), with or without robust mode.
  RTCScene new_scene(bool robust_mode) {
    RTCScene s = rtcNewScene(device);
    check("scene creation");
    rtcSetSceneFlags(s, robust_mode ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_MEDIUM);
    const std::size_t triangles = indices->size() / 3;
    if (triangles > 0) {
      RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
      check("geometry creation");
      static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
      // Embree loads the last vertex with a 16-byte read: vertex_data has 4 bytes of slack after it.
      rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertex_data, 0, sizeof(glm::vec3),
                                 positions->size());
      rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices->data(), 0,
                                 3 * sizeof(std::uint32_t), triangles);
      rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_MEDIUM);
      rtcCommitGeometry(geometry);
      rtcAttachGeometryByID(s, geometry, 0);
      rtcReleaseGeometry(geometry);
      check("geometry setup");
    }
    {
      ScopedFlushDenormals ftz;
      rtcCommitScene(s);
    }
    check("BVH build");
    return s;
  }

  // The scene with robust mode: `scene` itself, or a second one built on first use.
  RTCScene robust_for_contacts() {
    if (robust) return scene;
    std::call_once(robust_once, [this] { robust_scene = new_scene(true); });
    return robust_scene;
  }

  // Throws prt::Error if Embree reported an error since the last check.
  void check(const char* step) {
    RTCError code = device ? rtcGetDeviceError(device) : rtcGetDeviceError(nullptr);
    if (code == RTC_ERROR_NONE) return;
    std::string message;
    {
      std::lock_guard<std::mutex> lock(errors.mutex);
      message = errors.message.empty() ? error_name(code) : errors.message;
    }
    fail(std::string("trace: Embree ") + step + " failed: " + message);
  }
};

RayBatch::RayBatch(std::size_t capacity) : rays_(std::max<std::size_t>(capacity, 1)) {}

std::size_t RayBatch::occluded_count() const {
  std::size_t count = 0;
  for (std::size_t i = 0; i < size_; ++i) count += is_occluded(i) ? 1 : 0;
  return count;
}

std::size_t RayBatch::hit_count(const void* rows, std::size_t row_bytes) const {
  std::size_t count = 0;
  const char* base = static_cast<const char*>(rows);
  for (std::size_t i = 0; i < size_; ++i) {
    const Hit& h = rays_[i].hit;
    if (h.geom_id == kNoHit) continue;
    ++count;
    if (base) {
      const char* row = base + static_cast<std::size_t>(h.prim_id) * row_bytes;
      for (std::size_t offset = 0; offset < row_bytes; offset += 64) __builtin_prefetch(row + offset);
      __builtin_prefetch(row + row_bytes - 1);  // a row may straddle one more cache line
    }
  }
  return count;
}

HitResult RayBatch::hit(std::size_t i) const {
  const RayHit& r = rays_[i];
  HitResult result;
  if (r.hit.geom_id == kNoHit) return result;
  result.prim_id = r.hit.prim_id;
  result.t = r.ray.tfar;
  result.u = r.hit.u;
  result.v = r.hit.v;
  result.ng = glm::vec3(r.hit.ng_x, r.hit.ng_y, r.hit.ng_z);
  return result;
}

float ray_offset_for(const std::vector<glm::vec3>& positions) {
  float max_abs = 0.0f;
  for (const glm::vec3& p : positions) max_abs = std::max({max_abs, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  return std::ldexp(max_abs, -18);
}

Scene::Scene(const mesh::Mesh& mesh, const SceneOptions& options) : impl_(std::make_unique<Impl>()) {
  const auto& positions = mesh.positions;
  const auto& indices = mesh.indices;
  if (indices.size() % 3 != 0) fail("trace: index count " + std::to_string(indices.size()) + " is not a multiple of 3");
  for (std::size_t i = 0; i < indices.size(); ++i)
    if (indices[i] >= positions.size())
      fail("trace: triangle " + std::to_string(i / 3) + " refers to vertex " + std::to_string(indices[i]) + " of " +
           std::to_string(positions.size()));
  for (std::size_t i = 0; i < positions.size(); ++i)
    if (!std::isfinite(positions[i].x) || !std::isfinite(positions[i].y) || !std::isfinite(positions[i].z))
      fail("trace: vertex " + std::to_string(i) + " has a non-finite position");
  if (positions.size() > 0xFFFFFFFFu) fail("trace: more than 2^32 vertices");

  triangle_count_ = indices.size() / 3;
  ray_offset_ = ray_offset_for(positions);
  contact_rule_ = !options.robust && options.contact_rule;
  if (!positions.empty()) {
    lo_ = hi_ = positions[0];
    for (const glm::vec3& p : positions) {
      lo_ = glm::min(lo_, p);
      hi_ = glm::max(hi_, p);
    }
  }

  Impl& im = *impl_;
  im.batch_call = options.batch_call;
  im.positions = &positions;
  im.indices = &indices;
  std::string config = "threads=" + std::to_string(std::max(options.build_threads, 0));
  if (!options.device_config.empty()) config += "," + options.device_config;
  im.device = rtcNewDevice(config.c_str());
  if (!im.device) im.check("device creation");
  rtcSetDeviceErrorFunction(im.device, record_error, &im.errors);
  rtcSetDeviceMemoryMonitorFunction(im.device, monitor_memory, &im.memory);

  im.stats.shares_positions = triangle_count_ > 0 && positions.capacity() > positions.size();
  im.vertex_data = positions.data();
  if (!im.stats.shares_positions && triangle_count_ > 0) {
    im.padded_positions.assign(3 * positions.size() + 1, 0.0f);
    std::memcpy(im.padded_positions.data(), positions.data(), positions.size() * sizeof(glm::vec3));
    im.vertex_data = im.padded_positions.data();
  }
  im.stats.geometry_bytes = im.padded_positions.size() * sizeof(float);
  im.robust = options.robust;
  const auto start = std::chrono::steady_clock::now();
  im.scene = im.new_scene(options.robust);
  im.stats.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  im.check("BVH build");
  im.stats.embree_bytes = static_cast<std::size_t>(std::max<std::int64_t>(im.memory.now.load(), 0));
  im.stats.embree_peak_bytes = static_cast<std::size_t>(std::max<std::int64_t>(im.memory.peak.load(), 0));
}

Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

const SceneStats& Scene::stats() const { return impl_->stats; }

void Scene::occluded(RayBatch& batch) const {
  if (batch.empty()) return;
  ScopedFlushDenormals ftz;
  RTCScene target = batch.robust() ? impl_->robust_for_contacts() : impl_->scene;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  // A contact point's batch (robust mode in a scene without it) goes ray by ray: rtcOccluded1M is up to
  // 280x slower for rays whose origin lies in a surface (scene.h, BATCH SIZE AND CALLS); same answers.
  const bool contact = batch.robust() && !impl_->robust;
  if (impl_->batch_call == BatchCall::stream && !contact) {
    rtcOccluded1M(target, &context, reinterpret_cast<RTCRay*>(batch.data()), static_cast<unsigned>(batch.size()),
                  sizeof(RayHit));
  } else {
    for (std::size_t i = 0; i < batch.size(); ++i)
      rtcOccluded1(target, &context, reinterpret_cast<RTCRay*>(&batch.data()[i].ray));
  }
}

void Scene::intersect(RayBatch& batch) const {
  if (batch.empty()) return;
  ScopedFlushDenormals ftz;
  RTCScene target = batch.robust() ? impl_->robust_for_contacts() : impl_->scene;
  RayHit* rays = batch.data();
  for (std::size_t i = 0; i < batch.size(); ++i) {
    rays[i].hit.geom_id = kNoHit;
    rays[i].hit.prim_id = kNoHit;
    rays[i].hit.inst_id = kNoHit;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  if (impl_->batch_call == BatchCall::stream) {
    rtcIntersect1M(target, &context, reinterpret_cast<RTCRayHit*>(rays), static_cast<unsigned>(batch.size()),
                   sizeof(RayHit));
  } else {
    for (std::size_t i = 0; i < batch.size(); ++i)
      rtcIntersect1(target, &context, reinterpret_cast<RTCRayHit*>(&rays[i]));
  }
  refine_hits(rays, batch.size(), *impl_->positions, *impl_->indices);
}

namespace {

// Distance from q to triangle (a, b, c) in double: to the plane where q projects inside the triangle,
// else to the nearest edge. A degenerate triangle is measured by its edges.
double distance_to_segment(const glm::dvec3& q, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(glm::dot(q - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(q - (a + t * ab));
}

double distance_to_triangle(const glm::dvec3& q, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 normal = glm::cross(b - a, c - a);
  const double area2 = glm::dot(normal, normal);
  if (area2 > 0.0) {
    // Signed sub-areas: q's projection is inside iff all three have the normal's orientation.
    const bool inside = glm::dot(glm::cross(b - a, q - a), normal) >= 0.0 && glm::dot(glm::cross(c - b, q - b), normal) >= 0.0 &&
                        glm::dot(glm::cross(a - c, q - c), normal) >= 0.0;
    if (inside) return std::fabs(glm::dot(q - a, normal)) / std::sqrt(area2);
  }
  return std::min({distance_to_segment(q, a, b), distance_to_segment(q, b, c), distance_to_segment(q, c, a)});
}

// What the contact query's callback needs.
struct ContactQuery {
  const std::vector<glm::vec3>* positions;
  const std::vector<std::uint32_t>* indices;
  glm::dvec3 origin;    // the lifted origin
  double distance;      // contact_distance()
  bool touches = false;
};

bool contact_callback(RTCPointQueryFunctionArguments* args) {
  auto* q = static_cast<ContactQuery*>(args->userPtr);
  const std::uint32_t* tri = q->indices->data() + 3 * static_cast<std::size_t>(args->primID);
  const glm::vec3 &a = (*q->positions)[tri[0]], &b = (*q->positions)[tri[1]], &c = (*q->positions)[tri[2]];
  if (distance_to_triangle(q->origin, glm::dvec3(a), glm::dvec3(b), glm::dvec3(c)) > q->distance) return false;
  q->touches = true;
  args->query->radius = 0.0f;  // found: nothing more to visit
  return true;
}

}  // namespace

bool Scene::origin_touches_surface(const glm::vec3& p, const glm::vec3& n) const {
  if (triangle_count_ == 0) return false;
  const glm::vec3 o = offset_origin(p, n);
  ContactQuery query{impl_->positions, impl_->indices, glm::dvec3(o), static_cast<double>(contact_distance())};
  RTCPointQuery point;
  point.x = o.x;
  point.y = o.y;
  point.z = o.z;
  point.time = 0.0f;
  point.radius = contact_distance();
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(impl_->scene, &point, &context, contact_callback, &query);
  return query.touches;
}

SpawnPoint Scene::spawn_point(const glm::vec3& p, const glm::vec3& n) const {
  SpawnPoint s;
  s.origin = offset_origin(p, n);
  s.robust = contact_rule_ && origin_touches_surface(p, n);
  return s;
}

// Spreads the low 10 bits of v to every third bit.
static std::uint32_t spread_bits_10(std::uint32_t v) {
  v &= 0x3FFu;
  v = (v | (v << 16)) & 0x030000FFu;
  v = (v | (v << 8)) & 0x0300F00Fu;
  v = (v | (v << 4)) & 0x030C30C3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

std::uint32_t morton_code(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi) {
  std::uint32_t q[3];
  for (int a = 0; a < 3; ++a) {
    const float extent = hi[a] - lo[a];
    const float unit = extent > 0.0f ? (p[a] - lo[a]) / extent : 0.0f;
    const float scaled = std::clamp(unit, 0.0f, 1.0f) * 1024.0f;  // a NaN stays NaN and maps to 0 below
    q[a] = scaled >= 1023.0f ? 1023u : (scaled > 0.0f ? static_cast<std::uint32_t>(scaled) : 0u);
  }
  return (spread_bits_10(q[0]) << 2) | (spread_bits_10(q[1]) << 1) | spread_bits_10(q[2]);
}

std::vector<std::uint32_t> morton_order(const std::vector<glm::vec3>& positions) {
  std::vector<std::uint32_t> order(positions.size());
  std::iota(order.begin(), order.end(), 0u);
  if (positions.empty()) return order;
  glm::vec3 lo = positions[0], hi = positions[0];
  for (const glm::vec3& p : positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  // Sort (code, index) pairs: equal codes keep index order, the sort is stable by construction.
  std::vector<std::uint64_t> keyed(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i)
    keyed[i] = (std::uint64_t(morton_code(positions[i], lo, hi)) << 32) | i;
  std::sort(keyed.begin(), keyed.end());
  for (std::size_t i = 0; i < keyed.size(); ++i) order[i] = static_cast<std::uint32_t>(keyed[i]);
  return order;
}

}  // namespace prt::trace
