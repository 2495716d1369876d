// Batched SH evaluation over a structure of arrays of directions: the kernels of eval_kernels.h applied to
// one block of directions at a time, each block's values stored into every one of the bands^2 output rows.
//
// Layout: the rows lie out_stride apart. Each kernel call stores one block into each row, so the rows
// should fall on different L1 cache sets: sh::padded_stride gives such a stride (an odd number of cache
// lines). Any stride >= count gives the same values; a stride whose byte size is a multiple of 4 KiB puts
// every row on one cache set and runs up to 10x slower (docs/performance.md).
#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "sh/basis.h"
#include "sh/eval_kernels.h"

namespace prt::sh {
namespace detail {
namespace {

// Stores coefficient k of one block of directions into out[k * stride + j ...].
template <typename T>
struct StridedStore {
  T* out;
  std::size_t stride;
  template <typename V>
  PRT_SH_INLINE void operator()(int k, V value) const {
    store(out + static_cast<std::size_t>(k) * stride, value);
  }
};

constexpr std::size_t kCacheLine = 64;

// What one kernel call evaluates: one vector of directions, or two (a Pair, eval_kernels.h) where a vector is
// shorter than a cache line, so that every store fills a whole line of its row (half-line stores into bands^2
// rows cost 1.4x whole-line ones, docs/performance.md).
template <typename T>
using Block = std::conditional_t<(sizeof(Vec<T>) < kCacheLine), Pair<Vec<T>>, Vec<T>>;
template <typename T>
inline constexpr std::size_t kBlockLanes = sizeof(Block<T>) / sizeof(T);

// Directions to skip so that out + j is `alignment`-byte aligned (0 if out is not even T-aligned).
template <typename T>
std::size_t alignment_peel(const T* out, std::size_t alignment) {
  std::size_t misalign = reinterpret_cast<std::uintptr_t>(out) % alignment;
  if (misalign == 0 || misalign % sizeof(T) != 0) return 0;
  return (alignment - misalign) / sizeof(T);
}

// Calls block(j) for starts j of blocks of `width` directions covering [0, count), count >= width:
// j = 0, then peel (if 0 < peel < width), peel + width, ... (aligned stores from there on), each
// clamped to count - width so the last block ends exactly at count. Overlapping blocks recompute a
// few directions, with identical results (the output never aliases the input). `block` has one call
// site, so it is inlined once.
template <typename Block>
PRT_SH_INLINE void for_each_block(std::size_t count, std::size_t width, std::size_t peel, Block&& block) {
  const std::size_t last = count - width;
  std::size_t j = 0;
  std::size_t next = peel > 0 && peel < width ? peel : width;
  for (;;) {
    block(j);
    if (j >= last) break;
    j = next < last ? next : last;
    next += width;
  }
}

// The loop shared by every band count: `kernel(x, y, z, put)` evaluates one Block (kLines), vector or scalar
// of directions and stores into every row. Without kLines (the generic kernel) it takes vectors only.
template <typename T, bool kLines, typename Kernel>
PRT_SH_INLINE void run_batch(std::size_t count, const T* x, const T* y, const T* z, T* out, std::size_t stride,
                             Kernel&& kernel) {
  using V = Vec<T>;
  if constexpr (kLines && kBlockLanes<T> > kLanes<T>) {
    using B = Block<T>;
    if (count >= kBlockLanes<T>) {
      for_each_block(count, kBlockLanes<T>, alignment_peel(out, sizeof(B)), [&](std::size_t j) PRT_SH_LAMBDA_INLINE {
        StridedStore<T> put{out + j, stride};
        kernel(load<B>(x + j), load<B>(y + j), load<B>(z + j), put);
      });
      return;
    }
  }
  if (count >= kLanes<T>) {
    // Line-aligned stores when the rows are (stride a multiple of the vector): no store splits.
    const std::size_t peel = alignment_peel(out, sizeof(V));
    for_each_block(count, kLanes<T>, peel, [&](std::size_t j) PRT_SH_LAMBDA_INLINE {
      StridedStore<T> put{out + j, stride};
      kernel(load<V>(x + j), load<V>(y + j), load<V>(z + j), put);
    });
  } else {
    for (std::size_t j = 0; j < count; ++j) {
      StridedStore<T> put{out + j, stride};
      kernel(x[j], y[j], z[j], put);
    }
  }
}

template <int N, typename T>
void batch_fixed(std::size_t count, const T* x, const T* y, const T* z, T* out, std::size_t stride) {
  auto kernel = [](auto vx, auto vy, auto vz, StridedStore<T>& put)
                    PRT_SH_LAMBDA_INLINE { eval_fixed<N, T>(vx, vy, vz, put); };
  run_batch<T, true>(count, x, y, z, out, stride, kernel);
}

template <typename T>
void batch_generic(int bands, std::size_t count, const T* x, const T* y, const T* z, T* out, std::size_t stride) {
  run_batch<T, false>(count, x, y, z, out, stride,
                      [bands](auto vx, auto vy, auto vz, StridedStore<T>& put) PRT_SH_LAMBDA_INLINE {
                        eval_generic<T>(bands, vx, vy, vz, put);
                      });
}

template <typename T>
using BatchFunction = void (*)(std::size_t, const T*, const T*, const T*, T*, std::size_t);

// batch_fixed<1> .. batch_fixed<kMaxFastBands>, indexed by bands - 1.
template <typename T, int... I>
constexpr auto make_fixed_table(std::integer_sequence<int, I...>) {
  return std::array<BatchFunction<T>, sizeof...(I)>{&batch_fixed<I + 1, T>...};
}

template <typename T>
void batch_dispatch(int bands, std::size_t count, const T* x, const T* y, const T* z, T* out, std::size_t stride) {
  static constexpr auto kFixed = make_fixed_table<T>(std::make_integer_sequence<int, kMaxFastBands>{});
  if (bands >= 1 && bands <= kMaxFastBands) {
    kFixed[static_cast<std::size_t>(bands - 1)](count, x, y, z, out, stride);
  } else {
    batch_generic<T>(bands, count, x, y, z, out, stride);
  }
}

}  // namespace

void eval_batch_generic(int bands, std::size_t count, const float* x, const float* y, const float* z, float* out,
                        std::size_t out_stride) {
  batch_generic<float>(bands, count, x, y, z, out, out_stride);
}

void eval_batch_generic(int bands, std::size_t count, const double* x, const double* y, const double* z,
                        double* out, std::size_t out_stride) {
  batch_generic<double>(bands, count, x, y, z, out, out_stride);
}

void eval_one_generic(int bands, float x, float y, float z, float* out) {
  auto put = [out](int k, float v) { out[k] = v; };
  eval_generic<float>(bands, x, y, z, put);
}

void eval_one_generic(int bands, double x, double y, double z, double* out) {
  auto put = [out](int k, double v) { out[k] = v; };
  eval_generic<double>(bands, x, y, z, put);
}

}  // namespace detail

std::size_t padded_stride(std::size_t count, std::size_t element_bytes) {
  // An odd number of cache lines: rows start line-aligned and step through every set of a 4 KiB page.
  const std::size_t per_line = element_bytes >= detail::kCacheLine ? 1 : detail::kCacheLine / element_bytes;
  std::size_t lines = (count + per_line - 1) / per_line;
  if (lines % 2 == 0) ++lines;
  return per_line * lines;
}

void eval_batch(int bands, std::size_t count, const float* x, const float* y, const float* z, float* out,
                std::size_t out_stride) {
  assert(out_stride >= count);
  detail::batch_dispatch<float>(bands, count, x, y, z, out, out_stride);
}

void eval_batch(int bands, std::size_t count, const double* x, const double* y, const double* z, double* out,
                std::size_t out_stride) {
  assert(out_stride >= count);
  detail::batch_dispatch<double>(bands, count, x, y, z, out, out_stride);
}

}  // namespace prt::sh
