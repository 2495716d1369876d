#include "lightmap/denoise.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numeric>

#include <glm/geometric.hpp>

#include "core/big_buffer.h"
#include "core/constants.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/parallel.h"
#include "lightmap/charts.h"

namespace prt::lightmap {

namespace {

// Rows per parallel chunk: every texel's output depends only on the previous iteration, so the split
// does not change the bytes.
constexpr std::size_t kRowGrain = 4;

// x^p for x in [0, 1]: repeated squaring for integer p (exact and fast), else exp(p log x).
float power01(float x, float p, bool integer) {
  if (x <= 0.0f) return p == 0.0f ? 1.0f : 0.0f;
  if (!integer) return std::exp(p * std::log(x));
  float result = 1.0f, base = x;
  for (unsigned e = unsigned(p); e; e >>= 1) {
    if (e & 1u) result *= base;
    base *= base;
  }
  return result;
}

struct Grid {
  const DenoiseGuides& g;
  bool same_chart(std::size_t p, long i, long j) const {
    if (i < 0 || j < 0 || i >= g.width || j >= g.height) return false;
    const std::size_t q = std::size_t(i) + std::size_t(j) * std::size_t(g.width);
    return g.covered[q] && g.chart[q] == g.chart[p];
  }
};

// In 8 lanes (c mod 8) summed at the end: a fixed order the compiler can vectorise.
float squared_distance(const float* a, const float* b, std::size_t stride) {
  float lane[8] = {};
  std::size_t c = 0;
  for (; c + 8 <= stride; c += 8)
    for (std::size_t k = 0; k < 8; ++k) lane[k] += (a[c + k] - b[c + k]) * (a[c + k] - b[c + k]);
  for (std::size_t k = 0; c < stride; ++c, ++k) lane[k] += (a[c] - b[c]) * (a[c] - b[c]);
  return ((lane[0] + lane[1]) + (lane[2] + lane[3])) + ((lane[4] + lane[5]) + (lane[6] + lane[7]));
}

// The element of rank n / 2 of values[0..n) in ascending order (n <= 25): the value std::nth_element
// gives, found without branches on the data: the element with n / 2 elements before it, counting
// smaller ones and, among equal ones, those at smaller indices.
float median_of(const std::array<float, 25>& values, std::size_t n) {
  const std::size_t rank = n / 2;
  float found = values[0];
  for (std::size_t a = 0; a < n; ++a) {
    std::size_t before = 0;
    for (std::size_t b = 0; b < n; ++b)
      before += std::size_t(values[b] < values[a]) + std::size_t(b < a && values[b] == values[a]);
    if (before == rank) found = values[a];
  }
  return found;
}

// The initial noise variance of each covered texel's transfer vector (denoise.h): the median over p's
// 5 x 5 chart window of the squared norm of each texel's difference from the mean of its chart's 3 x 3
// neighbours, corrected for the mean's share of the noise (x k / (k - 1) for k texels).
std::vector<float> initial_variance(const std::vector<float>& values, std::size_t stride, const DenoiseGuides& g, int threads) {
  const Grid grid{g};
  const std::size_t w = std::size_t(g.width);
  std::vector<float> residual(g.covered.size(), -1.0f), variance(g.covered.size(), 0.0f);
  parallel_for(std::size_t(g.height), kRowGrain, threads, [&](std::size_t begin, std::size_t end) {
    std::vector<double> mean(stride);
    for (std::size_t j = begin; j < end; ++j)
      for (std::size_t i = 0; i < w; ++i) {
        const std::size_t p = i + j * w;
        if (!g.covered[p]) continue;
        std::fill(mean.begin(), mean.end(), 0.0);
        int k = 0;
        for (long dj = -1; dj <= 1; ++dj)
          for (long di = -1; di <= 1; ++di)
            if (grid.same_chart(p, long(i) + di, long(j) + dj)) {
              const float* q = values.data() + std::size_t(long(p) + di + dj * long(w)) * stride;
              for (std::size_t c = 0; c < stride; ++c) mean[c] += q[c];
              ++k;
            }
        if (k < 2) continue;
        double r2 = 0.0;
        for (std::size_t c = 0; c < stride; ++c) {
          const double r = values[p * stride + c] - mean[c] / k;
          r2 += r * r;
        }
        residual[p] = float(r2 * k / (k - 1));
      }
  });
  parallel_for(std::size_t(g.height), kRowGrain, threads, [&](std::size_t begin, std::size_t end) {
    std::array<float, 25> window;
    for (std::size_t j = begin; j < end; ++j)
      for (std::size_t i = 0; i < w; ++i) {
        const std::size_t p = i + j * w;
        if (!g.covered[p]) continue;
        std::size_t k = 0;
        for (long dj = -2; dj <= 2; ++dj)
          for (long di = -2; di <= 2; ++di)
            if (grid.same_chart(p, long(i) + di, long(j) + dj)) {
              const float r = residual[std::size_t(long(p) + di + dj * long(w))];
              if (r >= 0.0f) window[k++] = r;
            }
        if (k > 0) variance[p] = median_of(window, k);
      }
  });
  return variance;
}

// Turns the weights w of taps at grid offsets (in steps) into the equivalent kernel of a weighted local
// linear fit T(q) ~ a + b . offset, evaluated at the centre (a): w_q (c0 + c1 dx + c2 dy) with
// c = M^-1 e0, M = sum w [1 dx dy]^T [1 dx dy] + ridge sum w on the slopes (against collinear taps, and
// a pull towards the weighted mean where one-sided taps would extrapolate noise),
// renormalised to sum 1. A weighted mean is biased by one-sided neighbourhoods (a chart border, a
// contact line, taps cut off by the range weight) wherever the transfer has a gradient; the linear
// fit is not, for gradients that are linear over the taps.
void local_linear(int n, const std::array<glm::vec2, 9>& offsets, std::array<float, 9>& w, double ridge) {
  double m[3][3] = {};
  for (int k = 0; k < n; ++k) {
    const double x[3] = {1.0, offsets[std::size_t(k)].x, offsets[std::size_t(k)].y};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) m[a][b] += w[std::size_t(k)] * x[a] * x[b];
  }
  m[1][1] += ridge * m[0][0];
  m[2][2] += ridge * m[0][0];
  // First column of the inverse of the symmetric 3 x 3 matrix (cofactors / determinant).
  const double c0 = m[1][1] * m[2][2] - m[1][2] * m[2][1], c1 = m[1][2] * m[2][0] - m[1][0] * m[2][2],
               c2 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
  const double det = m[0][0] * c0 + m[0][1] * c1 + m[0][2] * c2;
  if (!(std::abs(det) > 1e-12 * m[0][0] * m[0][0] * m[0][0])) return;  // keep the weighted mean
  double sum = 0.0;
  std::array<double, 9> out{};
  for (int k = 0; k < n; ++k) {
    out[std::size_t(k)] = w[std::size_t(k)] * (c0 + c1 * offsets[std::size_t(k)].x + c2 * offsets[std::size_t(k)].y) / det;
    sum += out[std::size_t(k)];
  }
  for (int k = 0; k < n; ++k) w[std::size_t(k)] = float(out[std::size_t(k)] / sum);
}

// d = sum over the 9 slots of w[slot] centre[(di step + dj row) floats] (slot 3 (dj + 1) + di + 1; a zero
// weight reads nothing), in slot order. kStride > 0: `stride` == kStride, the sum held in registers
// across the slots (the same float operations).
template <std::size_t kStride>
void weighted_sum_fixed(const float* centre, float* d, const float* w, long step, long row, std::size_t stride) {
  const std::size_t n = kStride > 0 ? kStride : stride;
  float held[kStride > 0 ? kStride : 1];
  float* acc = kStride > 0 ? held : d;
  for (std::size_t c = 0; c < n; ++c) acc[c] = w[4] * centre[c];  // the centre is always a tap
  for (int slot = 0; slot < 9; ++slot) {
    if (slot == 4 || w[slot] == 0.0f) continue;
    const float* s = centre + ((slot % 3) - 1) * step + ((slot / 3) - 1) * row;
    const float ws = w[slot];
    for (std::size_t c = 0; c < n; ++c) acc[c] += ws * s[c];
  }
  if (kStride > 0) std::copy_n(held, n, d);
}

// out[p] = sum over the 9 slots of w[slot] in[p + step (di + dj width)], in slot order: the same float
// operations whichever thread runs p.
void weighted_sum(const std::vector<float>& in, std::vector<float>& out, std::size_t p, const float* w, long step, int width,
                  std::size_t stride) {
  float* d = out.data() + p * stride;
  const float* centre = in.data() + p * stride;
  const long step_floats = step * long(stride), row_floats = step_floats * long(width);
  switch (stride) {
    case 25: return weighted_sum_fixed<25>(centre, d, w, step_floats, row_floats, stride);
    case 75: return weighted_sum_fixed<75>(centre, d, w, step_floats, row_floats, stride);
    default: return weighted_sum_fixed<0>(centre, d, w, step_floats, row_floats, stride);
  }
}

// The normalised tap weights of every level, 9 per covered texel (slot 3 (dj + 1) + di + 1, 0 for no
// tap), covered texels only, in row-major order: a level's weights of the texels of row j start at
// row_first[j] x 9.
struct StoredWeights {
  std::vector<std::size_t> row_first;  // covered texels before each row; height + 1 entries
  std::unique_ptr<float[]> data;       // written by each level at every covered texel before it is read

