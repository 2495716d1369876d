// The direct pass of a glossy bake: per-vertex transfer matrices with binary visibility (bake.h, GLOSSY).
#include <algorithm>
#include <cmath>

#include <glm/matrix.hpp>

#include "bake/glossy_passes.h"
#include "core/constants.h"
#include "core/progress.h"

namespace prt::bake {

void rotate_rows(const sh::Rotation& r, int rows, double* matrix) {
  const int n = r.bands() * r.bands();
  std::vector<double> rotated(static_cast<std::size_t>(n));
  for (int row = 0; row < rows; ++row) {
    double* values = matrix + static_cast<std::size_t>(row) * n;
    r.apply(values, rotated.data());
    std::copy(rotated.begin(), rotated.end(), values);
  }
}

void rotate_columns(const sh::Rotation& r, int columns, double* matrix) {
  // Band by band: rows (l, -l..l) of every column are mixed by block(l).
  for (int l = 0; l < r.bands(); ++l) {
    const int width = 2 * l + 1, first = l * l;
    const double* block = r.block(l);
    std::vector<double> band(static_cast<std::size_t>(width) * columns);
    std::copy(matrix + static_cast<std::size_t>(first) * columns, matrix + static_cast<std::size_t>(first + width) * columns,
              band.begin());
    for (int m = 0; m < width; ++m) {
      double* out = matrix + static_cast<std::size_t>(first + m) * columns;
      std::fill(out, out + columns, 0.0);
      for (int k = 0; k < width; ++k) {
        const double b = block[m * width + k];
        if (b == 0.0) continue;
        const double* in = band.data() + static_cast<std::size_t>(k) * columns;
        for (int c = 0; c < columns; ++c) out[c] += b * in[c];
      }
    }
  }
}

namespace {

// Per chunk: sums y_out(w_s) y_in(w_s)^T over v's occluded rays (sample frame), then writes
// M = Rot(F^T) - (2 pi / S) Rot_out(F^T F_s) C Rot_in(F_s^T).
class GlossyDirectWorker : public OccludedSamples<GlossyDirectWorker> {
 public:
  GlossyDirectWorker(const GlossyContext& ctx, std::vector<float>& out)
      : OccludedSamples(*ctx.samples), ctx_(ctx), out_(out), n_in_(ctx.bands * ctx.bands),
        n_out_(ctx.bands_out * ctx.bands_out), per_vertex_(static_cast<std::size_t>(n_out_) * n_in_),
        occluded_sum_(per_vertex_), matrix_(per_vertex_), correction_(per_vertex_) {}

  void clear() { std::fill(occluded_sum_.begin(), occluded_sum_.end(), 0.0f); }
  // The outer product y_out(w_s) y_in(w_s)^T (sample frame).
  void add_occluded(const float* y) {
    for (int row = 0; row < n_out_; ++row) {
      const float a = y[row];
      float* dst = occluded_sum_.data() + static_cast<std::size_t>(row) * n_in_;
      for (int col = 0; col < n_in_; ++col) dst[col] += a * y[col];
    }
  }

  void finish(std::uint32_t v, const glm::mat3& sample_frame) {
    // Unoccluded part: the first n_out rows of Rot(F^T), which takes world coefficients to local ones.
    const glm::dmat3 world_to_local = glm::transpose(glm::dmat3((*ctx_.frames)[v]));
    const sh::Rotation to_local(ctx_.bands, world_to_local);
    std::fill(matrix_.begin(), matrix_.end(), 0.0);
    for (int l = 0; l < ctx_.bands_out; ++l) {
      const int width = 2 * l + 1;
      const double* block = to_local.block(l);
      for (int a = 0; a < width; ++a)
        for (int b = 0; b < width; ++b) matrix_[static_cast<std::size_t>(l * l + a) * n_in_ + l * l + b] = block[a * width + b];
    }
    if (any_occluded()) {
      // Occluded part: Rot_out(F^T F_s) C Rot_in(F_s^T), C in the sample frame F_s.
      const double scale = 2.0 * kPi / static_cast<double>(ctx_.samples->directions.size());  // 1 / (pdf S)
      for (std::size_t i = 0; i < per_vertex_; ++i) correction_[i] = occluded_sum_[i];
      rotate_rows(sh::Rotation(ctx_.bands, glm::dmat3(sample_frame)), n_out_, correction_.data());
      rotate_columns(sh::Rotation(ctx_.bands_out, world_to_local * glm::dmat3(sample_frame)), n_in_, correction_.data());
      for (std::size_t i = 0; i < per_vertex_; ++i) matrix_[i] -= scale * correction_[i];
    }
    float* o = out_.data() + static_cast<std::size_t>(v) * per_vertex_;
    for (std::size_t i = 0; i < per_vertex_; ++i) o[i] = static_cast<float>(matrix_[i]);
  }

 private:
  const GlossyContext& ctx_;
  std::vector<float>& out_;
  int n_in_, n_out_;
  std::size_t per_vertex_;
  std::vector<float> occluded_sum_;
  std::vector<double> matrix_, correction_;
};

}  // namespace

std::uint64_t glossy_direct_pass(const GlossyContext& ctx, std::vector<float>& out) {
  const std::size_t per_vertex = static_cast<std::size_t>(ctx.bands_out * ctx.bands_out) * (ctx.bands * ctx.bands);
  out.assign(ctx.mesh->positions.size() * per_vertex, 0.0f);
  Progress progress("bake glossy shadowed", "vertices", ctx.mesh->positions.size(), ctx.progress);
  return trace::trace_vertex_rays(ctx.rays(trace::Query::occluded), progress, [&] { return GlossyDirectWorker(ctx, out); });
}

}  // namespace prt::bake
