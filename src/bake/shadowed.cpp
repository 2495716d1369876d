#include <algorithm>
#include <atomic>

#include "bake/passes.h"
#include "core/parallel.h"
#include "sh/rotation.h"

namespace prt::bake {

namespace {

// Fills `batch` with the rays s in [first, first + count) of vertex v.
void fill_rays(trace::RayBatch& batch, const glm::vec3& origin, const glm::mat3& frame,
               const std::vector<glm::vec3>& local, std::size_t first, std::size_t count) {
  batch.clear();
  for (std::size_t s = first; s < first + count; ++s) batch.push(origin, frame * local[s]);
}

}  // namespace

std::uint64_t shadowed_geometric(const PassContext& ctx, std::vector<float>& out) {
  const mesh::Mesh& mesh = *ctx.mesh;
  const LocalSampleSet& set = *ctx.samples;
  const int n = set.bands * set.bands;
  const std::size_t sample_count = set.directions.size();
  const float inv_samples = 1.0f / static_cast<float>(sample_count);
  const std::vector<double> factors = unshadowed_factors(set.bands);
  out.assign(mesh.positions.size() * static_cast<std::size_t>(n), 0.0f);
  Progress progress("bake shadowed", "vertices", mesh.positions.size(), ctx.progress);
  std::atomic<std::uint64_t> rays{0};

  parallel_for(ctx.order->size(), 64, ctx.threads, [&](std::size_t begin, std::size_t end) {
    trace::RayBatch batch(std::min<std::size_t>(sample_count, trace::kDefaultBatchCapacity));
    std::vector<float> local_sum(static_cast<std::size_t>(n)), world_sum(static_cast<std::size_t>(n));
    std::uint64_t traced = 0;
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t v = (*ctx.order)[k];
      const glm::mat3 frame = vertex_frame(mesh.normals[v], ctx.seed, v);
      const glm::vec3 origin = ctx.scene->offset_origin(mesh.positions[v], mesh.normals[v]);
      std::fill(local_sum.begin(), local_sum.end(), 0.0f);
      bool any_occluded = false;
      for (std::size_t first = 0; first < sample_count; first += batch.capacity()) {
        const std::size_t count = std::min(batch.capacity(), sample_count - first);
        fill_rays(batch, origin, frame, set.directions, first, count);
        ctx.scene->occluded(batch);
        traced += count;
        for (std::size_t i = 0; i < count; ++i) {
          if (!batch.is_occluded(i)) continue;
          any_occluded = true;
          const float* y = set.basis.data() + (first + i) * n;
          for (int c = 0; c < n; ++c) local_sum[c] += y[c];
        }
      }
      float* o = out.data() + static_cast<std::size_t>(v) * n;
      unshadowed_vertex(set.bands, factors, mesh.normals[v], o);
      if (any_occluded) {
        sh::rotate(set.bands, frame, local_sum.data(), world_sum.data());
        for (int c = 0; c < n; ++c) o[c] -= inv_samples * world_sum[c];
      }
    }
    rays += traced;
    progress.advance(end - begin);
  });
  progress.finish();
  return rays.load();
}

}  // namespace prt::bake