  StoredWeights(const DenoiseGuides& g, int levels) : row_first(std::size_t(g.height) + 1, 0) {
    const std::size_t width = std::size_t(g.width);
    for (std::size_t j = 0; j < std::size_t(g.height); ++j)
      row_first[j + 1] = row_first[j] + std::size_t(std::count_if(g.covered.begin() + std::ptrdiff_t(j * width),
                                                                   g.covered.begin() + std::ptrdiff_t((j + 1) * width),
                                                                   [](std::uint8_t c) { return c != 0; }));
    const std::size_t floats = row_first.back() * 9 * std::size_t(levels);
    data.reset(new float[floats]);  // uninitialised: no pass over it
    advise_huge_pages(data.get(), floats * sizeof(float));
  }
  // The first weight of `level` for row j.
  float* row(int level, std::size_t j) const { return data.get() + (std::size_t(level) * row_first.back() + row_first[j]) * 9; }
};

struct Iteration {
  const DenoiseGuides& g;
  const DenoiseOptions& o;
  long step;
  float level_floor;  // value_floor x floor_decay^level
  const std::vector<float>& variance;

  // The taps' weights of covered texel p at (i, j), from `in` (the previous iteration); returns how
  // many taps (q indices in `taps`).
  int weights(const std::vector<float>& in, std::size_t stride, std::size_t p, long i, long j, std::array<std::size_t, 9>& taps,
              std::array<float, 9>& w, std::array<int, 9>& slots) const {
    std::array<glm::vec2, 9> offsets;
    static constexpr float h[3] = {0.25f, 0.5f, 0.25f};
    constexpr long r = 1;
    const Grid grid{g};
    const bool integer = o.normal_power == std::floor(o.normal_power) && o.normal_power <= 1024.0f;
    const float plane = o.plane_sigma * g.size[p];
    const float inv_plane2 = plane > 0.0f ? 1.0f / (plane * plane) : 0.0f;
    const float* tp = in.data() + p * stride;
    const float norm2 = level_floor * level_floor * std::inner_product(tp, tp + stride, tp, 0.0f) + 1e-30f;
    const bool value_weight = !std::isinf(o.value_sigma);
    int n = 0;
    for (long dj = -r; dj <= r; ++dj)
      for (long di = -r; di <= r; ++di) {
        if (!grid.same_chart(p, i + di * step, j + dj * step)) continue;
        const std::size_t q = std::size_t(long(p) + (di + dj * long(g.width)) * step);
        if (q == p) {
          slots[std::size_t(n)] = int(3 * (dj + r) + di + r);
          taps[std::size_t(n)] = q;
          offsets[std::size_t(n)] = {0.0f, 0.0f};
          w[std::size_t(n++)] = h[r] * h[r];  // the centre always counts fully
          continue;
        }
        const float d_plane = glm::dot(g.normal[p], g.position[q] - g.position[p]);
        float exponent = d_plane * d_plane * inv_plane2;
        if (value_weight) {
          const float noise = variance[p] + variance[q];
          const float signal2 = std::max(0.0f, squared_distance(tp, in.data() + q * stride, stride) - noise);
          exponent += signal2 / (o.value_sigma * o.value_sigma * noise + norm2);
        }
        const float wq = h[di + r] * h[dj + r] * power01(glm::dot(g.normal[p], g.normal[q]), o.normal_power, integer) *
                         std::exp(-exponent);
        if (!(wq > 0.0f)) continue;
        slots[std::size_t(n)] = int(3 * (dj + r) + di + r);
        taps[std::size_t(n)] = q;
        offsets[std::size_t(n)] = {float(di), float(dj)};
        w[std::size_t(n++)] = wq;
      }
    if (o.linear) local_linear(n, offsets, w, o.slope_ridge);
    return n;
  }

