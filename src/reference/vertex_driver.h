// Internal to prt_reference: the per-vertex loop shared by the diffuse (reference.cpp) and glossy
// (glossy_reference.cpp) references. It owns what makes the result independent of --threads: Morton
// order of work, one SampleStream(seed, v) per vertex, per-vertex results written in place, and the
// noise figure computed afterwards in vertex order.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <vector>

#include <glm/exponential.hpp>
#include <glm/vec3.hpp>

#include "core/parallel.h"
#include "core/progress.h"
#include "dist/exchange.h"
#include "mesh/mesh.h"
#include "mesh/vertex_footprint.h"
#include "reference/estimator.h"
#include "reference/reference.h"
#include "trace/scene.h"

namespace prt::reference::detail {

/// Vertices per parallel chunk: each vertex costs `samples` paths, so small chunks balance well.
constexpr std::size_t kVerticesPerChunk = 8;

/// Fills rep.mean_relative_standard_error from per-vertex values and standard errors (vertices darker
/// than 1e-6 of the brightest are left out), and copies the errors to `standard_error` if given.
void summarise_noise(const std::vector<glm::vec3>& radiance, const std::vector<glm::dvec3>& error,
                     ReferenceReport& rep, std::vector<glm::vec3>* standard_error);

/// Runs `estimate(v, stream, workspace) -> RadianceEstimate` for every point (a mesh's vertices, or
/// other sample points) at `positions` in Morton order on `threads` threads, each point with
/// SampleStream(seed, v). Fills rep.seconds_trace, rays, paths (= points * samples) and the noise
/// figure; returns per-point radiance. Distributed (`dist` of more than one rank): each rank estimates
/// its share of the order, rank 0 gathers the results and alone returns them complete (the others'
/// are undefined); rays are summed over ranks.
template <class Workspace, class Estimate>
std::vector<glm::vec3> trace_every_vertex(const std::vector<glm::vec3>& positions, const char* label, std::uint32_t seed,
                                          int samples, int threads, bool show_progress, const dist::Context* dist,
                                          ReferenceReport& rep, std::vector<glm::vec3>* standard_error,
                                          const Estimate& estimate) {
  const std::size_t vertices = positions.size();
  const std::vector<std::uint32_t> order = trace::morton_order(positions);
  std::vector<glm::vec3> radiance(vertices);
  std::vector<glm::dvec3> error(vertices);
  std::atomic<std::uint64_t> rays{0};
  Progress progress(label, "vertices", std::max<std::size_t>(vertices, 1), show_progress);
  const dist::Context& ranks = dist::or_single(dist);
  const dist::Range share = dist::my_range(ranks, order.size());
  const std::size_t progress_scale = ranks.size();  // equal shares: this rank's progress estimates the job's
  const auto start = std::chrono::steady_clock::now();
  parallel_for(share.size(), kVerticesPerChunk, threads, [&](std::size_t chunk_begin, std::size_t chunk_end) {
    Workspace workspace;
    std::uint64_t traced = 0;
    const std::size_t begin = share.begin + chunk_begin, end = share.begin + chunk_end;
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t v = order[k];
      SampleStream stream(seed, v);
      const RadianceEstimate e = estimate(v, stream, workspace);
      radiance[v] = glm::vec3(e.value);
      error[v] = e.standard_error;
      traced += e.rays;
    }
    rays += traced;
    progress.advance((end - begin) * progress_scale);
  });
  progress.finish();
  dist::gather_items(ranks, radiance, 1, &order);
  dist::gather_items(ranks, error, 1, &order);
  rep.seconds_trace = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  rep.rays = ranks.sum(rays.load());
  rep.paths = static_cast<std::uint64_t>(vertices) * static_cast<std::uint64_t>(samples);
  summarise_noise(radiance, error, rep, standard_error);
  return radiance;
}

/// Vertex v's estimate over its footprint (mesh/vertex_footprint.h), from `samples` paths cut into
/// mesh::footprint_point_count(samples) runs of nearly equal length. Run k leaves from footprint point
/// footprints.stratified_point(v, k, scramble) (scramble = the first output of SampleStream(seed, v))
/// and has its own stream, SampleStream(seed, v * mesh::kMaxFootprintPoints + k), for its paths:
/// estimate_at(position, triangle, paths, stream) -> RadianceEstimate, with the triangle the point lies
/// on (mesh::kNoTriangle if none; the true-surface rule's, trace/true_surface.h). The runs' means are weighted by their
/// lengths; their standard errors, independent, are combined the same way.
template <class EstimateAt>
RadianceEstimate footprint_estimate(const mesh::VertexFootprints& footprints, std::uint32_t v, std::uint32_t seed, int samples,
                                    const EstimateAt& estimate_at) {
  const int runs = mesh::footprint_point_count(samples);
  const std::uint32_t scramble = SampleStream(seed, v).rng().next_u32();
  const auto run_end = [&](int run) { return static_cast<int>(static_cast<std::int64_t>(samples) * run / runs); };
  RadianceEstimate total;
  glm::dvec3 variance(0.0);
  for (int k = 0; k < runs; ++k) {
    const int paths = run_end(k + 1) - run_end(k);
    SampleStream stream(seed, static_cast<std::uint64_t>(v) * mesh::kMaxFootprintPoints + static_cast<std::uint64_t>(k));
    std::uint32_t triangle = mesh::kNoTriangle;
    const glm::vec3 position = footprints.stratified_point(v, static_cast<std::uint32_t>(k), scramble, &triangle);
    const RadianceEstimate e = estimate_at(position, triangle, paths, stream);
    const double w = static_cast<double>(paths) / samples;
    total.value += w * e.value;
    variance += w * w * e.standard_error * e.standard_error;
    total.rays += e.rays;
  }
  total.standard_error = glm::sqrt(variance);
  return total;
}

}  // namespace prt::reference::detail
