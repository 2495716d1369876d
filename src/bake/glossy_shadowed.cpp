// The direct pass of a glossy bake: per-vertex transfer matrices with binary visibility (bake.h, GLOSSY).
#include <algorithm>
#include <atomic>
#include <cmath>

#include <glm/matrix.hpp>

#include "bake/glossy_passes.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "sh/basis.h"
#include "sh/sampling.h"

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

std::uint64_t glossy_direct_pass(const GlossyContext& ctx, std::vector<float>& out) {
  const mesh::Mesh& mesh = *ctx.mesh;
  const LocalSampleSet& set = *ctx.samples;
  const int n_in = ctx.bands * ctx.bands, n_out = ctx.bands_out * ctx.bands_out;
  const std::size_t per_vertex = static_cast<std::size_t>(n_out) * n_in;
  const std::size_t sample_count = set.directions.size();
  const double scale = 2.0 * M_PI / static_cast<double>(sample_count);  // 1 / (pdf S), uniform pdf 1 / (2 pi)
  out.assign(mesh.positions.size() * per_vertex, 0.0f);
  Progress progress("bake glossy shadowed", "vertices", mesh.positions.size(), ctx.progress);
  std::atomic<std::uint64_t> rays{0};

  parallel_for(ctx.order->size(), 64, ctx.threads, [&](std::size_t begin, std::size_t end) {
    trace::RayBatch batch(std::min<std::size_t>(sample_count, trace::kDefaultBatchCapacity));
    std::vector<float> occluded_sum(per_vertex);
    std::vector<double> matrix(per_vertex), correction(per_vertex);
    std::uint64_t traced = 0;
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t v = (*ctx.order)[k];
      const glm::mat3 sample_frame = vertex_frame(mesh.normals[v], ctx.seed, v);
      const glm::mat3& frame = (*ctx.frames)[v];
      const glm::vec3 origin = ctx.scene->offset_origin(mesh.positions[v], mesh.normals[v]);
      std::fill(occluded_sum.begin(), occluded_sum.end(), 0.0f);
      bool any_occluded = false;
      for (std::size_t first = 0; first < sample_count; first += batch.capacity()) {
        const std::size_t count = std::min(batch.capacity(), sample_count - first);
        batch.clear();
        for (std::size_t s = first; s < first + count; ++s) batch.push(origin, sample_frame * set.directions[s]);
        ctx.scene->occluded(batch);
        traced += count;
        for (std::size_t i = 0; i < count; ++i) {
          if (!batch.is_occluded(i)) continue;
          any_occluded = true;
          // Accumulate the outer product y_out(w_s) y_in(w_s)^T (sample frame).
          const float* y = set.basis.data() + (first + i) * n_in;
          for (int row = 0; row < n_out; ++row) {
            const float a = y[row];
            float* dst = occluded_sum.data() + static_cast<std::size_t>(row) * n_in;
            for (int col = 0; col < n_in; ++col) dst[col] += a * y[col];
          }
        }
      }
      // Unoccluded part: the first n_out rows of Rot(F^T), which takes world coefficients to local ones.
      const glm::dmat3 world_to_local = glm::transpose(glm::dmat3(frame));
      const sh::Rotation to_local(ctx.bands, world_to_local);
      std::fill(matrix.begin(), matrix.end(), 0.0);
      for (int l = 0; l < ctx.bands_out; ++l) {
        const int width = 2 * l + 1;
        const double* block = to_local.block(l);
        for (int a = 0; a < width; ++a)
          for (int b = 0; b < width; ++b) matrix[static_cast<std::size_t>(l * l + a) * n_in + l * l + b] = block[a * width + b];
      }
      if (any_occluded) {
        // Occluded part: Rot_out(F^T F_s) C Rot_in(F_s^T), C in the sample frame F_s.
        for (std::size_t i = 0; i < per_vertex; ++i) correction[i] = occluded_sum[i];
        rotate_rows(sh::Rotation(ctx.bands, glm::dmat3(sample_frame)), n_out, correction.data());
        rotate_columns(sh::Rotation(ctx.bands_out, world_to_local * glm::dmat3(sample_frame)), n_in, correction.data());
        for (std::size_t i = 0; i < per_vertex; ++i) matrix[i] -= scale * correction[i];
      }
      float* o = out.data() + static_cast<std::size_t>(v) * per_vertex;
      for (std::size_t i = 0; i < per_vertex; ++i) o[i] = static_cast<float>(matrix[i]);
    }
    rays += traced;
    progress.advance(end - begin);
  });
  progress.finish();
  return rays.load();
}

}  // namespace prt::bake