  // One level (`level`): out = the filtered `in` (and bounce_out of bounce_in), next_variance, and each
  // covered texel's normalised weights in `stored`.
  void apply(const std::vector<float>& in, std::vector<float>& out, const std::vector<float>* bounce_in,
             std::vector<float>* bounce_out, std::size_t stride, std::vector<float>& next_variance, const StoredWeights& stored,
             int level) const {
    const std::size_t width = std::size_t(g.width);
    parallel_for(std::size_t(g.height), kRowGrain, o.threads, [&](std::size_t begin, std::size_t end) {
      std::array<std::size_t, 9> taps{};
      std::array<float, 9> w{};
      std::array<int, 9> slots{};
      float* slot_w = stored.row(level, begin);
      for (std::size_t j = begin; j < end; ++j)
        for (std::size_t i = 0; i < width; ++i) {
          const std::size_t p = i + j * width;
          if (!g.covered[p]) continue;
          const int n = weights(in, stride, p, long(i), long(j), taps, w, slots);
          float sum = 0.0f, var = 0.0f;
          for (int k = 0; k < n; ++k) {
            sum += w[std::size_t(k)];
            var += w[std::size_t(k)] * w[std::size_t(k)] * variance[taps[std::size_t(k)]];
          }
          const float inv_sum = 1.0f / sum;
          next_variance[p] = var * inv_sum * inv_sum;
          std::fill(slot_w, slot_w + 9, 0.0f);
          for (int k = 0; k < n; ++k) slot_w[slots[std::size_t(k)]] = w[std::size_t(k)] * inv_sum;
          weighted_sum(in, out, p, slot_w, step, g.width, stride);
          if (bounce_in) weighted_sum(*bounce_in, *bounce_out, p, slot_w, step, g.width, stride);
          slot_w += 9;
        }
    });
  }
};

// Applies the stored weights of one level (Iteration::apply) to `in`, into `out`.
void apply_stored(const DenoiseGuides& g, const StoredWeights& stored, int level, const std::vector<float>& in, std::vector<float>& out,
                  std::size_t stride, int threads) {
  const std::size_t width = std::size_t(g.width);
  parallel_for(std::size_t(g.height), kRowGrain, threads, [&](std::size_t begin, std::size_t end) {
    const float* slot_w = stored.row(level, begin);
    for (std::size_t p = begin * width; p < end * width; ++p)
      if (g.covered[p]) {
        weighted_sum(in, out, p, slot_w, 1L << level, g.width, stride);
        slot_w += 9;
      }
  });
}

}  // namespace

