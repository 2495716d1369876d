// SH evaluation fused with accumulation (sh::eval_accumulate): the weighted sums
// sum_j w_j Y_k(d_j) that projecting a sampled function needs, with nothing per direction stored.
//
// The recurrence is eval_kernels.h's, rescaled so that each step costs one multiply and one
// multiply-add and the normalisation leaves the loop. Write F_l^m = s_lm G_l^m with
//   s_mm = F_m^m,  s_{m+1,m} = F_{m+1}^m / z,  s_lm = a_lm s_{l-1,m}  (l >= m + 2);
// then G_m^m = 1, G_{m+1}^m = z and
//   G_l^m = z G_{l-1}^m + e_lm G_{l-2}^m,   e_lm = b_lm s_{l-2,m} / s_lm,
// (divide F_l = a_lm z F_{l-1} + b_lm F_{l-2} by s_lm). The sums are linear, so the kernel adds
// w G_l^m C_m (and S_m) per direction and multiplies each finished sum by s_lm once per call. The weight
// rides in the starting values: column 0 starts its recurrence at w instead of 1 (the recurrence is
// linear and homogeneous), and the other columns use (C_1, S_1) = (w x, w y), which the complex
// multiplication C_{m+1} + i S_{m+1} = (x + i y)(C_m + i S_m) carries to every m.
//
// Directions are taken 2 kLanes<T> at a time, one vector accumulator per coefficient; a partial last
// group is padded with zero weights (every term carries the weight, so the padding adds exact zeros).
#include <array>
#include <cstddef>
#include <cstring>
#include <utility>

#include "sh/basis.h"
#include "sh/eval_kernels.h"

