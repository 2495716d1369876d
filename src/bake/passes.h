#pragma once
// Internal to prt_bake: the passes of a diffuse bake. All buffers are vertex-major; "geometric"
// transfer has no albedo (bands^2 floats per vertex), "channel" transfer has `channels` blocks of
// bands^2 floats per vertex (docs/formats.md payload layout).
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "bake/vertex_samples.h"
#include "core/progress.h"
#include "mesh/mesh.h"
#include "trace/scene.h"
#include "trace/vertex_rays.h"

namespace prt::bake {

/// What every ray-tracing pass shares.
struct PassContext {
  const mesh::Mesh* mesh = nullptr;
  const trace::Scene* scene = nullptr;
  const LocalSampleSet* samples = nullptr;
  const std::vector<std::uint32_t>* order = nullptr;  ///< vertex visiting order (Morton)
  std::uint32_t seed = 0;
  int threads = 0;
  bool progress = false;

  /// The per-vertex ray loop of this context (trace/vertex_rays.h) with query `query`.
  trace::VertexRays rays(trace::Query query) const {
    return trace::VertexRays{scene, mesh, order, &samples->directions, seed, threads, query};
  }
};

/// (1/pi) A_l, l < bands: the clamped-cosine factors of the unshadowed transfer.
std::vector<double> unshadowed_factors(int bands);

/// (1/pi) A_l Y_lm(n) at one unit normal: the albedo-free unshadowed transfer (bands^2 floats).
void unshadowed_vertex(int bands, const std::vector<double>& factors, const glm::vec3& normal, float* out);

/// The albedo-free unshadowed transfer of every vertex, closed form.
void unshadowed_geometric(const mesh::Mesh& mesh, int bands, int threads, std::vector<float>& out);

/// The albedo-free shadowed transfer of every vertex with the control-variate estimator (bake.h).
/// Returns the number of rays traced.
std::uint64_t shadowed_geometric(const PassContext& ctx, std::vector<float>& out);

/// One interreflection pass: next[v] = albedo_v / S * sum over front-face hits of prev interpolated at
/// the hit. `albedo` has one entry per vertex; `channels` is 1 (albedo grey: its red value is used) or 3.
/// Returns the number of rays traced.
std::uint64_t bounce_pass(const PassContext& ctx, const std::vector<glm::vec3>& albedo, int channels,
                          const std::vector<float>& prev, std::vector<float>& next, const char* label);

}  // namespace prt::bake
