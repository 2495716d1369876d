// Interreflection passes of a glossy bake (Sloan, Kautz and Snyder 2002, section 5; bake.h, GLOSSY).
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "bake/glossy_passes.h"
#include "core/constants.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "sh/basis.h"
#include "sh/sampling.h"

namespace prt::bake {

namespace {

// Rows k of a BRDF matrix that are not identically zero (l + m even; projection.h, STRUCTURE).
std::vector<int> nonzero_rows(int bands) {
  std::vector<int> rows;
  for (int l = 0; l < bands; ++l)
    for (int m = -l; m <= l; ++m)
      if ((l + std::abs(m)) % 2 == 0) rows.push_back(sh::index(l, m));
  return rows;
}

// P_q,c = B_q,c M_q,c for every vertex q (B_q = b[brdfs.of(q)]) and channel c: the map from world lighting to the outgoing
// radiance coefficients of q (local frame), rows restricted to `rows`. Layout: vertex-major,
// channel-major, [rows.size()][n_in].
void outgoing_matrices(const GlossyContext& ctx, const std::vector<brdf::BrdfMatrix>& b, const brdf::VertexBrdfs& brdfs, int channels,
                       const std::vector<int>& rows, const std::vector<float>& transfer, std::vector<float>& out) {
  const int n_in = ctx.bands * ctx.bands, n_out = ctx.bands_out * ctx.bands_out;
  const std::size_t matrix_size = static_cast<std::size_t>(n_out) * n_in;
  const std::size_t block = rows.size() * static_cast<std::size_t>(n_in);
  const std::size_t vertices = ctx.mesh->positions.size();
  out.assign(vertices * channels * block, 0.0f);
  parallel_for(vertices, 256, ctx.threads, [&](std::size_t begin, std::size_t end) {
    std::vector<double> row_sum(static_cast<std::size_t>(n_in));
    for (std::size_t q = begin; q < end; ++q)
      for (int c = 0; c < channels; ++c) {
        const brdf::BrdfMatrix& bq = b[brdfs.of(q)];
        const double* bc = bq.channel(bq.channels == 1 ? 0 : c);
        const float* m = transfer.data() + (q * channels + c) * matrix_size;
        float* p = out.data() + (q * channels + c) * block;
        for (std::size_t r = 0; r < rows.size(); ++r) {
          std::fill(row_sum.begin(), row_sum.end(), 0.0);
          const double* brow = bc + static_cast<std::size_t>(rows[r]) * n_out;
          for (int j = 0; j < n_out; ++j) {
            if (brow[j] == 0.0) continue;
            const float* mrow = m + static_cast<std::size_t>(j) * n_in;
            for (int i = 0; i < n_in; ++i) row_sum[i] += brow[j] * mrow[i];
          }
          for (int i = 0; i < n_in; ++i) p[r * n_in + i] = static_cast<float>(row_sum[i]);
        }
      }
  });
}

// Per chunk: for each front-face hit of v's rays, the radiance row leaving the hit point toward v
// (interpolated over the hit triangle's corners q: sum_k y_k(F_q^T (-w)) P_q[k, :]) times y_out(w_s),
// summed; then rotated from the sample frame to v's frame.
class GlossyBounceWorker {
 public:
  GlossyBounceWorker(const GlossyContext& ctx, int channels, const std::vector<int>& rows, const std::vector<float>& outgoing,
                     std::vector<float>& next)
      : ctx_(ctx), channels_(channels), rows_(rows), outgoing_(outgoing), next_(next), n_in_(ctx.bands * ctx.bands),
        n_out_(ctx.bands_out * ctx.bands_out), matrix_size_(static_cast<std::size_t>(n_out_) * n_in_),
        block_(rows.size() * static_cast<std::size_t>(n_in_)), gathered_(matrix_size_ * channels),
        radiance_row_(static_cast<std::size_t>(channels) * n_in_), y_corner_(static_cast<std::size_t>(n_out_)),
        matrix_(matrix_size_) {}

  void start(std::uint32_t, const glm::mat3&) {
    std::fill(gathered_.begin(), gathered_.end(), 0.0f);
    any_hit_ = false;
  }

