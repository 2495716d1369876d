// Batched SH evaluation over a structure of arrays of directions: the kernels of eval_kernels.h
// applied to one vector of directions at a time (kLanes<T> directions per kernel call).
//
// Memory layout matters as much as arithmetic here. Every kernel call stores one vector into each of
// the bands^2 output rows, rows out_stride apart. When out_stride * sizeof(T) is a multiple of 4 KiB
// (count = 1024 or 4096 with out_stride = count, the natural choice), all those stores fall into the
// same L1 cache set, and beyond its 8-12 ways every store misses: 6-15x slower, measured. Such strides
// take a staged path instead (staged_tile below) whose stores run along each row, about 2x slower
// than the direct path with a good stride; padded_stride() gives one.
#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <cstring>
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
constexpr std::size_t kPage = 4096;  // L1 data caches of x86 (and most others) index sets within 4 KiB

std::size_t gcd(std::size_t a, std::size_t b) {
  while (b != 0) {
    std::size_t t = a % b;
    a = b;
    b = t;
  }
  return a;
}

// True when `rows` rows out_stride apart crowd into few cache sets: the row starts fall on at most 2
// distinct 64-byte set positions of a 4 KiB page, with more than 12 rows per position. Measured on a
// 12-way L1 (float, direct stores, against the best stride): 1 position: 9 rows cost nothing, 25 rows
// 6x, 81 rows 10x; 2 positions: 81 rows 7x; 4 positions: 81 rows 2.5x, as slow as the staged path;
// 8 positions: 81 rows 1.1x, 1024 rows 1.3x.
// Rows per set position beyond which stores thrash: half the ways of an 8-way L1 (Zen 3; measured with
// bench_sh_eval: 9 rows on one position, stride = count = 1024 floats, 3.5x the padded figure).
constexpr std::size_t kRowsPerSet = 4;

template <typename T>
bool rows_share_cache_sets(int rows, std::size_t stride) {
  std::size_t offset = (stride * sizeof(T)) % kPage;
  std::size_t step = gcd(offset == 0 ? kPage : offset, kPage);
  std::size_t sets = kPage / (step > kCacheLine ? step : kCacheLine);
  return sets <= 2 && static_cast<std::size_t>(rows) > kRowsPerSet * sets;
}

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

// Staged path for crowded strides. A tile of kStageBytes worth of consecutive directions is evaluated
// column group by column group (columns m, all l, at most kStageRows rows per group) into a small
// scratch block in L1, and each scratch row is then copied to its output row: the output stores run
// along rows (8 cache lines at a time) instead of down the crowded column of rows. The recurrence is
// the generic one; the memory traffic, not the arithmetic, bounds this path.
constexpr std::size_t kStageBytes = 512;
constexpr int kStageRows = 64;  // >= 2 (kMaxBands - 1), the largest column

int column_rows(int bands, int m) { return m == 0 ? bands : 2 * (bands - m); }

template <typename T>
void staged_tile(int bands, const T* x, const T* y, const T* z, T* out, std::size_t stride) {
  using V = Vec<T>;
  constexpr std::size_t lanes = kLanes<T>, width = kStageBytes / sizeof(T), blocks = width / lanes;
  constexpr std::size_t scratch_stride = width + kCacheLine / sizeof(T);  // rows padded off one another's sets
  alignas(64) T scratch[kStageRows * scratch_stride];
  int row_index[kStageRows];  // output row of each scratch row
  V c[blocks] = {}, s[blocks] = {};  // (C_m, S_m) of the last column done, per block
  const RecurrenceTables& r = kRecurrence;
  for (int m_begin = 0; m_begin < bands;) {
    int m_end = m_begin, rows = 0;
    while (m_end < bands && rows + column_rows(bands, m_end) <= kStageRows) rows += column_rows(bands, m_end++);
    int* next_index = row_index;  // the order in which the kernel below emits rows
    for (int m = m_begin; m < m_end; ++m)
      for (int l = m; l < bands; ++l) {
        *next_index++ = index(l, m);
        if (m > 0) *next_index++ = index(l, -m);
      }
    for (std::size_t b = 0; b < blocks; ++b) {
      const V vx = load<V>(x + b * lanes), vy = load<V>(y + b * lanes), vz = load<V>(z + b * lanes);
      V cm = c[b], sm = s[b];
      T* dst = scratch + b * lanes;  // next scratch row, in row_index order
      auto put = [&](V value) {
        store(dst, value);
        dst += scratch_stride;
      };
      for (int m = m_begin; m < m_end; ++m) {
        if (m == 1) {
          cm = vx;
          sm = vy;
        } else if (m > 1) {
          V c_next = vx * cm - vy * sm;
          sm = vx * sm + vy * cm;
          cm = c_next;
        }
        auto emit = [&](V f) {
          if (m == 0) {
            put(f);
          } else {
            put(f * cm);
            put(f * sm);
          }
        };
        V f2 = splat<V>(static_cast<T>(r.f_mm[m]));
        emit(f2);
        if (m + 1 >= bands) continue;
        V f1 = static_cast<T>(r.f_m1[m]) * vz;
        emit(f1);
        for (int l = m + 2; l < bands; ++l) {
          V f = (static_cast<T>(r.a[l][m]) * vz) * f1 + static_cast<T>(r.b[l][m]) * f2;
          f2 = f1;
          f1 = f;
          emit(f);
        }
      }
      c[b] = cm;
      s[b] = sm;
    }
    for (int row = 0; row < rows; ++row)
      std::memcpy(out + static_cast<std::size_t>(row_index[row]) * stride, scratch + row * scratch_stride,
                  sizeof(T) * width);
    m_begin = m_end;
  }
}

