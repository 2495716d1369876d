#include "probes/surface.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "core/constants.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "dist/exchange.h"
#include "light/environment.h"
#include "light/projection.h"
#include "probes/pilot.h"
#include "sh/basis.h"
#include "sh/sampling.h"
#include "sh/zonal.h"
#include "trace/scene.h"
#include "trace/vertex_rays.h"

namespace prt::probes {

namespace {

constexpr int kControlVariateBands = 5;

struct Context {
  const trace::Scene* scene;
  const mesh::Mesh* mesh;
  const std::vector<glm::vec3>* albedo;
  const std::vector<glm::vec3>* local_directions;
  std::vector<std::uint32_t> order;
  std::uint32_t seed;
  int threads;
  bool progress;
  const dist::Context* dist;  // each rank traces its share of `order`; results are allgathered
};

// One traversal of every vertex's S rays (trace/vertex_rays.h); `visit(v, batch)` consumes each batch.
// Distributed: this rank's share of the vertices only; returns the rays of all ranks.
template <class Visit>
std::uint64_t for_each_vertex_rays(const Context& ctx, const char* label, Visit visit) {
  struct Worker {
    Visit* visit;
    void start(std::uint32_t, const glm::mat3&) {}
    void batch(std::uint32_t v, const trace::RayBatch& batch, std::size_t) { (*visit)(v, batch); }
    void finish(std::uint32_t, const glm::mat3&) {}
  };
  Progress progress(label, "vertices", std::max<std::size_t>(1, ctx.mesh->positions.size()), ctx.progress);
  const dist::Range share = dist::my_range(dist::or_single(ctx.dist), ctx.order.size());
  const trace::VertexRays rays{ctx.scene, ctx.mesh, &ctx.order, ctx.local_directions, ctx.seed, ctx.threads,
                               trace::Query::closest_hit, nullptr, nullptr, share.begin, share.end};
  return dist::or_single(ctx.dist).sum(trace::trace_vertex_rays(rays, progress, [&] { return Worker{&visit}; }));
}

void check_surface_options(const SurfaceOptions& o) {
  if (o.samples < 1 || o.samples > 65536) fail_option("surface_samples", " " + std::to_string(o.samples) + " is out of range 1..65536");
  if (o.sun_samples < 1 || o.sun_samples > 4096) fail_option("sun_samples", " " + std::to_string(o.sun_samples) + " is out of range 1..4096");
  if (o.bounces < 0 || o.bounces > 64) fail_option("bounces", " " + std::to_string(o.bounces) + " is out of range 0..64");
}

// The pilot pass: per vertex, whether at most half of kPilotRays cosine-distributed occlusion rays (their
// own Sobol set, turned by their own hashed angle: independent of the S rays) are blocked. Such vertices
// use the control variate for all their rays, the others plain Monte Carlo (surface.h, ESTIMATORS).
std::vector<std::uint8_t> pilot_open(const Context& ctx, std::uint64_t& rays) {
  const mesh::Mesh& mesh = *ctx.mesh;
  std::vector<glm::vec3> pilot;
  for (const glm::dvec3& d : sh::hemisphere_directions_cosine(kPilotRays, hash_to_u32(ctx.seed, 0, kPilotSalt)))
    pilot.emplace_back(d);
  std::vector<std::uint8_t> open(mesh.positions.size(), 0);
  parallel_for(mesh.positions.size(), 256, ctx.threads, [&](std::size_t begin, std::size_t end) {
    trace::RayBatch batch(pilot.size());
    for (std::size_t v = begin; v < end; ++v) {
      const glm::mat3 frame = sh::turned_frame(mesh.normals[v], 2.0 * kPi * hash_to_unit(ctx.seed, v, kPilotSalt));
      const glm::vec3 origin = ctx.scene->offset_origin(mesh.positions[v], mesh.normals[v]);
      batch.clear();
      for (const glm::vec3& d : pilot) batch.push(origin, frame * d);
      ctx.scene->occluded(batch);
      open[v] = 2 * batch.occluded_count() <= batch.size() ? 1 : 0;
    }
  });
  rays += static_cast<std::uint64_t>(kPilotRays) * mesh.positions.size();
  return open;
}

// D's environment part, albedo / pi * E_env, added to `direct`.
void add_direct_environment(const Context& ctx, const light::Environment& environment, std::vector<glm::vec3>& direct,
                            std::uint64_t& rays) {
  const mesh::Mesh& mesh = *ctx.mesh;
  const sh::RgbCoefficients env_sh = light::project(environment, kControlVariateBands, ctx.threads);
  const light::Environment lookup = lookup_environment(environment);
  const int n = kControlVariateBands * kControlVariateBands;
  const double scale = kPi / static_cast<double>(ctx.local_directions->size());
  const std::vector<std::uint8_t> control_variate = pilot_open(ctx, rays);
  rays += for_each_vertex_rays(ctx, "probes: surface light", [&](std::uint32_t v, const trace::RayBatch& batch) {
    // The control variate: (pi/S) sum [V L_env - L_sh]; plain Monte Carlo: (pi/S) sum over escaping rays
    // of L_env, which skips the basis evaluations.
    glm::dvec3 sum(0.0);
    double basis[kControlVariateBands * kControlVariateBands];
    for (std::size_t i = 0; i < batch.size(); ++i) {
      const glm::dvec3 w(batch.direction(i));
      if (!batch.is_hit(i)) sum += lookup.radiance(w);
      if (control_variate[v]) {
        sh::eval(kControlVariateBands, w, basis);
        for (int k = 0; k < n; ++k) sum -= env_sh.values[k] * basis[k];
      }
    }
    direct[v] += glm::vec3(sum * scale);
  });
  dist::allgather_items(dist::or_single(ctx.dist), direct, 1, &ctx.order);
  parallel_for(mesh.positions.size(), 1024, ctx.threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      glm::dvec3 e(direct[v]);
      if (control_variate[v]) e += sh::irradiance(env_sh, glm::dvec3(mesh.normals[v]));
      direct[v] = glm::vec3(e * glm::dvec3((*ctx.albedo)[v]) / kPi);
    }
  });
}