namespace {

// Twicing (Tukey, "Exploratory Data Analysis", 1977): smooth += twicing x S (input - smooth), S the
// levels whose weights are `stored`. `input` and `scratch` are overwritten.
void twice(std::vector<float>& smooth, std::vector<float>& input, std::vector<float>& scratch, std::size_t stride,
           const DenoiseGuides& g, const StoredWeights& stored, const DenoiseOptions& o) {
  for (std::size_t k = 0; k < input.size(); ++k) input[k] -= smooth[k];
  for (int it = 0; it < o.iterations; ++it) {
    apply_stored(g, stored, it, input, scratch, stride, o.threads);
    input.swap(scratch);
  }
  for (std::size_t t = 0; t < g.covered.size(); ++t)
    if (g.covered[t])
      for (std::size_t c = 0; c < stride; ++c) smooth[t * stride + c] += o.twicing * input[t * stride + c];
}

}  // namespace

DenoiseGuides denoise_guides(const mesh::Mesh& mesh, const TexelSamples& samples) {
  DenoiseGuides g;
  g.width = samples.width;
  g.height = samples.height;
  const std::size_t texels = std::size_t(g.width) * std::size_t(g.height);
  g.covered.assign(texels, 0);
  g.position.assign(texels, glm::vec3(0.0f));
  g.normal.assign(texels, glm::vec3(0.0f));
  g.size.assign(texels, 0.0f);
  g.chart.assign(texels, 0);
  const std::vector<std::uint32_t> charts = triangle_charts(mesh);
  const std::vector<float> sizes = texel_world_sizes(mesh, g.width, g.height);
  for (const TexelSample& s : samples.samples) {
    g.covered[s.texel] = 1;
    g.position[s.texel] = s.position;
    g.normal[s.texel] = s.normal;
    g.size[s.texel] = sizes[s.triangle];
    g.chart[s.texel] = charts[s.triangle];
  }
  return g;
}

