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
// Directions are taken 2 kLanes<T> at a time, one vector accumulator per coefficient. A call's first kernel
// step sets the accumulators instead of adding to them (nothing is zeroed) and takes the last vector of
// directions, alone or with the one before it, so that whole pairs remain; that last vector ends at `count`
// and, when count is not a multiple of kLanes<T>, overlaps the one before it, its overlapped lanes weighted
// zero (every term carries the weight, so they add exact zeros). Only a call of fewer than kLanes<T>
// directions copies them, into a zero-padded vector. At the end the bands^2 accumulators are reduced
// kLanes<T> at a time by a transpose-and-add butterfly (reduce_group) that leaves one coefficient's total
// per lane, so the totals are scaled and added to `sums` a vector at a time. Against zeroing the
// accumulators, one horizontal sum per coefficient and zero-padded pairs, this took a call of 16 directions
// from 17.0 to 6.5 ns per direction at 9 bands (Xeon, AVX-512) and changed nothing measurable from 256 up.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <utility>

#include "sh/accumulator.h"
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
// Accumulators<kSet, A>: the kernel's sink, acc[k] = v (the first step of a call) or acc[k] += v.
// A compiler barrier on the accumulators: they stay in memory between kernel steps. Without it GCC keeps
// all bands^2 of them in registers across the loop and spills most (9 bands: 81 copies in and out per call
// and stack traffic in every step).
template <typename V>
PRT_SH_INLINE void keep_in_memory(V* acc) {
#if defined(__GNUC__)
  asm volatile("" : : "r"(acc) : "memory");
#else
  (void)acc;
#endif
}

// kInMemory (sh::Accumulator): a barrier after every update. A pair is summed before it is added, so that
// each step puts one add, not two, on each sum's chain (through memory in an Accumulator: store, forwarded
// load, add): at 1 band, where that chain is all the work, Accumulator calls of 16 directions went from
// 0.32 to 0.26 ns per direction (Zen 3).
template <bool kSet, typename A, bool kInMemory = false>
struct Accumulators {
  A* acc;
  PRT_SH_INLINE void add(int k, A v) const {
    if constexpr (kSet) {
      acc[k] = v;
    } else {
      acc[k] += v;
    }
    if constexpr (kInMemory) keep_in_memory(acc);
  }
  PRT_SH_INLINE void add(int k, Pair<A> v) const {
    if constexpr (kSet) {
      acc[k] = v.a + v.b;
    } else {
      acc[k] += v.a + v.b;
    }
    if constexpr (kInMemory) keep_in_memory(acc);
  }
};

// acc += w G_L^M (column 0, the weight already in g) or w G_L^M (C_M, S_M) (c, s carry the weight).
template <int L, int M, typename V, typename Sink>
PRT_SH_INLINE void add(V g, V c, V s, const Sink& acc) {
  if constexpr (M == 0) {
    acc.add(index(L, 0), g);
  } else {
    acc.add(index(L, M), g * c);
    acc.add(index(L, -M), g * s);
  }
}

// G_L^M .. G_{N-1}^M from g1 = G_{L-1}^M and g2 = G_{L-2}^M.
template <int N, int M, int L, typename T, typename V, typename Sink>
PRT_SH_INLINE void scaled_tail(V z, V c, V s, V g1, V g2, const Sink& acc) {
  if constexpr (L < N) {
    constexpr T e = static_cast<T>(kScaled.e[L][M]);
    V g = z * g1 + e * g2;
    add<L, M>(g, c, s, acc);
    scaled_tail<N, M, L + 1, T>(z, c, s, g, g1, acc);
  }
}