namespace prt::sh {
namespace detail {
namespace {

struct ScaledTables {
  double scale[kMaxBands][kMaxBands];  // s_lm at [l][m], m <= l
  double e[kMaxBands][kMaxBands];      // e_lm at [l][m], l >= m + 2 (zero elsewhere)
};

constexpr ScaledTables make_scaled_tables() {
  ScaledTables t{};
  const RecurrenceTables& r = kRecurrence;
  for (int m = 0; m < kMaxBands; ++m) {
    t.scale[m][m] = r.f_mm[m];
    if (m + 1 < kMaxBands) t.scale[m + 1][m] = r.f_m1[m];
    for (int l = m + 2; l < kMaxBands; ++l) {
      t.scale[l][m] = r.a[l][m] * t.scale[l - 1][m];
      t.e[l][m] = r.b[l][m] * t.scale[l - 2][m] / t.scale[l][m];
    }
  }
  return t;
}

inline constexpr ScaledTables kScaled = make_scaled_tables();

// Two vectors of directions (Pair, eval_kernels.h) are evaluated together, so that each accumulator is
// loaded and stored once per 2 kLanes directions (the bands^2 accumulators do not fit in registers; their
// memory traffic, not the arithmetic, bounded a one-vector loop at 9 bands: 5.9 against 4.0 ns).
template <typename A>
PRT_SH_INLINE void accumulate(A& acc, Pair<A> v) {
  acc += v.a;
  acc += v.b;
}

// acc += w G_L^M (column 0, the weight already in g) or w G_L^M (C_M, S_M) (c, s carry the weight).
template <int L, int M, typename V, typename A>
PRT_SH_INLINE void add(V g, V c, V s, A* acc) {
  if constexpr (M == 0) {
    accumulate(acc[index(L, 0)], g);
  } else {
    accumulate(acc[index(L, M)], g * c);
    accumulate(acc[index(L, -M)], g * s);
  }
}

// G_L^M .. G_{N-1}^M from g1 = G_{L-1}^M and g2 = G_{L-2}^M.
template <int N, int M, int L, typename T, typename V, typename A>
PRT_SH_INLINE void scaled_tail(V z, V c, V s, V g1, V g2, A* acc) {
  if constexpr (L < N) {
    constexpr T e = static_cast<T>(kScaled.e[L][M]);
    V g = z * g1 + e * g2;
    add<L, M>(g, c, s, acc);
    scaled_tail<N, M, L + 1, T>(z, c, s, g, g1, acc);
  }
}

// Columns M..N-1 (M >= 1), (c, s) = w (C_M, S_M).
template <int N, int M, typename T, typename V, typename A>
PRT_SH_INLINE void scaled_columns(V x, V y, V z, V z2, V c, V s, A* acc) {
  if constexpr (M < N) {
    accumulate(acc[index(M, M)], c);  // G_M^M = 1
    accumulate(acc[index(M, -M)], s);
    if constexpr (M + 1 < N) {
      add<M + 1, M>(z, c, s, acc);  // G_{M+1}^M = z
      if constexpr (M + 2 < N) {
        V g2 = z2 + static_cast<T>(kScaled.e[M + 2][M]);  // z G_{M+1} + e G_M
        add<M + 2, M>(g2, c, s, acc);
        scaled_tail<N, M, M + 3, T>(z, c, s, g2, z, acc);
      }
      V c_next = x * c - y * s;
      V s_next = x * s + y * c;
      scaled_columns<N, M + 1, T>(x, y, z, z2, c_next, s_next, acc);
    }
  }
}

// acc[k] += w G_k (C or S factor included) for a pair of vectors of directions, N a compile-time band count.
template <int N, typename T, typename V, typename A>
PRT_SH_INLINE void accumulate_fixed(V x, V y, V z, V w, A* acc) {
  accumulate(acc[0], w);
  if constexpr (N > 1) {
    V g1 = w * z;
    accumulate(acc[index(1, 0)], g1);
    scaled_tail<N, 0, 2, T>(z, w, w, g1, w, acc);
    scaled_columns<N, 1, T>(x, y, z, z * z, w * x, w * y, acc);
  }
}

// The sum of the lanes of a vector of Bytes bytes, halves added pairwise in registers (storing the
// vector and reading its lanes back stalls on store forwarding: ~15 cycles per coefficient, measured).
template <typename T, std::size_t Bytes>
struct LaneSum {
  typedef T W __attribute__((vector_size(Bytes)));
  typedef T H __attribute__((vector_size(Bytes / 2)));
  static PRT_SH_INLINE T of(W v) {
    H lo, hi;
    std::memcpy(&lo, &v, Bytes / 2);
    std::memcpy(&hi, reinterpret_cast<const char*>(&v) + Bytes / 2, Bytes / 2);
    return LaneSum<T, Bytes / 2>::of(lo + hi);
  }
};
template <typename T>
struct LaneSum<T, 2 * sizeof(T)> {
  typedef T W __attribute__((vector_size(2 * sizeof(T))));
  static PRT_SH_INLINE T of(W v) { return v[0] + v[1]; }
};

template <typename T>
PRT_SH_INLINE T lane_sum(Vec<T> v) {
  if constexpr (kLanes<T> == 1) {
    return v;
  } else {
    return LaneSum<T, sizeof(Vec<T>)>::of(v);
  }
}

// s_l|m| by flat index k, in T.
template <typename T>
struct ScaleByIndex {
  T value[kMaxBands * kMaxBands];
};
template <typename T>
constexpr ScaleByIndex<T> make_scale_by_index() {
  ScaleByIndex<T> t{};
  for (int l = 0; l < kMaxBands; ++l)
    for (int m = -l; m <= l; ++m) t.value[index(l, m)] = static_cast<T>(kScaled.scale[l][m < 0 ? -m : m]);
  return t;
}
template <typename T>
inline constexpr ScaleByIndex<T> kScaleByIndex = make_scale_by_index<T>();

// sums[k] += s_k * (lane sum of acc[k]) for k < n (the fixed kernels' rescaling), or without s_k.
template <bool kScaledSums, typename T>
PRT_SH_INLINE void finish(int n, const Vec<T>* acc, T* sums) {
  for (int k = 0; k < n; ++k) {
    const T total = lane_sum<T>(acc[k]);
    sums[k] += kScaledSums ? kScaleByIndex<T>.value[k] * total : total;
  }
}

// Calls step(x, y, z, w) for each pair of vectors of directions (one inlined call site), the last pair
// padded with zero weights.
template <typename T, typename Step>
PRT_SH_INLINE void for_each_pair(std::size_t count, const T* x, const T* y, const T* z, const T* w, Step&& step) {
  using V = Vec<T>;
  constexpr std::size_t lanes = kLanes<T>, width = 2 * lanes;
  alignas(64) T pad[4][width];  // filled (zero-weight padded) only for a partial last pair
  for (std::size_t j = 0; j < count; j += width) {
    const T *px = x + j, *py = y + j, *pz = z + j, *pw = w + j;
    if (count - j < width) {
      for (std::size_t i = 0; i < width; ++i) {
        const bool in = j + i < count;
        pad[0][i] = in ? x[j + i] : T(0);
        pad[1][i] = in ? y[j + i] : T(0);
        pad[2][i] = in ? z[j + i] : T(0);
        pad[3][i] = in ? w[j + i] : T(0);
      }
      px = pad[0];
      py = pad[1];
      pz = pad[2];
      pw = pad[3];
    }
    step(load_pair<V>(px), load_pair<V>(py), load_pair<V>(pz), load_pair<V>(pw));
  }
}

// acc[k] = 0 as one vector store each: `V acc[n] = {}` became a `rep stos` or memset call whose start-up
// cost (~30 cycles on Zen 3) was most of a small call's time.
template <typename V, std::size_t... K>
PRT_SH_INLINE void zero(V* acc, std::index_sequence<K...>) {
  ((acc[K] = V{}), ...);
}

template <int N, typename T>
void accumulate_batch(std::size_t count, const T* x, const T* y, const T* z, const T* w, T* sums) {
  using V = Vec<T>;
  V acc[N * N];
  zero(acc, std::make_index_sequence<N * N>{});
  for_each_pair<T>(count, x, y, z, w, [&acc](Pair<V> vx, Pair<V> vy, Pair<V> vz, Pair<V> vw) PRT_SH_LAMBDA_INLINE {
    accumulate_fixed<N, T>(vx, vy, vz, vw, acc);
  });
  finish<true, T>(N * N, acc, sums);
}

// Beyond kMaxFastBands: eval_generic's values, weighted and added (no rescaling).
template <typename T>
void accumulate_generic(int bands, std::size_t count, const T* x, const T* y, const T* z, const T* w, T* sums) {
  using V = Vec<T>;
  V acc[kMaxBands * kMaxBands];
  for (int k = 0; k < bands * bands; ++k) acc[k] = V{};
  for_each_pair<T>(count, x, y, z, w, [&acc, bands](Pair<V> vx, Pair<V> vy, Pair<V> vz, Pair<V> vw) {
    auto put = [&acc, vw](int k, Pair<V> value) PRT_SH_LAMBDA_INLINE { accumulate(acc[k], vw * value); };
    eval_generic<T>(bands, vx, vy, vz, put);
  });
  finish<false, T>(bands * bands, acc, sums);
}

template <typename T>
using AccumulateFunction = void (*)(std::size_t, const T*, const T*, const T*, const T*, T*);

template <typename T, int... I>
constexpr auto make_accumulate_table(std::integer_sequence<int, I...>) {
  return std::array<AccumulateFunction<T>, sizeof...(I)>{&accumulate_batch<I + 1, T>...};
}

template <typename T>
void accumulate_dispatch(int bands, std::size_t count, const T* x, const T* y, const T* z, const T* w, T* sums) {
  static constexpr auto kFixed = make_accumulate_table<T>(std::make_integer_sequence<int, kMaxFastBands>{});
  if (bands >= 1 && bands <= kMaxFastBands) {
    kFixed[static_cast<std::size_t>(bands - 1)](count, x, y, z, w, sums);
  } else {
    accumulate_generic<T>(bands, count, x, y, z, w, sums);
  }
}

}  // namespace

void eval_accumulate_generic(int bands, std::size_t count, const float* x, const float* y, const float* z,
                             const float* w, float* sums) {
  accumulate_generic<float>(bands, count, x, y, z, w, sums);
}

void eval_accumulate_generic(int bands, std::size_t count, const double* x, const double* y, const double* z,
                             const double* w, double* sums) {
  accumulate_generic<double>(bands, count, x, y, z, w, sums);
}

}  // namespace detail

void eval_accumulate(int bands, std::size_t count, const float* x, const float* y, const float* z, const float* w,
                     float* sums) {
  detail::accumulate_dispatch<float>(bands, count, x, y, z, w, sums);
}

void eval_accumulate(int bands, std::size_t count, const double* x, const double* y, const double* z,
                     const double* w, double* sums) {
  detail::accumulate_dispatch<double>(bands, count, x, y, z, w, sums);
}

}  // namespace prt::sh
