#include "probes/surface.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "bake/vertex_samples.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "light/environment.h"
#include "light/projection.h"
#include "sh/basis.h"
#include "sh/sampling.h"
#include "sh/zonal.h"
#include "trace/scene.h"

namespace prt::probes {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kControlVariateBands = 5;

std::uint64_t mix64(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  x ^= x >> 31;
  return x;
}

struct Context {
  const trace::Scene* scene;
  const mesh::Mesh* mesh;
  const std::vector<glm::vec3>* albedo;
  const std::vector<glm::vec3>* local_directions;
  std::vector<std::uint32_t> order;
  std::uint32_t seed;
  int threads;
  bool progress;
};

// Front-face test and barycentric interpolation of per-vertex values at a closest hit.
bool front_hit(const mesh::Mesh& mesh, const trace::HitResult& hit, const glm::vec3& dir, std::uint32_t* tri_out) {
  const std::uint32_t* tri = mesh.indices.data() + 3 * static_cast<std::size_t>(hit.prim_id);
  const glm::vec3& p0 = mesh.positions[tri[0]];
  const glm::vec3 face_normal = glm::cross(mesh.positions[tri[1]] - p0, mesh.positions[tri[2]] - p0);
  for (int k = 0; k < 3; ++k) tri_out[k] = tri[k];
  return glm::dot(face_normal, dir) < 0.0f;
}

// One traversal of every vertex's S rays; `visit(v, frame, batch, count, first)` consumes each batch.
template <class Visit>
std::uint64_t for_each_vertex_rays(const Context& ctx, const char* label, Visit visit) {
  const mesh::Mesh& mesh = *ctx.mesh;
  const std::size_t samples = ctx.local_directions->size();
  Progress progress(label, "vertices", std::max<std::size_t>(1, mesh.positions.size()), ctx.progress);
  std::atomic<std::uint64_t> rays{0};
  parallel_for(ctx.order.size(), 64, ctx.threads, [&](std::size_t begin, std::size_t end) {
    trace::RayBatch batch(std::min<std::size_t>(samples, trace::kDefaultBatchCapacity));
    std::uint64_t traced = 0;
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t v = ctx.order[k];
      const glm::mat3 frame = bake::turned_frame(mesh.normals[v], 2.0 * kPi * hash_to_unit(ctx.seed, v, 0x5eedu));
      const glm::vec3 origin = ctx.scene->offset_origin(mesh.positions[v], mesh.normals[v]);
      for (std::size_t first = 0; first < samples; first += batch.capacity()) {
        const std::size_t count = std::min(batch.capacity(), samples - first);
        batch.clear();
        for (std::size_t s = first; s < first + count; ++s) batch.push(origin, frame * (*ctx.local_directions)[s]);
        ctx.scene->intersect(batch);
        traced += count;
        visit(v, batch, count);
      }
    }
    rays += traced;
    progress.advance(end - begin);
  });
  progress.finish();
  return rays.load();
}

}  // namespace

double hash_to_unit(std::uint32_t seed, std::uint64_t index, std::uint32_t salt) {
  const std::uint64_t h = mix64(mix64(index + 0x9e3779b97f4a7c15ull * (seed + 1)) ^ (static_cast<std::uint64_t>(salt) << 32));
  return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0);
}

