#include <algorithm>

#include "bake/passes.h"
#include "core/big_buffer.h"
#include "sh/rotation.h"
#include "trace/vertex_rays.h"

namespace prt::bake {

namespace {

// Per chunk: sums the local basis rows of v's occluded rays, then writes the unshadowed transfer minus
// that sum rotated to the world (the control variate of bake.h).
class ShadowedWorker {
 public:
  ShadowedWorker(const PassContext& ctx, const std::vector<double>& factors, const OccludedRowSums& rows, std::vector<float>& out)
      : ctx_(ctx), factors_(factors), rows_(rows), out_(out), n_(ctx.samples->bands * ctx.samples->bands),
        local_sum_(static_cast<std::size_t>(rows.width())), world_sum_(n_) {}

  void start(std::uint32_t, const glm::mat3&) {
    std::fill(local_sum_.begin(), local_sum_.end(), 0.0f);
    any_occluded_ = false;
  }

  // `first` counts from the point's own set (ctx.point_set): its rows start at first_sample(v).
  void batch(std::uint32_t v, const trace::RayBatch& batch, std::size_t first) {
    if (rows_.add(batch, ctx_.first_sample(v) + first, local_sum_.data()) > 0) any_occluded_ = true;
  }

  void finish(std::uint32_t v, const glm::mat3& frame) {
    const int bands = ctx_.samples->bands;
    float* o = out_.data() + static_cast<std::size_t>(v) * n_;
    unshadowed_vertex(bands, factors_, ctx_.point_normals()[v], o);
    if (!any_occluded_) return;
    const float inv_samples = 1.0f / static_cast<float>(ctx_.samples->per_point());
    sh::rotate(bands, frame, local_sum_.data(), world_sum_.data());
    for (int c = 0; c < n_; ++c) o[c] -= inv_samples * world_sum_[c];
  }

 private:
  const PassContext& ctx_;
  const std::vector<double>& factors_;
  const OccludedRowSums& rows_;
  std::vector<float>& out_;
  int n_;
  std::vector<float> local_sum_, world_sum_;  // local_sum_: rows_.width() floats, the first n_ used
  bool any_occluded_ = false;
};

}  // namespace

std::uint64_t shadowed_geometric(const PassContext& ctx, std::vector<float>& out) {
  const std::size_t n = static_cast<std::size_t>(ctx.samples->bands) * ctx.samples->bands;
  const std::vector<double> factors = unshadowed_factors(ctx.samples->bands);
  const OccludedRowSums rows(*ctx.samples);
  assign_big(out, ctx.point_count() * n, 0.0f);
  Progress progress("bake shadowed", ctx.point_unit(), ctx.point_count(), ctx.progress);
  return trace::trace_vertex_rays(ctx.rays(trace::Query::occluded), progress,
                                  [&] { return ShadowedWorker(ctx, factors, rows, out); });
}

}  // namespace prt::bake