// D's sun part, albedo / pi * E_sun, added to `direct`.
void add_direct_sun(const Context& ctx, const Sun& sun, int sun_samples, std::vector<glm::vec3>& direct, std::uint64_t& rays) {
  const mesh::Mesh& mesh = *ctx.mesh;
  const glm::dvec3 scale = sun.radiance() * (sun.solid_angle() / sun_samples);
  std::atomic<std::uint64_t> sun_rays{0};
  parallel_for(mesh.positions.size(), 256, ctx.threads, [&](std::size_t begin, std::size_t end) {
    trace::RayBatch batch(static_cast<std::size_t>(sun_samples));
    std::vector<float> cosines(static_cast<std::size_t>(sun_samples));
    std::uint64_t traced = 0;
    for (std::size_t v = begin; v < end; ++v) {
      const glm::vec3 n = mesh.normals[v];
      if (glm::dot(glm::dvec3(n), sun.direction) <= -std::sin(sun.angular_radius)) continue;
      const glm::vec3 origin = ctx.scene->offset_origin(mesh.positions[v], n);
      const std::uint32_t scramble = hash_to_u32(ctx.seed, v, 0x50u);
      batch.clear();
      for (int k = 0; k < sun_samples; ++k) {
        const glm::dvec2 u = sh::sobol_2d(static_cast<std::uint32_t>(k), scramble);
        const glm::vec3 w(sun_direction_sample(sun, u.x, u.y));
        cosines[k] = std::max(0.0f, glm::dot(n, w));
        batch.push(origin, w);
      }
      ctx.scene->occluded(batch);
      traced += batch.size();
      double sum = 0.0;
      for (int k = 0; k < sun_samples; ++k)
        if (!batch.is_occluded(static_cast<std::size_t>(k))) sum += cosines[k];
      direct[v] += glm::vec3(scale * sum * glm::dvec3((*ctx.albedo)[v]) / kPi);
    }
    sun_rays += traced;
  });
  rays += sun_rays.load();
}

// One gather G f: per vertex, the sum over its front-face hits of f interpolated at the hit.
std::vector<glm::vec3> gather(const Context& ctx, const std::vector<glm::vec3>& f, int bounce, std::uint64_t& rays) {
  std::vector<glm::vec3> sums(f.size(), glm::vec3(0.0f));
  const std::vector<std::uint32_t>& indices = ctx.mesh->indices;
  const std::string label = "probes: surface bounce " + std::to_string(bounce);
  rays += for_each_vertex_rays(ctx, label.c_str(), [&](std::uint32_t v, const trace::RayBatch& batch) {
    glm::vec3 sum(0.0f);
    for (std::size_t i = 0; i < batch.size(); ++i) {
      if (!batch.is_front_hit(i)) continue;
      const trace::HitResult hit = batch.hit(i);
      const std::uint32_t* tri = indices.data() + 3 * static_cast<std::size_t>(hit.prim_id);
      sum += (1.0f - hit.u - hit.v) * f[tri[0]] + hit.u * f[tri[1]] + hit.v * f[tri[2]];
    }
    sums[v] += sum;
  });
  dist::allgather_items(dist::or_single(ctx.dist), sums, 1, &ctx.order);
  return sums;
}

}  // namespace

std::vector<glm::vec3> surface_radiance(const trace::Scene& scene, const mesh::Mesh& mesh,
                                        const std::vector<glm::vec3>& albedo, const SceneLight& light,
                                        const SurfaceOptions& o, std::uint64_t* rays_out) {
  check_surface_options(o);
  const std::size_t vertices = mesh.positions.size();
  std::vector<glm::vec3> local;
  for (const glm::dvec3& d : sh::hemisphere_directions_cosine(static_cast<std::size_t>(o.samples), o.seed))
    local.emplace_back(d);
  const Context ctx{&scene, &mesh, &albedo, &local, trace::morton_order(mesh.positions), o.seed, o.threads, o.progress, o.dist};
  std::uint64_t rays = 0;

  // Direct reflection D of the environment (with the SH control variate) and the sun.
  std::vector<glm::vec3> direct(vertices, glm::vec3(0.0f));
  if (o.environment && light.environment) add_direct_environment(ctx, *light.environment, direct, rays);
  if (light.sun) add_direct_sun(ctx, *light.sun, o.sun_samples, direct, rays);

  // R_0 = E_m + D, then K gathers: R_k = E_m + D + G R_(k-1).
  const bool has_emission = !light.emission.empty();
  std::vector<glm::vec3> radiance = direct;
  if (has_emission)
    for (std::size_t v = 0; v < vertices; ++v) radiance[v] += light.emission[v];
  const float inv_samples = static_cast<float>(1.0 / static_cast<double>(o.samples));
  for (int bounce = 1; bounce <= o.bounces; ++bounce) {
    std::vector<glm::vec3> next = gather(ctx, radiance, bounce, rays);
    for (std::size_t v = 0; v < vertices; ++v) {
      next[v] = direct[v] + albedo[v] * next[v] * inv_samples;
      if (has_emission) next[v] += light.emission[v];
    }
    radiance.swap(next);
  }
  if (rays_out) *rays_out = rays;
  return radiance;
}

}  // namespace prt::probes