std::vector<glm::vec3> surface_radiance(const trace::Scene& scene, const mesh::Mesh& mesh,
                                        const std::vector<glm::vec3>& albedo, const SceneLight& light,
                                        const SurfaceOptions& o, std::uint64_t* rays_out) {
  if (o.samples < 1 || o.samples > 65536) fail("--surface-samples " + std::to_string(o.samples) + " is out of range 1..65536");
  if (o.sun_samples < 1 || o.sun_samples > 4096) fail("--sun-samples " + std::to_string(o.sun_samples) + " is out of range 1..4096");
  if (o.bounces < 0 || o.bounces > 64) fail("--bounces " + std::to_string(o.bounces) + " is out of range 0..64");
  const std::size_t vertices = mesh.positions.size();
  const bool has_emission = !light.emission.empty();
  const bool use_environment = o.environment && light.environment != nullptr;

  std::vector<glm::vec3> local;
  for (const glm::dvec3& d : sh::hemisphere_directions_cosine(static_cast<std::size_t>(o.samples), o.seed))
    local.emplace_back(d);
  Context ctx{&scene, &mesh, &albedo, &local, trace::morton_order(mesh.positions), o.seed, o.threads, o.progress};
  const double inv_samples = 1.0 / static_cast<double>(o.samples);
  std::uint64_t rays = 0;

  // Direct reflection D of the environment (with the SH control variate) and the sun.
  std::vector<glm::vec3> direct(vertices, glm::vec3(0.0f));
  if (use_environment) {
    const sh::RgbCoefficients env_sh = light::project(*light.environment, kControlVariateBands, o.threads);
    const light::Environment lookup = lookup_environment(*light.environment);
    const int n = kControlVariateBands * kControlVariateBands;
    std::vector<double> control_variate_share(vertices, 0.0);
    rays += for_each_vertex_rays(ctx, "probes: surface light", [&](std::uint32_t v, const trace::RayBatch& batch, std::size_t count) {
      // Per batch, as the probe baker: with more escaping than blocked rays the control variate
      // (its share of E_sh(n) plus (pi/S) sum [V L_env - L_sh]); with more blocked rays plain Monte
      // Carlo ((pi/S) sum over escaping rays of L_env), which skips the basis evaluations.
      std::size_t hits = 0;
      for (std::size_t i = 0; i < count; ++i) hits += batch.data()[i].hit.geom_id != trace::kNoHit;
      const bool control_variate = 2 * hits <= count;
      if (control_variate) control_variate_share[v] += static_cast<double>(count) * inv_samples;
      glm::dvec3 sum(0.0);
      double basis[kControlVariateBands * kControlVariateBands];
      for (std::size_t i = 0; i < count; ++i) {
        const trace::Ray& r = batch.data()[i].ray;
        const glm::dvec3 w(r.dir_x, r.dir_y, r.dir_z);
        const bool escaped = !batch.hit(i).hit();
        if (escaped) sum += lookup.radiance(w);
        if (control_variate) {
          sh::eval(kControlVariateBands, w, basis);
          for (int k = 0; k < n; ++k) sum -= env_sh.values[k] * basis[k];
        }
      }
      direct[v] += glm::vec3(sum * (kPi * inv_samples));
    });
    parallel_for(vertices, 1024, o.threads, [&](std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) {
        const glm::dvec3 e = glm::dvec3(direct[v]) + control_variate_share[v] * sh::irradiance(env_sh, glm::dvec3(mesh.normals[v]));
        direct[v] = glm::vec3(e * glm::dvec3(albedo[v]) / kPi);
      }
    });
  }
  if (light.sun) {
    const Sun& sun = *light.sun;
    const glm::dvec3 scale = sun.radiance() * (sun.solid_angle() / o.sun_samples);
    std::atomic<std::uint64_t> sun_rays{0};
    parallel_for(vertices, 256, o.threads, [&](std::size_t begin, std::size_t end) {
      trace::RayBatch batch(static_cast<std::size_t>(o.sun_samples));
      std::vector<float> cosines(static_cast<std::size_t>(o.sun_samples));
      std::uint64_t traced = 0;
      for (std::size_t v = begin; v < end; ++v) {
        const glm::vec3 n = mesh.normals[v];
        if (glm::dot(glm::dvec3(n), sun.direction) <= -std::sin(sun.angular_radius)) continue;
        const glm::vec3 origin = scene.offset_origin(mesh.positions[v], n);
        const auto scramble = static_cast<std::uint32_t>(hash_to_unit(o.seed, v, 0x50u) * 4294967296.0);
        batch.clear();
        for (int k = 0; k < o.sun_samples; ++k) {
          const glm::dvec2 u = sh::sobol_2d(static_cast<std::uint32_t>(k), scramble);
          const glm::vec3 w(sun_direction_sample(sun, u.x, u.y));
          cosines[k] = std::max(0.0f, glm::dot(n, w));
          batch.push(origin, w);
        }
        scene.occluded(batch);
        traced += batch.size();
        double sum = 0.0;
        for (int k = 0; k < o.sun_samples; ++k)
          if (!batch.is_occluded(static_cast<std::size_t>(k))) sum += cosines[k];
        direct[v] += glm::vec3(scale * sum * glm::dvec3(albedo[v]) / kPi);
      }
      sun_rays += traced;
    });
    rays += sun_rays.load();
  }

  // R_0 = E_m + D, then K gathers.
  std::vector<glm::vec3> radiance = direct;
  if (has_emission)
    for (std::size_t v = 0; v < vertices; ++v) radiance[v] += light.emission[v];
  for (int bounce = 1; bounce <= o.bounces; ++bounce) {
    std::vector<glm::vec3> next(vertices, glm::vec3(0.0f));
    const std::string label = "probes: surface bounce " + std::to_string(bounce);
    rays += for_each_vertex_rays(ctx, label.c_str(), [&](std::uint32_t v, const trace::RayBatch& batch, std::size_t count) {
      glm::vec3 sum(0.0f);
      std::uint32_t tri[3];
      for (std::size_t i = 0; i < count; ++i) {
        const trace::HitResult hit = batch.hit(i);
        if (!hit.hit()) continue;
        const trace::Ray& r = batch.data()[i].ray;
        if (!front_hit(mesh, hit, glm::vec3(r.dir_x, r.dir_y, r.dir_z), tri)) continue;
        sum += (1.0f - hit.u - hit.v) * radiance[tri[0]] + hit.u * radiance[tri[1]] + hit.v * radiance[tri[2]];
      }
      next[v] += sum;
    });
    for (std::size_t v = 0; v < vertices; ++v) {
      next[v] = direct[v] + albedo[v] * next[v] * static_cast<float>(inv_samples);
      if (has_emission) next[v] += light.emission[v];
    }
    radiance.swap(next);
  }
  if (rays_out) *rays_out = rays;
  return radiance;
}

}  // namespace prt::probes
