#include <algorithm>

#include <glm/geometric.hpp>

#include "bake/passes.h"

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

// Per chunk: merges the barycentric weights of v's front-face hits per hit vertex, then reads each
// distinct vertex's previous transfer once.
class BounceWorker {
 public:
  BounceWorker(const PassContext& ctx, const std::vector<glm::vec3>& albedo, int channels, const std::vector<float>& prev,
               std::vector<float>& next)
      : ctx_(ctx), albedo_(albedo), channels_(channels), prev_(prev), next_(next),
        n_(static_cast<std::size_t>(ctx.samples->bands) * ctx.samples->bands), stride_(n_ * channels),
        weights_(3 * ctx.samples->directions.size()), gathered_(stride_) {}

  void start(std::uint32_t, const glm::mat3&) { weights_.clear(); }

  void batch(std::uint32_t, const trace::RayBatch& batch, std::size_t) {
    const mesh::Mesh& mesh = *ctx_.mesh;
    for (std::size_t i = 0; i < batch.size(); ++i) {
      if (!batch.is_hit(i)) continue;
      const trace::HitResult hit = batch.hit(i);
      const std::uint32_t* tri = mesh.indices.data() + 3 * static_cast<std::size_t>(hit.prim_id);
      const glm::vec3& p0 = mesh.positions[tri[0]];
      const glm::vec3 face_normal = glm::cross(mesh.positions[tri[1]] - p0, mesh.positions[tri[2]] - p0);
      if (glm::dot(face_normal, batch.direction(i)) >= 0.0f) continue;  // back face: black
      weights_.add(tri[0], 1.0f - hit.u - hit.v);
      weights_.add(tri[1], hit.u);
      weights_.add(tri[2], hit.v);
    }
  }

  void finish(std::uint32_t v, const glm::mat3&) {
    std::fill(gathered_.begin(), gathered_.end(), 0.0f);
    for (std::size_t e = 0; e < weights_.size(); ++e) {
      const float w = weights_.weight(e);
      const float* p = prev_.data() + static_cast<std::size_t>(weights_.key(e)) * stride_;
      for (std::size_t c = 0; c < stride_; ++c) gathered_[c] += w * p[c];
    }
    const float inv_samples = 1.0f / static_cast<float>(ctx_.samples->directions.size());
    float* o = next_.data() + static_cast<std::size_t>(v) * stride_;
    for (int ch = 0; ch < channels_; ++ch) {
      const float scale = albedo_[v][ch] * inv_samples;
      for (std::size_t c = 0; c < n_; ++c) o[ch * n_ + c] = scale * gathered_[ch * n_ + c];
    }
  }

 private:
  const PassContext& ctx_;
  const std::vector<glm::vec3>& albedo_;
  int channels_;
  const std::vector<float>& prev_;
  std::vector<float>& next_;
  std::size_t n_, stride_;
  WeightMap weights_;
  std::vector<float> gathered_;
};

}  // namespace

std::uint64_t bounce_pass(const PassContext& ctx, const std::vector<glm::vec3>& albedo, int channels,
                          const std::vector<float>& prev, std::vector<float>& next, const char* label) {
  next.assign(prev.size(), 0.0f);
  Progress progress(label, "vertices", ctx.mesh->positions.size(), ctx.progress);
  return trace::trace_vertex_rays(ctx.rays(trace::Query::closest_hit), progress,
                                  [&] { return BounceWorker(ctx, albedo, channels, prev, next); });
}

}  // namespace prt::bake
