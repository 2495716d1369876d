// Interreflection passes of a glossy bake (Sloan, Kautz and Snyder 2002, section 5; bake.h, GLOSSY).
#include <algorithm>
#include <atomic>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "bake/glossy_passes.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "sh/basis.h"

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

// P_q,c = B_c M_q,c for every vertex q and channel c: the map from world lighting to the outgoing
// radiance coefficients of q (local frame), rows restricted to `rows`. Layout: vertex-major,
// channel-major, [rows.size()][n_in].
void outgoing_matrices(const GlossyContext& ctx, const brdf::BrdfMatrix& b, int channels, const std::vector<int>& rows,
                       const std::vector<float>& transfer, std::vector<float>& out) {
  const int n_in = ctx.bands * ctx.bands, n_out = ctx.bands_out * ctx.bands_out;
  const std::size_t matrix_size = static_cast<std::size_t>(n_out) * n_in;
  const std::size_t block = rows.size() * static_cast<std::size_t>(n_in);
  const std::size_t vertices = ctx.mesh->positions.size();
  out.assign(vertices * channels * block, 0.0f);
  parallel_for(vertices, 256, ctx.threads, [&](std::size_t begin, std::size_t end) {
    std::vector<double> row_sum(static_cast<std::size_t>(n_in));
    for (std::size_t q = begin; q < end; ++q)
      for (int c = 0; c < channels; ++c) {
        const double* bc = b.channel(b.channels == 1 ? 0 : c);
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

}  // namespace

std::uint64_t glossy_bounce_pass(const GlossyContext& ctx, const brdf::BrdfMatrix& brdf_matrix, int channels,
                                 const std::vector<float>& prev, std::vector<float>& next, const char* label) {
  const mesh::Mesh& mesh = *ctx.mesh;
  const LocalSampleSet& set = *ctx.samples;
  const int n_in = ctx.bands * ctx.bands, n_out = ctx.bands_out * ctx.bands_out;
  const std::size_t matrix_size = static_cast<std::size_t>(n_out) * n_in;
  const std::size_t stride = matrix_size * channels;
  const std::size_t sample_count = set.directions.size();
  const double scale = 2.0 * M_PI / static_cast<double>(sample_count);
  const std::vector<int> rows = nonzero_rows(ctx.bands_out);
  const std::size_t block = rows.size() * static_cast<std::size_t>(n_in);
  std::vector<float> outgoing;
  outgoing_matrices(ctx, brdf_matrix, channels, rows, prev, outgoing);
  next.assign(prev.size(), 0.0f);
  Progress progress(label, "vertices", mesh.positions.size(), ctx.progress);
  std::atomic<std::uint64_t> rays{0};

  parallel_for(ctx.order->size(), 64, ctx.threads, [&](std::size_t begin, std::size_t end) {
    trace::RayBatch batch(std::min<std::size_t>(sample_count, trace::kDefaultBatchCapacity));
    std::vector<float> gathered(stride), radiance_row(static_cast<std::size_t>(channels) * n_in), y_corner(static_cast<std::size_t>(n_out));
    std::vector<double> matrix(matrix_size);
    std::uint64_t traced = 0;
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t v = (*ctx.order)[k];
      const glm::mat3 sample_frame = vertex_frame(mesh.normals[v], ctx.seed, v);
      const glm::vec3 origin = ctx.scene->offset_origin(mesh.positions[v], mesh.normals[v]);
      std::fill(gathered.begin(), gathered.end(), 0.0f);
      bool any_hit = false;
      for (std::size_t first = 0; first < sample_count; first += batch.capacity()) {
        const std::size_t count = std::min(batch.capacity(), sample_count - first);
        batch.clear();
        for (std::size_t s = first; s < first + count; ++s) batch.push(origin, sample_frame * set.directions[s]);
        ctx.scene->intersect(batch);
        traced += count;
        for (std::size_t i = 0; i < count; ++i) {
          const trace::HitResult hit = batch.hit(i);
          if (!hit.hit()) continue;
          const std::uint32_t* tri = mesh.indices.data() + 3 * static_cast<std::size_t>(hit.prim_id);
          const trace::Ray& ray = batch.data()[i].ray;
          const glm::vec3 dir(ray.dir_x, ray.dir_y, ray.dir_z);
          if (glm::dot(hit.ng, dir) >= 0.0f) continue;  // back face: black (single-sided surfaces)
          any_hit = true;
          // Radiance row toward v: sum over corners c of bary_c sum_k y_k(F_c^T (-dir)) P_c[k, :].
          std::fill(radiance_row.begin(), radiance_row.end(), 0.0f);
          const float bary[3] = {1.0f - hit.u - hit.v, hit.u, hit.v};
          for (int corner = 0; corner < 3; ++corner) {
            if (bary[corner] == 0.0f) continue;
            const std::uint32_t q = tri[corner];
            const glm::vec3 toward = glm::transpose((*ctx.frames)[q]) * (-dir);
            sh::eval(ctx.bands_out, toward, y_corner.data());
            for (int c = 0; c < channels; ++c) {
              const float* p = outgoing.data() + (static_cast<std::size_t>(q) * channels + c) * block;
              float* dst = radiance_row.data() + static_cast<std::size_t>(c) * n_in;
              for (std::size_t r = 0; r < rows.size(); ++r) {
                const float w = bary[corner] * y_corner[rows[r]];
                const float* prow = p + r * n_in;
                for (int col = 0; col < n_in; ++col) dst[col] += w * prow[col];
              }
            }
          }
          // Outer product with y_out(w_s) (sample frame).
          const float* y = set.basis.data() + (first + i) * n_in;
          for (int c = 0; c < channels; ++c) {
            const float* src = radiance_row.data() + static_cast<std::size_t>(c) * n_in;
            for (int row = 0; row < n_out; ++row) {
              const float a = y[row];
              float* dst = gathered.data() + c * matrix_size + static_cast<std::size_t>(row) * n_in;
              for (int col = 0; col < n_in; ++col) dst[col] += a * src[col];
            }
          }
        }
      }
      if (!any_hit) continue;
      // Rows from the sample frame to the vertex frame: Rot_out(F^T F_s); columns are already world.
      const glm::dmat3 world_to_local = glm::transpose(glm::dmat3((*ctx.frames)[v]));
      const sh::Rotation rows_to_local(ctx.bands_out, world_to_local * glm::dmat3(sample_frame));
      float* o = next.data() + static_cast<std::size_t>(v) * stride;
      for (int c = 0; c < channels; ++c) {
        for (std::size_t i = 0; i < matrix_size; ++i) matrix[i] = scale * gathered[c * matrix_size + i];
        rotate_columns(rows_to_local, n_in, matrix.data());
        for (std::size_t i = 0; i < matrix_size; ++i) o[c * matrix_size + i] = static_cast<float>(matrix[i]);
      }
    }
    rays += traced;
    progress.advance(end - begin);
  });
  progress.finish();
  return rays.load();
}

}  // namespace prt::bake
