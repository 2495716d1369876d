#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "bake/passes.h"
#include "core/constants.h"
#include "core/parallel.h"
#include "mesh/texture.h"
#include "mesh/texture_mips.h"

namespace prt::bake {

namespace {

// Sums of barycentric weights per vertex, in first-insertion order, for one gathering vertex: the
// hits of S rays land on few distinct vertices, so each previous-pass vector is read once per
// distinct vertex instead of three times per hit. A weight has one value per channel: the
// barycentric weight times the albedo at the hit (1 unless albedo_at_hits).
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
  void add(std::uint32_t key, const glm::vec3& weight) {
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
  const glm::vec3& weight(std::size_t i) const { return weights_[i]; }

 private:
  static constexpr std::uint32_t kEmpty = 0xffffffffu;
  std::vector<std::uint32_t> slots_, keys_, slot_of_;
  std::vector<glm::vec3> weights_;
  std::size_t mask_ = 0;
};

// The hit's lightmap UV (barycentric over the triangle's corner UVs) spread bilinearly over the four
// nearest texel centres of `grid` (clamped to the edge); empty texels are left out and the remaining
// weights renormalised, so a hit beside a chart without gutter still reads the chart's own values.
// Each weight is multiplied by `albedo`, the albedo at the hit.
void add_texel_weights(const TexelGrid& grid, std::size_t triangle, float u, float v, const glm::vec3& albedo,
                       WeightMap& weights) {
  const glm::vec2* c = grid.corner_uv->data() + 3 * triangle;
  const glm::vec2 uv = (1.0f - u - v) * c[0] + u * c[1] + v * c[2];
  // UVs far outside [0, 1] (a triangle the texel bake skipped, lightmap/uv_validation.h) are brought
  // to [-1, 2] and NaN to 0 before the integer conversion; the texels read are clamped to the edge
  // below, and UVs within [-1, 2] are used exactly as they are.
  auto tame = [](float s) { return s >= -1.0f ? (s <= 2.0f ? s : 2.0f) : (s < -1.0f ? -1.0f : 0.0f); };
  const float x = tame(uv.x) * static_cast<float>(grid.width) - 0.5f, y = tame(uv.y) * static_cast<float>(grid.height) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float ax = x - fx, ay = y - fy;
  std::uint32_t texel[4];
  float w[4];
  float total = 0.0f;
  for (int k = 0; k < 4; ++k) {
    const int i = std::clamp(static_cast<int>(fx) + (k & 1), 0, grid.width - 1);
    const int j = std::clamp(static_cast<int>(fy) + (k >> 1), 0, grid.height - 1);
    texel[k] = static_cast<std::uint32_t>(i + j * grid.width);
    w[k] = ((*grid.coverage)[texel[k]] == 0) ? 0.0f : ((k & 1) ? ax : 1.0f - ax) * ((k >> 1) ? ay : 1.0f - ay);
    total += w[k];
  }
  if (!(total > 0.0f)) return;
  for (int k = 0; k < 4; ++k)
    if (w[k] > 0.0f) weights.add(texel[k], (w[k] / total) * albedo);
}

// Per chunk: merges the barycentric weights of v's front-face hits per hit vertex, then reads each
// distinct vertex's previous transfer once. Without albedo_at_hits the receiver's albedo scales the
// sum (prev includes the hit vertices' albedo); with it each hit's weights carry the base colour at
// the hit and the result stays albedo-free (interreflect folds the receiver's albedo in).
class BounceWorker {
 public:
  // `colours`: every triangle's base colour lookup (HitColours), empty unless albedo_at_hits.
  BounceWorker(const PassContext& ctx, const std::vector<glm::vec3>& albedo, int channels, const std::vector<float>& prev,
               std::vector<float>& next, const std::vector<mesh::TriangleColour>& colours)
      : ctx_(ctx), albedo_(albedo), channels_(channels), prev_(prev), next_(next),
        n_(static_cast<std::size_t>(ctx.samples->bands) * ctx.samples->bands), stride_(n_ * channels),
        at_hits_(albedo_at_hits(*ctx.mesh)), weights_(4 * ctx.samples->per_point()), gathered_(stride_),
        colours_(colours), cone_(sample_cone_width(ctx.samples->per_point())) {}

  void start(std::uint32_t, const glm::mat3&) { weights_.clear(); }

