#include <algorithm>
#include <atomic>

#include <glm/geometric.hpp>

#include "bake/passes.h"
#include "core/parallel.h"

namespace prt::bake {

namespace {

// Sums of barycentric weights per vertex, in first-insertion order, for one gathering vertex: the
// hits of S rays land on few distinct vertices, so each previous-pass vector is read once per
// distinct vertex instead of three times per hit.
class WeightMap {
 public:
  explicit WeightMap(std::size_t max_entries) {
    std::size_t capacity = 16;
    while (capacity < 2 * max_entries) capacity *= 2;
    slots_.assign(capacity, kEmpty);
    mask_ = capacity - 1;
    keys_.reserve(max_entries);
    weights_.reserve(max_entries);
    slot_of_.reserve(max_entries);
  }
  void add(std::uint32_t key, float weight) {
    std::size_t slot = (key * 0x9e3779b1u) & mask_;
    for (;;) {
      std::uint32_t entry = slots_[slot];
      if (entry == kEmpty) {
        slots_[slot] = static_cast<std::uint32_t>(keys_.size());
        slot_of_.push_back(static_cast<std::uint32_t>(slot));
        keys_.push_back(key);
        weights_.push_back(weight);
        return;
      }
      if (keys_[entry] == key) {
        weights_[entry] += weight;
        return;
      }
      slot = (slot + 1) & mask_;
    }
  }
  void clear() {
    for (std::uint32_t slot : slot_of_) slots_[slot] = kEmpty;
    slot_of_.clear();
    keys_.clear();
    weights_.clear();
  }
  std::size_t size() const { return keys_.size(); }
  std::uint32_t key(std::size_t i) const { return keys_[i]; }
  float weight(std::size_t i) const { return weights_[i]; }

 private:
  static constexpr std::uint32_t kEmpty = 0xffffffffu;
  std::vector<std::uint32_t> slots_, keys_, slot_of_;
  std::vector<float> weights_;
  std::size_t mask_ = 0;
};

}  // namespace

std::uint64_t bounce_pass(const PassContext& ctx, const std::vector<glm::vec3>& albedo, int channels,
                          const std::vector<float>& prev, std::vector<float>& next, const char* label) {
  const mesh::Mesh& mesh = *ctx.mesh;
  const LocalSampleSet& set = *ctx.samples;
  const std::size_t n = static_cast<std::size_t>(set.bands) * set.bands;
  const std::size_t stride = n * static_cast<std::size_t>(channels);
  const std::size_t sample_count = set.directions.size();
  const float inv_samples = 1.0f / static_cast<float>(sample_count);
  next.assign(prev.size(), 0.0f);
  Progress progress(label, "vertices", mesh.positions.size(), ctx.progress);
  std::atomic<std::uint64_t> rays{0};

  parallel_for(ctx.order->size(), 64, ctx.threads, [&](std::size_t begin, std::size_t end) {
    trace::RayBatch batch(std::min<std::size_t>(sample_count, trace::kDefaultBatchCapacity));
    WeightMap weights(3 * sample_count);
    std::vector<float> gathered(stride);
    std::uint64_t traced = 0;
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t v = (*ctx.order)[k];
      const glm::mat3 frame = vertex_frame(mesh.normals[v], ctx.seed, v);
      const glm::vec3 origin = ctx.scene->offset_origin(mesh.positions[v], mesh.normals[v]);
      weights.clear();
      for (std::size_t first = 0; first < sample_count; first += batch.capacity()) {
        const std::size_t count = std::min(batch.capacity(), sample_count - first);
        batch.clear();
        for (std::size_t s = first; s < first + count; ++s) batch.push(origin, frame * set.directions[s]);
        ctx.scene->intersect(batch);
        traced += count;
        for (std::size_t i = 0; i < count; ++i) {
          const trace::HitResult hit = batch.hit(i);
          if (!hit.hit()) continue;
          const std::uint32_t* tri = mesh.indices.data() + 3 * static_cast<std::size_t>(hit.prim_id);
          const glm::vec3& p0 = mesh.positions[tri[0]];
          const glm::vec3 face_normal = glm::cross(mesh.positions[tri[1]] - p0, mesh.positions[tri[2]] - p0);
          const trace::Ray& d = batch.data()[i].ray;
          if (face_normal.x * d.dir_x + face_normal.y * d.dir_y + face_normal.z * d.dir_z >= 0.0f) continue;
          weights.add(tri[0], 1.0f - hit.u - hit.v);
          weights.add(tri[1], hit.u);
          weights.add(tri[2], hit.v);
        }
      }
      std::fill(gathered.begin(), gathered.end(), 0.0f);
      for (std::size_t e = 0; e < weights.size(); ++e) {
        const float w = weights.weight(e);
        const float* p = prev.data() + static_cast<std::size_t>(weights.key(e)) * stride;
        for (std::size_t c = 0; c < stride; ++c) gathered[c] += w * p[c];
      }
      float* o = next.data() + static_cast<std::size_t>(v) * stride;
      for (int ch = 0; ch < channels; ++ch) {
        const float scale = albedo[v][ch] * inv_samples;
        for (std::size_t c = 0; c < n; ++c) o[ch * n + c] = scale * gathered[ch * n + c];
      }
    }
    rays += traced;
    progress.advance(end - begin);
  });
  progress.finish();
  return rays.load();
}

}  // namespace prt::bake