  void batch(std::uint32_t, const trace::RayBatch& batch, std::size_t first) {
    for (std::size_t i = 0; i < batch.size(); ++i) {
      if (!batch.is_front_hit(i)) continue;  // a miss, or a back face: black (single-sided surfaces)
      any_hit_ = true;
      radiance_toward(batch.hit(i), batch.direction(i));
      // Outer product with y_out(w_s) (sample frame).
      const float* y = ctx_.samples->basis.data() + (first + i) * n_in_;
      for (int c = 0; c < channels_; ++c) {
        const float* src = radiance_row_.data() + static_cast<std::size_t>(c) * n_in_;
        for (int row = 0; row < n_out_; ++row) {
          const float a = y[row];
          float* dst = gathered_.data() + c * matrix_size_ + static_cast<std::size_t>(row) * n_in_;
          for (int col = 0; col < n_in_; ++col) dst[col] += a * src[col];
        }
      }
    }
  }

  void finish(std::uint32_t v, const glm::mat3& sample_frame) {
    if (!any_hit_) return;
    // Rows from the sample frame to the vertex frame: Rot_out(F^T F_s); columns are already world.
    const double scale = 2.0 * kPi / static_cast<double>(ctx_.samples->directions.size());
    const glm::dmat3 world_to_local = glm::transpose(glm::dmat3((*ctx_.frames)[v]));
    const sh::Rotation rows_to_local(ctx_.bands_out, world_to_local * glm::dmat3(sample_frame));
    float* o = next_.data() + static_cast<std::size_t>(v) * matrix_size_ * channels_;
    for (int c = 0; c < channels_; ++c) {
      for (std::size_t i = 0; i < matrix_size_; ++i) matrix_[i] = scale * gathered_[c * matrix_size_ + i];
      rotate_columns(rows_to_local, n_in_, matrix_.data());
      for (std::size_t i = 0; i < matrix_size_; ++i) o[c * matrix_size_ + i] = static_cast<float>(matrix_[i]);
    }
  }

 private:
  // radiance_row_ := the radiance row toward the gathering vertex at `hit` (ray direction `dir`):
  // sum over corners c of bary_c sum_k y_k(F_c^T (-dir)) P_c[k, :].
  void radiance_toward(const trace::HitResult& hit, const glm::vec3& dir) {
    const std::uint32_t* tri = ctx_.mesh->indices.data() + 3 * static_cast<std::size_t>(hit.prim_id);
    std::fill(radiance_row_.begin(), radiance_row_.end(), 0.0f);
    const float bary[3] = {1.0f - hit.u - hit.v, hit.u, hit.v};
    for (int corner = 0; corner < 3; ++corner) {
      if (bary[corner] == 0.0f) continue;
      const std::uint32_t q = tri[corner];
      const glm::vec3 toward = glm::transpose((*ctx_.frames)[q]) * (-dir);
      sh::eval(ctx_.bands_out, toward, y_corner_.data());
      for (int c = 0; c < channels_; ++c) {
        const float* p = outgoing_.data() + (static_cast<std::size_t>(q) * channels_ + c) * block_;
        float* dst = radiance_row_.data() + static_cast<std::size_t>(c) * n_in_;
        for (std::size_t r = 0; r < rows_.size(); ++r) {
          const float w = bary[corner] * y_corner_[rows_[r]];
          const float* prow = p + r * n_in_;
          for (int col = 0; col < n_in_; ++col) dst[col] += w * prow[col];
        }
      }
    }
  }

  const GlossyContext& ctx_;
  int channels_;
  const std::vector<int>& rows_;
  const std::vector<float>& outgoing_;
  std::vector<float>& next_;
  int n_in_, n_out_;
  std::size_t matrix_size_, block_;
  std::vector<float> gathered_, radiance_row_, y_corner_;
  std::vector<double> matrix_;
  bool any_hit_ = false;
};

}  // namespace

std::uint64_t glossy_bounce_pass(const GlossyContext& ctx, const std::vector<brdf::BrdfMatrix>& brdf_matrices,
                                 const brdf::VertexBrdfs& brdfs, int channels,
                                 const std::vector<float>& prev, std::vector<float>& next, const char* label) {
  const std::vector<int> rows = nonzero_rows(ctx.bands_out);
  std::vector<float> outgoing;
  outgoing_matrices(ctx, brdf_matrices, brdfs, channels, rows, prev, outgoing);
  next.assign(prev.size(), 0.0f);
  Progress progress(label, "vertices", ctx.mesh->positions.size(), ctx.progress);
  return trace::trace_vertex_rays(ctx.rays(trace::Query::closest_hit), progress,
                                  [&] { return GlossyBounceWorker(ctx, channels, rows, outgoing, next); });
}

}  // namespace prt::bake