  // The batch's front-face hits first, each textured one's texels requested (the hits fall on the
  // texture at random: requested together, their loads overlap); then their weights, in ray order.
  void batch(std::uint32_t, const trace::RayBatch& batch, std::size_t) {
    const mesh::Mesh& mesh = *ctx_.mesh;
    front_.clear();
    requests_.clear();
    // The hit triangles' lookups (two cache lines each, read at random) start loading now.
    if (at_hits_) batch.hit_count(colours_.data(), sizeof(mesh::TriangleColour));
    for (std::size_t i = 0; i < batch.size(); ++i) {
      if (!batch.is_hit(i)) continue;
      const trace::HitResult hit = batch.hit(i);
      const std::uint32_t* tri = mesh.indices.data() + 3 * static_cast<std::size_t>(hit.prim_id);
      const glm::vec3& p0 = mesh.positions[tri[0]];
      const glm::vec3 face_normal = glm::cross(mesh.positions[tri[1]] - p0, mesh.positions[tri[2]] - p0);
      if (glm::dot(face_normal, batch.direction(i)) >= 0.0f) continue;  // back face: black
      front_.push_back(hit);
      if (!at_hits_) continue;
      const mesh::TriangleColour& colour = colours_[hit.prim_id];
      requests_.push_back(colour.request(hit.u, hit.v, colour.level_for(double(hit.t) * cone_)));
    }
    for (std::size_t k = 0; k < front_.size(); ++k) {
      const trace::HitResult& hit = front_[k];
      const glm::vec3 albedo = at_hits_ ? colours_[hit.prim_id].at(requests_[k]) : glm::vec3(1.0f);
      if (ctx_.grid && !ctx_.grid->per_vertex(hit.prim_id)) {
        add_texel_weights(*ctx_.grid, hit.prim_id, hit.u, hit.v, albedo, weights_);
        continue;
      }
      const std::uint32_t base = ctx_.grid ? ctx_.grid->vertex_base() : 0;  // mixed scenes: vertices after the texels
      const std::uint32_t* tri = mesh.indices.data() + 3 * static_cast<std::size_t>(hit.prim_id);
      weights_.add(base + tri[0], (1.0f - hit.u - hit.v) * albedo);
      weights_.add(base + tri[1], hit.u * albedo);
      weights_.add(base + tri[2], hit.v * albedo);
    }
  }

  void finish(std::uint32_t v, const glm::mat3&) {
    std::fill(gathered_.begin(), gathered_.end(), 0.0f);
    for (std::size_t e = 0; e < weights_.size(); ++e) {
      const glm::vec3& w = weights_.weight(e);
      const float* p = prev_.data() + static_cast<std::size_t>(weights_.key(e)) * stride_;
      for (int ch = 0; ch < channels_; ++ch)
        for (std::size_t c = ch * n_; c < (ch + 1) * n_; ++c) gathered_[c] += w[ch] * p[c];
    }
    const float inv_samples = 1.0f / static_cast<float>(ctx_.samples->per_point());
    float* o = next_.data() + static_cast<std::size_t>(v) * stride_;
    for (int ch = 0; ch < channels_; ++ch) {
      const float scale = (at_hits_ ? 1.0f : albedo_[v][ch]) * inv_samples;
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
  bool at_hits_;
  WeightMap weights_;
  std::vector<float> gathered_;
  const std::vector<mesh::TriangleColour>& colours_;  // per triangle (at_hits_ only)
  std::vector<trace::HitResult> front_;               // this batch's front-face hits
  std::vector<mesh::TriangleColour::Request> requests_;  // their base colour lookups (at_hits_ only)
  double cone_;  // a sample's footprint width per unit of hit distance (sample_cone_width)
};

}  // namespace

HitColours::HitColours(const PassContext& ctx) {
  const mesh::Mesh& mesh = *ctx.mesh;
  if (!albedo_at_hits(mesh)) return;
  mips_ = mesh::build_mips(mesh.textures, std::vector<bool>(mesh.textures.size(), true), ctx.threads);
  triangles_.resize(mesh.triangle_count());
  parallel_for(triangles_.size(), 4096, ctx.threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) triangles_[t] = mesh::TriangleColour(mesh, static_cast<std::uint32_t>(t), &mips_);
  });
}

bool albedo_at_hits(const mesh::Mesh& mesh) { return mesh.textured(); }

std::uint64_t hit_colour_bytes(const mesh::Mesh& mesh) {
  if (!albedo_at_hits(mesh)) return 0;
  std::uint64_t bytes = std::uint64_t(mesh.triangle_count()) * sizeof(mesh::TriangleColour);
  for (const mesh::Texture& t : mesh.textures) bytes += mesh::TextureMips::coarse_bytes(t.width, t.height);
  return bytes;
}

double sample_cone_width(std::size_t samples) { return std::sqrt(2.0 * kPi / static_cast<double>(samples)); }

std::uint64_t bounce_pass(const PassContext& ctx, const HitColours& hit_colours, const std::vector<glm::vec3>& albedo, int channels,
                          const std::vector<float>& prev, std::vector<float>& next, const char* label) {
  const std::size_t stride = static_cast<std::size_t>(ctx.samples->bands) * ctx.samples->bands * static_cast<std::size_t>(channels);
  next.assign(ctx.point_count() * stride, 0.0f);
  const std::vector<mesh::TriangleColour>& colours = hit_colours.triangles();
  Progress progress(label, ctx.point_unit(), ctx.point_count(), ctx.progress);
  return trace::trace_vertex_rays(ctx.rays(trace::Query::closest_hit), progress,
                                  [&] { return BounceWorker(ctx, albedo, channels, prev, next, colours); });
}

}  // namespace prt::bake
