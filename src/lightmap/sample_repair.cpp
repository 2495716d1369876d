#include "lightmap/sample_repair.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "core/parallel.h"
#include "sh/sampling.h"

namespace prt::lightmap {

namespace {

const std::vector<glm::vec3>& probe_directions() {
  static const std::vector<glm::vec3> directions = [] {
    std::vector<glm::vec3> out;
    for (const glm::dvec3& d : sh::hemisphere_directions_cosine(kProbeRays, 0x9e3779b9u)) out.emplace_back(d);
    return out;
  }();
  return directions;
}

}  // namespace

float texel_world_size(const mesh::Mesh& mesh, std::uint32_t t, int width, int height) {
  const std::uint32_t* idx = mesh.indices.data() + 3 * std::size_t(t);
  const glm::dvec3 a(mesh.positions[idx[0]]), b(mesh.positions[idx[1]]), c(mesh.positions[idx[2]]);
  const double world = glm::length(glm::cross(b - a, c - a));
  const glm::dvec2 u0(mesh.lightmap_uv[3 * t]), u1(mesh.lightmap_uv[3 * t + 1]), u2(mesh.lightmap_uv[3 * t + 2]);
  const glm::dvec2 e1 = (u1 - u0) * glm::dvec2(width, height), e2 = (u2 - u0) * glm::dvec2(width, height);
  const double texels = std::abs(e1.x * e2.y - e1.y * e2.x);
  return texels > 0.0 ? float(std::sqrt(world / texels)) : 0.0f;
}

bool probe_buried(const trace::Scene& scene, const glm::vec3& p, const glm::vec3& n, float range, std::uint32_t seed,
                  std::uint32_t index, glm::vec3* moved) {
  const std::vector<glm::vec3>& local = probe_directions();
  const glm::mat3 frame = sh::vertex_frame(n, seed, index);
  const glm::vec3 origin = scene.offset_origin(p, n);
  trace::RayBatch batch(local.size());
  for (const glm::vec3& d : local) batch.push(origin, frame * d, 0.0f, range);
  scene.intersect(batch);
  int back = 0;
  float nearest = trace::kInfinity;
  glm::vec3 exit(p);
  for (std::size_t i = 0; i < batch.size(); ++i) {
    if (!batch.is_hit(i) || batch.is_front_hit(i)) continue;
    ++back;
    const trace::HitResult hit = batch.hit(i);
    if (hit.t < nearest) {
      nearest = hit.t;
      const glm::vec3 ng = glm::normalize(hit.ng);
      const glm::vec3 h = origin + hit.t * batch.direction(i);
      exit = h + ng * std::max(4.0f * scene.ray_offset(), 1e-3f * range);
    }
  }
  if (float(back) < kBuriedFraction * float(local.size())) return false;
  *moved = exit - n * glm::dot(exit - p, n);
  return true;
}

RepairReport repair_samples(const mesh::Mesh& mesh, const trace::Scene& scene, TexelSamples& samples, std::uint32_t seed,
                            int threads) {
  std::atomic<std::size_t> moved{0}, unrecoverable{0};
  parallel_for(samples.samples.size(), 64, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      TexelSample& s = samples.samples[k];
      const float range = kProbeRange * texel_world_size(mesh, s.triangle, samples.width, samples.height);
      glm::vec3 out, again;
      if (!(range > 0.0f) || !probe_buried(scene, s.position, s.normal, range, seed, s.texel, &out)) continue;
      if (probe_buried(scene, out, s.normal, range, seed, s.texel, &again)) {
        ++unrecoverable;
        continue;
      }
      s.position = out;
      ++moved;
    }
  });
  RepairReport report;
  report.moved = moved.load();
  report.unrecoverable = unrecoverable.load();
  report.rays = std::uint64_t(samples.samples.size()) * kProbeRays;  // first probes; moved ones trace twice
  report.rays += std::uint64_t(report.moved + report.unrecoverable) * kProbeRays;
  return report;
}

}  // namespace prt::lightmap