// Staged path for crowded strides, with the band count's own kernel (up to kMaxFastBands bands): a
// tile of directions, as many as keep its bands^2 rows within kKernelStageBytes, is evaluated vector by
// vector into an L1 scratch block whose rows are padded off one another's cache sets, and each scratch
// row is then copied to its output row, whole cache lines along the row. The arithmetic is the fast
// path's; only the copy is added. The copy is bounded by its own write pattern: output rows 4 KiB apart
// written in runs of `tile` directions cost more the shorter the runs (bench_sh_eval's 'tiled' bound:
// 1.5x a plain fill at 48-direction runs, 3x at 16). So the tile is as long as a scratch of the whole
// L1 size allows: kKernelStageBytes = 32 KiB instead of 16 made stride == count 1.25x faster at 9 bands
// (20.5 -> 16.4 ns, Zen 3, two runs each, alternated) and changed nothing measurable at 3 and 5 bands.
constexpr std::size_t kKernelStageBytes = 32768;

template <typename T>
std::size_t kernel_tile(int bands) {
  const std::size_t lanes = kLanes<T>, rows = static_cast<std::size_t>(bands) * bands;
  std::size_t tile = kKernelStageBytes / (rows * sizeof(T)) / lanes * lanes;
  const std::size_t most = kStageBytes / sizeof(T);
  return tile < lanes ? lanes : tile > most ? most : tile;
}

template <typename T, typename Kernel>
PRT_SH_INLINE void staged_kernel_tile(int rows, std::size_t tile, const T* x, const T* y, const T* z, T* out,
                                      std::size_t stride, T* scratch, std::size_t scratch_stride, Kernel& kernel) {
  using V = Vec<T>;
  for (std::size_t b = 0; b < tile; b += kLanes<T>) {
    StridedStore<T> put{scratch + b, scratch_stride};
    kernel(load<V>(x + b), load<V>(y + b), load<V>(z + b), put);
  }
  // Inline vector copies: a memcpy call per row costs more than the row at small tiles.
  for (int row = 0; row < rows; ++row) {
    T* dst = out + static_cast<std::size_t>(row) * stride;
    const T* src = scratch + static_cast<std::size_t>(row) * scratch_stride;
    for (std::size_t b = 0; b < tile; b += kLanes<T>) store(dst + b, load<V>(src + b));
  }
}

// The batch driver shared by every band count: `kernel(x, y, z, put)` evaluates one vector (or one
// scalar) of directions.
template <typename T, typename Kernel>
PRT_SH_INLINE void run_batch(int bands, std::size_t count, const T* x, const T* y, const T* z, T* out,
                             std::size_t stride, Kernel&& kernel) {
  using V = Vec<T>;
  constexpr std::size_t lanes = kLanes<T>, tile = kStageBytes / sizeof(T);
  const bool crowded = rows_share_cache_sets<T>(bands * bands, stride);
  const std::size_t small_tile = bands <= kMaxFastBands ? kernel_tile<T>(bands) : 0;
  if (crowded && small_tile > 0 && count >= small_tile) {
    // rows * (tile + one line) * sizeof(T) <= 2 kKernelStageBytes for every band count up to kMaxFastBands
    alignas(64) T scratch[2 * kKernelStageBytes / sizeof(T)];
    const std::size_t scratch_stride = padded_stride(small_tile, sizeof(T));
    assert(static_cast<std::size_t>(bands * bands) * scratch_stride <= sizeof(scratch) / sizeof(T));
    const std::size_t peel = alignment_peel(out, kCacheLine);
    for_each_block(count, small_tile, peel, [&](std::size_t j) PRT_SH_LAMBDA_INLINE {
      staged_kernel_tile<T>(bands * bands, small_tile, x + j, y + j, z + j, out + j, stride, scratch, scratch_stride, kernel);
    });
  } else if (count >= tile && crowded) {
    const std::size_t peel = alignment_peel(out, kCacheLine);
    for_each_block(count, tile, peel, [&](std::size_t j) PRT_SH_LAMBDA_INLINE {
      staged_tile<T>(bands, x + j, y + j, z + j, out + j, stride);
    });
  } else if (count >= lanes) {
    // Line-aligned stores when the rows are (stride a multiple of the vector): no store splits.
    const std::size_t peel = alignment_peel(out, sizeof(V));
    for_each_block(count, lanes, peel, [&](std::size_t j) PRT_SH_LAMBDA_INLINE {
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
  run_batch<T>(N, count, x, y, z, out, stride,
               [](auto vx, auto vy, auto vz, StridedStore<T>& put) PRT_SH_LAMBDA_INLINE {
                 eval_fixed<N, T>(vx, vy, vz, put);
               });
}

template <typename T>
void batch_generic(int bands, std::size_t count, const T* x, const T* y, const T* z, T* out, std::size_t stride) {
  run_batch<T>(bands, count, x, y, z, out, stride,
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

std::size_t staged_tile_directions(int bands, std::size_t element_bytes) {
  if (element_bytes == sizeof(double)) {
    return bands <= kMaxFastBands ? kernel_tile<double>(bands) : kStageBytes / sizeof(double);
  }
  return bands <= kMaxFastBands ? kernel_tile<float>(bands) : kStageBytes / sizeof(float);
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
  detail::batch_dispatch<float>(bands, count, x, y, z, out, out_stride);
}

void eval_batch(int bands, std::size_t count, const double* x, const double* y, const double* z, double* out,
                std::size_t out_stride) {
  detail::batch_dispatch<double>(bands, count, x, y, z, out, out_stride);
}

}  // namespace prt::sh