// Columns M..N-1 (M >= 1), (c, s) = w (C_M, S_M).
template <int N, int M, typename T, typename V, typename Sink>
PRT_SH_INLINE void scaled_columns(V x, V y, V z, V z2, V c, V s, const Sink& acc) {
  if constexpr (M < N) {
    acc.add(index(M, M), c);  // G_M^M = 1
    acc.add(index(M, -M), s);
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

// acc[k] (+)= w G_k (C or S factor included) for one or two vectors of directions, N a compile-time band count.
template <int N, typename T, typename V, typename Sink>
PRT_SH_INLINE void accumulate_fixed(V x, V y, V z, V w, const Sink& acc) {
  acc.add(0, w);
  if constexpr (N > 1) {
    V g1 = w * z;
    acc.add(index(1, 0), g1);
    scaled_tail<N, 0, 2, T>(z, w, w, g1, w, acc);
    scaled_columns<N, 1, T>(x, y, z, z * z, w * x, w * y, acc);
  }
}

// ---------------------------------------------------------------------------------------------
// Reduction: bands^2 vector accumulators to bands^2 totals, kLanes at a time.

// The transpose-and-add step at distance H (a power of two below the lane count): lane i of the result is
// a[i] + a[i + H] where bit H of i is clear and b[i - H] + b[i] where it is set, so each of a and b keeps
// its partial sums in half of the lanes. One blend, one two-source shuffle and one add per pair of vectors
// (the blend written as a select, so that it need not take the shuffle unit).
template <std::size_t H, typename W, std::size_t... I>
PRT_SH_INLINE W fold_pair(W a, W b, std::index_sequence<I...>) {
  constexpr std::size_t n = sizeof...(I);
  using Bits = std::conditional_t<sizeof(W) / n == 4, std::int32_t, std::int64_t>;
  typedef Bits M __attribute__((vector_size(sizeof(W))));
  const M from_b = {((I & H) ? Bits(-1) : Bits(0))...};
  const W kept = from_b ? b : a;
  const W moved = __builtin_shufflevector(a, b, static_cast<int>((I & H) ? n + I - H : I + H)...);
  return kept + moved;
}

// Stage H of the butterfly and the stages after it: v[j] = fold(src[j], src[j + H]) for j < min(H, N), where
// src[0 .. N) hold the vectors to fold; the later stages then fold v in place (src = v). A pair whose second
// vector is absent folds the first with itself (the lanes that would belong to the absent one are left with
// values no total reads). The first stage reads the accumulators where they are: copying them into v first
// compiled to a memcpy call per group of kLanes, and calls of 16 directions took 2.3x as long at 5 and 9
// bands (Zen 5).
template <std::size_t H, std::size_t N, typename W, std::size_t... J>
PRT_SH_INLINE void fold_stage(const W* src, W* v, std::index_sequence<J...>) {
  constexpr auto lanes = std::make_index_sequence<sizeof(W) / sizeof(v[0][0])>{};
  ((v[J] = fold_pair<H>(src[J], src[J + H < N ? J + H : J], lanes)), ...);
  constexpr std::size_t live = sizeof...(J);
  if constexpr (H > 1) fold_stage<H / 2, live>(v, v, std::make_index_sequence<(H / 2 < live ? H / 2 : live)>{});
}

// The totals of N <= kLanes accumulators: lane i of the result is the sum of the lanes of acc[i] (i < N;
// the other lanes are unspecified). The order of the additions is fixed: the same inputs, the same bits.
template <typename T, std::size_t N>
PRT_SH_INLINE Vec<T> reduce_group(const Vec<T>* acc) {
  if constexpr (kLanes<T> == 1) {
    return acc[0];
  } else {
    constexpr std::size_t h = kLanes<T> / 2, live = h < N ? h : N;
    Vec<T> v[live];
    fold_stage<h, N>(acc, v, std::make_index_sequence<live>{});
    return v[0];
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

// sums[k + i] += s_{k+i} * (lane sum of acc[k + i]) for the N accumulators from k (the fixed kernels'
// rescaling), or without s: a whole group of kLanes totals as one vector, a partial one lane by lane.
template <bool kScaledSums, typename T, std::size_t N>
PRT_SH_INLINE void finish_group(std::size_t k, const Vec<T>* acc, T* sums) {
  using V = Vec<T>;
  const V total = reduce_group<T, N>(acc + k);
  const V scaled = kScaledSums ? load<V>(kScaleByIndex<T>.value + k) * total : total;
  if constexpr (N == kLanes<T>) {
    store(sums + k, load<V>(sums + k) + scaled);
  } else {
    T part[kLanes<T>];
    store(part, scaled);
    for (std::size_t i = 0; i < N; ++i) {
      T sum = sums[k + i] + part[i];
#if defined(__x86_64__) || defined(__i386__)
      // One sum at a time: GCC otherwise merges the first 8 into a 32-byte load, which waits whenever the
      // caller has just written sums with other stores (zeroed them, say: 3 bands, calls of 16 directions,
      // 23 against 18 ns per call, Zen 5).
      asm("" : "+x"(sum));
#endif
      sums[k + i] = sum;
    }
  }
}

// finish_group over the Count accumulators of a fixed band count.
template <bool kScaledSums, typename T, std::size_t Count, std::size_t... G>
PRT_SH_INLINE void finish(const Vec<T>* acc, T* sums, std::index_sequence<G...>) {
  constexpr std::size_t lanes = kLanes<T>;
  (finish_group<kScaledSums, T, (Count - G * lanes < lanes ? Count - G * lanes : lanes)>(G * lanes, acc, sums), ...);
}
template <bool kScaledSums, typename T, std::size_t Count>
PRT_SH_INLINE void finish(const Vec<T>* acc, T* sums) {
  finish<kScaledSums, T, Count>(acc, sums, std::make_index_sequence<(Count + kLanes<T> - 1) / kLanes<T>>{});
}

// The same for a runtime count: whole groups, then a partial one padded with zero accumulators.
template <typename T>
void finish_unscaled(std::size_t count, const Vec<T>* acc, T* sums) {
  constexpr std::size_t lanes = kLanes<T>;
  std::size_t k = 0;
  for (; k + lanes <= count; k += lanes) finish_group<false, T, lanes>(k, acc, sums);
  if (k < count) {
    Vec<T> padded[lanes] = {};
    for (std::size_t i = k; i < count; ++i) padded[i - k] = acc[i];
    T part[lanes] = {};
    finish_group<false, T, lanes>(0, padded, part);
    for (std::size_t i = k; i < count; ++i) sums[i] += part[i - k];
  }
}

// ---------------------------------------------------------------------------------------------
// The driver: which directions each kernel step takes.

// Bits that keep lanes i >= skip of a vector (all ones) and clear the others: from value + lanes - skip.
template <typename T>
struct LaneMasks {
  using Bits = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
  Bits value[2 * kLanes<T>];
};
template <typename T>
constexpr LaneMasks<T> make_lane_masks() {
  LaneMasks<T> m{};
  for (std::size_t i = kLanes<T>; i < 2 * kLanes<T>; ++i) m.value[i] = ~typename LaneMasks<T>::Bits(0);
  return m;
}

// The weights at w with those of the first `skip` lanes set to +0 (skip < kLanes).
template <typename T>
PRT_SH_INLINE Vec<T> load_weights(const T* w, std::size_t skip) {
  using V = Vec<T>;
  if constexpr (kLanes<T> == 1) {
    return load<V>(w);
  } else {
    using Bits = typename LaneMasks<T>::Bits;
    typedef Bits B __attribute__((vector_size(sizeof(V))));
    static constexpr LaneMasks<T> kMasks = make_lane_masks<T>();
    B bits = load<B>(w) & load<B>(kMasks.value + kLanes<T> - skip);
    V v;
    std::memcpy(&v, &bits, sizeof(V));
    return v;
  }
}

// one(x, y, z, w) with the count < kLanes directions copied into zero-padded vectors (zero weights).
template <typename T, typename One>
PRT_SH_INLINE void step_padded(std::size_t count, const T* x, const T* y, const T* z, const T* w, One&& one) {
  using V = Vec<T>;
  alignas(64) T pad[4][kLanes<T>] = {};
  for (std::size_t j = 0; j < count; ++j) {
    pad[0][j] = x[j];
    pad[1][j] = y[j];
    pad[2][j] = z[j];
    pad[3][j] = w[j];
  }
  one(load<V>(pad[0]), load<V>(pad[1]), load<V>(pad[2]), load<V>(pad[3]));
}

// Calls set_one(x, y, z, w) or set_pair(...) once, then add_pair(...) with every remaining pair of vectors of
// directions (one call site each, so each kernel is inlined once). The first call takes the last vector,
// which ends at `count` and, when count is not a multiple of kLanes, overlaps the one before it: its
// overlapped lanes get zero weights. It takes the vector before it too when the vector count is even, so that
// whole pairs remain for the loop, which needs no masks. Fewer than kLanes directions are copied into a
// zero-padded vector.
template <typename T, typename SetOne, typename SetPair, typename AddPair>
PRT_SH_INLINE void for_each_step(std::size_t count, const T* x, const T* y, const T* z, const T* w, SetOne&& set_one,
                                 SetPair&& set_pair, AddPair&& add_pair) {
  using V = Vec<T>;
  constexpr std::size_t lanes = kLanes<T>;
  if (count < lanes) return step_padded(count, x, y, z, w, set_one);
  const std::size_t vectors = (count + lanes - 1) / lanes, last = count - lanes;
  const V last_w = load_weights(w + last, (vectors - 1) * lanes - last);
  std::size_t paired = (vectors - 1) * lanes;  // directions [0, paired) are left for whole pairs
  if (vectors % 2 == 1) {
    set_one(load<V>(x + last), load<V>(y + last), load<V>(z + last), last_w);
  } else {
    paired -= lanes;
    auto pair = [paired, last](const T* p) PRT_SH_LAMBDA_INLINE { return Pair<V>{load<V>(p + paired), load<V>(p + last)}; };
    set_pair(pair(x), pair(y), pair(z), Pair<V>{load<V>(w + paired), last_w});
  }
  for (std::size_t j = 0; j < paired; j += 2 * lanes)
    add_pair(load<Pair<V>>(x + j), load<Pair<V>>(y + j), load<Pair<V>>(z + j), load<Pair<V>>(w + j));
}

template <int N, typename T>
void accumulate_batch(std::size_t count, const T* x, const T* y, const T* z, const T* w, T* sums) {
  using V = Vec<T>;
  if (count == 0) return;
  V acc[N * N];
  const Accumulators<true, V> set{acc};
  const Accumulators<false, V> add{acc};
  auto set_one = [&set](V vx, V vy, V vz, V vw) PRT_SH_LAMBDA_INLINE { accumulate_fixed<N, T>(vx, vy, vz, vw, set); };
  auto set_pair = [&set](Pair<V> vx, Pair<V> vy, Pair<V> vz, Pair<V> vw)
                      PRT_SH_LAMBDA_INLINE { accumulate_fixed<N, T>(vx, vy, vz, vw, set); };
  auto add_pair = [&add](Pair<V> vx, Pair<V> vy, Pair<V> vz, Pair<V> vw)
                      PRT_SH_LAMBDA_INLINE { accumulate_fixed<N, T>(vx, vy, vz, vw, add); };
  for_each_step(count, x, y, z, w, set_one, set_pair, add_pair);
  finish<true, T, N * N>(acc, sums);
}

// Beyond kMaxFastBands: eval_generic's values, weighted and added (no rescaling).
template <typename T>
void accumulate_generic(int bands, std::size_t count, const T* x, const T* y, const T* z, const T* w, T* sums) {
  using V = Vec<T>;
  if (count == 0) return;
  V acc[kMaxBands * kMaxBands];
  auto step = [bands](auto vx, auto vy, auto vz, auto vw, auto sink) {
    auto put = [&sink, vw](int k, decltype(vw) value) PRT_SH_LAMBDA_INLINE { sink.add(k, vw * value); };
    eval_generic<T>(bands, vx, vy, vz, put);
  };
  const Accumulators<true, V> set{acc};
  const Accumulators<false, V> add{acc};
  for_each_step(
      count, x, y, z, w, [&](V vx, V vy, V vz, V vw) { step(vx, vy, vz, vw, set); },
      [&](Pair<V> vx, Pair<V> vy, Pair<V> vz, Pair<V> vw) { step(vx, vy, vz, vw, set); },
      [&](Pair<V> vx, Pair<V> vy, Pair<V> vz, Pair<V> vw) { step(vx, vy, vz, vw, add); });
  finish_unscaled<T>(static_cast<std::size_t>(bands * bands), acc, sums);
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

// ---------------------------------------------------------------------------------------------
// sh::Accumulator: the same kernels adding into partial sums kept between calls (no set step, no
// reduction per call).

// Calls add_pair(x, y, z, w) with every whole pair of vectors of directions from the first, then add_one or
// add_pair once with the rest (fewer than 2 kLanes directions). That last step ends at `count`: its last
// vector overlaps the one before it when count is not a multiple of kLanes, the overlapped lanes weighted
// zero, as in for_each_step. Fewer than kLanes directions in all are copied into a zero-padded vector.
// Unlike for_each_step, no step is special (every step adds), so a call of whole pairs runs only the loop:
// a call of 16 float directions on AVX2 took 0.86-0.9x the time that for_each_step's masked first pair took.
template <typename T, typename AddOne, typename AddPair>
PRT_SH_INLINE void for_each_add(std::size_t count, const T* x, const T* y, const T* z, const T* w, AddOne&& add_one,
                                AddPair&& add_pair) {
  using V = Vec<T>;
  constexpr std::size_t lanes = kLanes<T>;
  std::size_t j = 0;
  for (; j + 2 * lanes <= count; j += 2 * lanes)
    add_pair(load<Pair<V>>(x + j), load<Pair<V>>(y + j), load<Pair<V>>(z + j), load<Pair<V>>(w + j));
  const std::size_t rest = count - j;
  if (rest == 0) return;
  if (count < lanes) return step_padded(count, x, y, z, w, add_one);
  const std::size_t last = count - lanes;
  if (rest <= lanes) {
    add_one(load<V>(x + last), load<V>(y + last), load<V>(z + last), load_weights(w + last, lanes - rest));
  } else {
    auto pair = [j, last](const T* p) PRT_SH_LAMBDA_INLINE { return Pair<V>{load<V>(p + j), load<V>(p + last)}; };
    add_pair(pair(x), pair(y), pair(z), Pair<V>{load<V>(w + j), load_weights(w + last, 2 * lanes - rest)});
  }
}

// acc[k] += the lane-wise weighted values of count directions.
template <int N, typename T>
void accumulate_stream(std::size_t count, const T* x, const T* y, const T* z, const T* w, Vec<T>* acc) {
  using V = Vec<T>;
  const Accumulators<false, V, true> add{acc};
  auto one = [&add](V vx, V vy, V vz, V vw) PRT_SH_LAMBDA_INLINE { accumulate_fixed<N, T>(vx, vy, vz, vw, add); };
  auto pair = [&add](Pair<V> vx, Pair<V> vy, Pair<V> vz, Pair<V> vw)
                  PRT_SH_LAMBDA_INLINE { accumulate_fixed<N, T>(vx, vy, vz, vw, add); };
  for_each_add(count, x, y, z, w, one, pair);
}

template <typename T>
PRT_SH_NOINLINE void accumulate_stream_generic(int bands, std::size_t count, const T* x, const T* y, const T* z, const T* w,
                               Vec<T>* acc) {
  const Accumulators<false, Vec<T>> add{acc};
  auto step = [bands, &add](auto vx, auto vy, auto vz, auto vw) {
    auto put = [&add, vw](int k, decltype(vw) value) PRT_SH_LAMBDA_INLINE { add.add(k, vw * value); };
    eval_generic<T>(bands, vx, vy, vz, put);
  };
  for_each_add(count, x, y, z, w, step, step);
}

template <int N, typename T>
void finish_stream(const Vec<T>* acc, T* sums) {
  finish<true, T, N * N>(acc, sums);
}

template <typename T>
using StreamFunction = void (*)(std::size_t, const T*, const T*, const T*, const T*, T*);
template <typename T>
using FinishFunction = void (*)(const Vec<T>*, T*);

// The kernels on the partial sums as the T array Accumulator holds (bands^2 vectors, 64-byte aligned).
template <int N, typename T>
void stream_fixed(std::size_t count, const T* x, const T* y, const T* z, const T* w, T* lanes) {
  accumulate_stream<N, T>(count, x, y, z, w, reinterpret_cast<Vec<T>*>(lanes));
}
template <int N, typename T>
void stream_generic(std::size_t count, const T* x, const T* y, const T* z, const T* w, T* lanes) {
  accumulate_stream_generic<T>(N, count, x, y, z, w, reinterpret_cast<Vec<T>*>(lanes));
}

template <int N, typename T>
constexpr StreamFunction<T> stream_entry() {
  if constexpr (N <= kMaxFastBands) {
    return &stream_fixed<N, T>;
  } else {
    return &stream_generic<N, T>;
  }
}
template <typename T, int... I>
constexpr auto make_stream_table(std::integer_sequence<int, I...>) {
  return std::array<StreamFunction<T>, sizeof...(I)>{stream_entry<I + 1, T>()...};
}
template <typename T, int... I>
constexpr auto make_finish_table(std::integer_sequence<int, I...>) {
  return std::array<FinishFunction<T>, sizeof...(I)>{&finish_stream<I + 1, T>...};
}

// The kernel that adds count directions to an Accumulator's partial sums (1 <= bands <= kMaxBands).
template <typename T>
StreamFunction<T> stream_function(int bands) {
  static constexpr auto kAll = make_stream_table<T>(std::make_integer_sequence<int, kMaxBands>{});
  return kAll[static_cast<std::size_t>(bands - 1)];
}

// The fixed kernels accumulate the rescaled G (sums scaled by s_lm at the end), the generic one Y itself.
template <typename T>
void finish_dispatch(int bands, const Vec<T>* acc, T* sums) {
  static constexpr auto kFixed = make_finish_table<T>(std::make_integer_sequence<int, kMaxFastBands>{});
  if (bands <= kMaxFastBands) {
    kFixed[static_cast<std::size_t>(bands - 1)](acc, sums);
  } else {
    finish_unscaled<T>(static_cast<std::size_t>(bands * bands), acc, sums);
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

// The partial sums' vectors start at a 64-byte boundary of storage_ (alignof of the widest vector).
constexpr std::size_t kAccumulatorAlignment = 64;

template <typename T>
Accumulator<T>::Accumulator(int bands) : bands_(bands) {
  static_assert(kAccumulatorAlignment % alignof(detail::Vec<T>) == 0, "the partial sums' vectors need at most 64-byte alignment");
  const std::size_t bytes = static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands) * sizeof(detail::Vec<T>);
  storage_.reset(new unsigned char[bytes + kAccumulatorAlignment]);
  const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(storage_.get());
  lanes_ = reinterpret_cast<T*>(storage_.get() + (kAccumulatorAlignment - start % kAccumulatorAlignment) % kAccumulatorAlignment);
  add_ = detail::stream_function<T>(bands);
  clear();
}

template <typename T>
Accumulator<T>::~Accumulator() = default;
template <typename T>
Accumulator<T>::Accumulator(Accumulator&&) noexcept = default;
template <typename T>
Accumulator<T>& Accumulator<T>::operator=(Accumulator&&) noexcept = default;

template <typename T>
void Accumulator<T>::add_to(T* sums) const {
  detail::finish_dispatch<T>(bands_, reinterpret_cast<const detail::Vec<T>*>(lanes_), sums);
}

template <typename T>
void Accumulator<T>::clear() {
  std::memset(lanes_, 0, static_cast<std::size_t>(bands_) * static_cast<std::size_t>(bands_) * sizeof(detail::Vec<T>));
}

template class Accumulator<float>;
template class Accumulator<double>;

}  // namespace prt::sh
