#include "bake/vertex_samples.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "sh/basis.h"
#include "sh/sampling.h"

namespace prt::bake {

namespace {

LocalSampleSet sample_set_from(const std::vector<glm::dvec3>& dirs, int bands) {
  LocalSampleSet set;
  set.bands = bands;
  const int n = bands * bands;
  set.directions.resize(dirs.size());
  set.basis.resize(dirs.size() * static_cast<std::size_t>(n));
  std::vector<double> y(static_cast<std::size_t>(n));
  for (std::size_t s = 0; s < dirs.size(); ++s) {
    set.directions[s] = glm::vec3(dirs[s]);
    sh::eval(bands, dirs[s], y.data());
    for (int i = 0; i < n; ++i) set.basis[s * n + i] = static_cast<float>(y[i]);
  }
  return set;
}

// Rays listed at a time by occluded_list.
constexpr std::size_t kListLength = 256;

// Writes the offsets i - begin of the rays i in [begin, end) (at most kListLength) that `batch`
// reports occluded to `list`, in ray order, and returns their number: one store per ray and no branch
// (in a closed room 3/4 of the rays are occluded, in no pattern a branch predictor could learn).
std::size_t occluded_list(const trace::RayBatch& batch, std::size_t begin, std::size_t end, std::uint16_t* list) {
  std::size_t count = 0;
  for (std::size_t i = begin; i < end; ++i) {
    list[count] = static_cast<std::uint16_t>(i - begin);
    count += batch.is_occluded(i) ? 1 : 0;
  }
  return count;
}

// Lists the occluded rays of `batch` kListLength at a time and hands each list to
// add_rows(begin, list, count) (rays begin + list[0 .. count)); returns the number of occluded rays.
template <class AddRows>
std::size_t for_occluded_lists(const trace::RayBatch& batch, AddRows add_rows) {
  std::uint16_t list[kListLength];
  std::size_t occluded = 0;
  for (std::size_t begin = 0; begin < batch.size(); begin += kListLength) {
    const std::size_t count = occluded_list(batch, begin, std::min(batch.size(), begin + kListLength), list);
    add_rows(begin, list, count);
    occluded += count;
  }
  return occluded;
}

// sum[0, width) += the rows (width floats apart) of the occluded rays of `batch`, in ray order.
std::size_t add_occluded_rows(const trace::RayBatch& batch, const float* rows, std::size_t width, float* sum) {
  return for_occluded_lists(batch, [&](std::size_t begin, const std::uint16_t* list, std::size_t count) {
    for (std::size_t j = 0; j < count; ++j) {
      const float* row = rows + (begin + list[j]) * width;
      for (std::size_t c = 0; c < width; ++c) sum[c] += row[c];
    }
  });
}

#if defined(__GNUC__)
// The same additions for a width of 8 K floats known at compile time, in GCC/Clang vector extensions
// (one AVX register of 8 floats, or two SSE ones): the K sums stay in registers.
typedef float Floats8 __attribute__((vector_size(32)));

template <int K>
std::size_t add_occluded_rows_fixed(const trace::RayBatch& batch, const float* rows, float* sum) {
  Floats8 acc[K];
  std::memcpy(acc, sum, sizeof(acc));
  const std::size_t occluded = for_occluded_lists(batch, [&](std::size_t begin, const std::uint16_t* list, std::size_t count) {
    for (std::size_t j = 0; j < count; ++j) {
      const float* row = rows + (begin + list[j]) * (8 * K);
      for (int k = 0; k < K; ++k) {
        Floats8 part;
        std::memcpy(&part, row + 8 * k, sizeof(part));
        acc[k] += part;
      }
    }
  });
  std::memcpy(sum, acc, sizeof(acc));
  return occluded;
}
#endif

}  // namespace

OccludedRowSums::OccludedRowSums(const LocalSampleSet& set) {
  const std::size_t n = static_cast<std::size_t>(set.bands) * set.bands;
  width_ = static_cast<int>((n + 7) / 8 * 8);
  const std::size_t samples = set.directions.size();
  rows_.assign(samples * width_, 0.0f);
  for (std::size_t s = 0; s < samples; ++s) std::copy_n(set.basis.data() + s * n, n, rows_.data() + s * width_);
}

std::size_t OccludedRowSums::add(const trace::RayBatch& batch, std::size_t first, float* sum) const {
  const float* rows = rows_.data() + first * width_;
#if defined(__GNUC__)
  switch (width_ / 8) {  // 1 to 8 bands
    case 1: return add_occluded_rows_fixed<1>(batch, rows, sum);
    case 2: return add_occluded_rows_fixed<2>(batch, rows, sum);
    case 4: return add_occluded_rows_fixed<4>(batch, rows, sum);
    case 5: return add_occluded_rows_fixed<5>(batch, rows, sum);
    case 7: return add_occluded_rows_fixed<7>(batch, rows, sum);
    case 8: return add_occluded_rows_fixed<8>(batch, rows, sum);
    default: break;
  }
#endif
  return add_occluded_rows(batch, rows, static_cast<std::size_t>(width_), sum);
}

LocalSampleSet make_local_sample_set(int samples, int bands, std::uint32_t seed) {
  return sample_set_from(sh::hemisphere_directions_cosine(static_cast<std::size_t>(samples), seed), bands);
}

LocalSampleSet make_interleaved_sample_sets(int samples, int bands, std::uint32_t seed, int sets) {
  const std::size_t total = static_cast<std::size_t>(samples) * static_cast<std::size_t>(sets);
  LocalSampleSet set = sample_set_from(sh::hemisphere_directions_cosine(total, seed), bands);
  set.sets = sets;
  return set;
}

LocalSampleSet make_uniform_sample_set(int samples, int bands, std::uint32_t seed) {
  return sample_set_from(sh::hemisphere_directions_uniform(static_cast<std::size_t>(samples), seed), bands);
}

}  // namespace prt::bake