int interleaved_tile_bits(int sample_count) {
  int bits = 0;
  while (bits < 4 && (std::uint64_t(sample_count) << (2 * (bits + 1))) <= (std::uint64_t(1) << 18)) ++bits;
  return bits;
}

namespace {

// The set texel (i, j) traces (denoise.h, interleaved_sampling): the bit-reversed Bayer index of
// (i xor j, i) within its tile, xor the tile's hash.
struct TileSets {
  std::uint32_t bits, side, tiles_across;
  std::uint32_t seed;
  std::uint8_t operator()(std::uint32_t i, std::uint32_t j) const {
    const std::uint32_t x = (i ^ j) % side, y = i % side;
    std::uint32_t set = 0;
    for (std::uint32_t b = 0; b < bits; ++b) set |= (((x >> b) & 1u) << (2 * b)) | (((y >> b) & 1u) << (2 * b + 1));
    // XOR with a constant maps every aligned block of consecutive sets onto another one.
    const double tile = hash_to_unit(seed, std::uint64_t(i / side) + std::uint64_t(j / side) * tiles_across, 0x5e7);
    return std::uint8_t(set ^ std::uint32_t(tile * double(side * side)));
  }
};

// The covered texel that traces the set of empty texel (i, j): its first covered neighbour, the four
// edge neighbours before the four corners; -1 if none.
std::int64_t adopting_sample(const std::vector<std::int64_t>& sample_at, std::uint32_t width, std::uint32_t height,
                             std::uint32_t i, std::uint32_t j) {
  static constexpr int kSteps[8][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}, {-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
  for (const auto& step : kSteps) {
    const std::int64_t x = std::int64_t(i) + step[0], y = std::int64_t(j) + step[1];
    if (x < 0 || y < 0 || x >= std::int64_t(width) || y >= std::int64_t(height)) continue;
    const std::int64_t k = sample_at[std::size_t(x + y * std::int64_t(width))];
    if (k >= 0) return k;
  }
  return -1;
}

}  // namespace

InterleavedSampling interleaved_sampling(const TexelSamples& samples, int sample_count, std::uint32_t seed) {
  InterleavedSampling out;
  out.tile_bits = interleaved_tile_bits(sample_count);
  const std::uint32_t bits = std::uint32_t(out.tile_bits), side = 1u << bits;
  const std::uint32_t width = std::uint32_t(std::max(samples.width, 1)), height = std::uint32_t(std::max(samples.height, 1));
  const TileSets sets{bits, side, (width + side - 1) / side, seed};
  out.set.reserve(samples.samples.size());
  std::vector<std::int64_t> sample_at(std::size_t(width) * height, -1);
  for (std::size_t k = 0; k < samples.samples.size(); ++k) {
    const std::uint32_t t = samples.samples[k].texel;
    out.set.push_back(sets(t % width, t / width));
    sample_at[t] = std::int64_t(k);
  }
  // Empty texels next to covered ones: their sets, traced by a covered neighbour (extra points).
  for (std::uint32_t j = 0; j < height; ++j)
    for (std::uint32_t i = 0; i < width; ++i) {
      if (sample_at[std::size_t(i) + std::size_t(j) * width] >= 0) continue;
      const std::int64_t k = adopting_sample(sample_at, width, height, i, j);
      if (k < 0) continue;
      out.set.push_back(sets(i, j));
      out.extra_sample.push_back(std::uint32_t(k));
    }
  return out;
}

std::size_t add_contact_sets(const TexelSamples& samples, const std::vector<float>& dc, InterleavedSampling& sampling) {
  if (sampling.tile_bits == 0) return 0;
  const int width = samples.width, height = samples.height;
  const auto covered = [&](int i, int j) {
    return i >= 0 && j >= 0 && i < width && j < height && samples.coverage[std::size_t(i) + std::size_t(j) * std::size_t(width)] != 0;
  };
  constexpr double kY00 = 0.28209479177387814;  // 1 / (2 sqrt(pi)): g of an unoccluded point
  const float limit = kContactContrast * float(kY00);
  const std::uint8_t top = std::uint8_t(1u << (2 * sampling.tile_bits - 1)), flips[kContactSets] = {top, std::uint8_t(top >> 1),
                                                                                                     std::uint8_t(top | (top >> 1))};
  std::size_t texels = 0;
  for (std::size_t k = 0; k < samples.samples.size(); ++k) {
    const int i = int(samples.samples[k].texel % std::uint32_t(width)), j = int(samples.samples[k].texel / std::uint32_t(width));
    bool steep = false;
    for (const auto& [di, dj] : {std::pair{2, 0}, std::pair{0, 2}}) {
      if (!covered(i + di, j + dj) || !covered(i - di, j - dj)) continue;
      const float a = dc[std::size_t(i + di) + std::size_t(j + dj) * std::size_t(width)],
                  b = dc[std::size_t(i - di) + std::size_t(j - dj) * std::size_t(width)];
      steep |= std::abs(a - b) > limit;
    }
    if (!steep) continue;
    ++texels;
    for (const std::uint8_t flip : flips) {
      sampling.set.push_back(std::uint8_t(sampling.set[k] ^ flip));
      sampling.extra_sample.push_back(std::uint32_t(k));
    }
  }
  return texels;
}

void validate_denoise_options(const DenoiseOptions& o) {
  if (o.iterations < 0 || o.iterations > 12) fail_option("iterations", " " + std::to_string(o.iterations) + " is out of range 0..12");
  if (!(o.plane_sigma > 0.0f)) fail_option("plane_sigma", " " + std::to_string(o.plane_sigma) + " must be > 0");
  if (!(o.normal_power >= 0.0f) || std::isinf(o.normal_power))
    fail_option("normal_power", " " + std::to_string(o.normal_power) + " must be finite and >= 0");
  if (!(o.value_sigma > 0.0f)) fail_option("value_sigma", " " + std::to_string(o.value_sigma) + " must be > 0");
  if (!(o.twicing >= 0.0f && o.twicing <= 1.0f)) fail_option("twicing", " " + std::to_string(o.twicing) + " is out of range 0..1");
  if (!(o.floor_decay > 0.0f && o.floor_decay <= 1.0f)) fail_option("floor_decay", " " + std::to_string(o.floor_decay) + " is out of range (0, 1]");
  if (!(o.slope_ridge >= 1e-3f && o.slope_ridge <= 10.0f)) fail_option("slope_ridge", " " + std::to_string(o.slope_ridge) + " is out of range 0.001..10");
  if (!(o.value_floor >= 0.0f) || std::isinf(o.value_floor))
    fail_option("value_floor", " " + std::to_string(o.value_floor) + " must be finite and >= 0");
}

void denoise_texels(std::vector<float>& values, std::vector<float>& bounce_only, std::size_t stride,
                    const DenoiseGuides& guides, const DenoiseOptions& options, const std::vector<float>* noise) {
  validate_denoise_options(options);
  if (options.iterations == 0 || stride == 0) return;
  const bool bounce = !bounce_only.empty();
  // Twicing keeps the input: the residual input - S input is filtered by the same levels S.
  // The copies are full-size, written at once: huge pages (core/big_buffer.h).
  std::vector<float> residual = options.twicing > 0.0f ? copy_big(values) : std::vector<float>(),
                     residual_bounce = options.twicing > 0.0f ? copy_big(bounce_only) : std::vector<float>();
  std::vector<float> next_values = copy_big(values), next_bounce = copy_big(bounce_only);
  std::vector<float> variance = noise ? *noise : initial_variance(values, stride, guides, options.threads), next_variance = variance;
  const StoredWeights stored(guides, options.iterations);
  for (int it = 0; it < options.iterations; ++it) {
    const Iteration iteration{guides, options, 1L << it, options.value_floor * std::pow(options.floor_decay, float(it)), variance};
    iteration.apply(values, next_values, bounce ? &bounce_only : nullptr, bounce ? &next_bounce : nullptr, stride, next_variance,
                    stored, it);
    values.swap(next_values);
    if (bounce) bounce_only.swap(next_bounce);
    variance.swap(next_variance);
  }
  if (options.twicing > 0.0f) {
    twice(values, residual, next_values, stride, guides, stored, options);
    if (bounce) twice(bounce_only, residual_bounce, next_bounce, stride, guides, stored, options);
  }
}

}  // namespace prt::lightmap
