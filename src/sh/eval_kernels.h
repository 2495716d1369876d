#pragma once
// Private to src/sh (and the SH benchmark): the kernels behind sh::eval and sh::eval_batch.
//
// Factored form (Sloan 2013, "Efficient Spherical Harmonic Evaluation", JCGT 2(2)):
//   Y_l,+m = F_l^m(z) C_m(x, y),  Y_l,-m = F_l^m(z) S_m(x, y),  Y_l,0 = F_l^0(z),
// where C_m + i S_m = (x + i y)^m = sin^m(theta) e^{i m phi}, and F_l^m = sqrt(2) K_lm P_l^m / sin^m
// (no sqrt(2) for m = 0) is a polynomial in z that carries the normalisation and the
// Condon-Shortley phase. F follows the fully normalised three-term recurrence in l:
//   F_m^m     = (-1)^m sqrt((2 - [m = 0]) (2m+1)/(4 pi) prod_{k=1..m} (2k-1)/(2k))
//   F_{m+1}^m = sqrt(2m+3) z F_m^m
//   F_l^m     = a_lm z F_{l-1}^m + b_lm F_{l-2}^m,   l >= m + 2,
//   a_lm = sqrt((4l^2 - 1)/(l^2 - m^2)),  b_lm = -sqrt(((l-1)^2 - m^2)(2l+1)/((2l-3)(l^2 - m^2))),
// and (C, S) by complex multiplication: C_{m+1} = x C_m - y S_m, S_{m+1} = x S_m + y C_m.
// All constants are computed once at compile time (kRecurrence), so nothing is recomputed per call.
//
// Two kernels share that recurrence:
// - eval_fixed<N>: the band count is a template parameter, every loop is unrolled into straight-line
//   code with compile-time constants (Sloan's generated code, built by the compiler from templates
//   instead of by a script). Used for 1 <= bands <= kMaxFastBands. It is a sequence of steps, one per
//   (l, m >= 0), that can stop after any step and resume later (eval_steps, resume_column, recompute_cs)
//   with the same bits: eval_batch runs it in pieces at crowded strides.
// - eval_generic: runtime loops over the same tables; for any band count up to kMaxBands.
// Both are written over a value type V that is either a scalar (float, double) or a GCC/Clang vector
// extension type holding several directions (one per lane), so one source gives the single-direction
// path and the path vectorised across directions. The arithmetic is plain + and *, and the sums of two
// products are madd() (below): the one place with intrinsics.
// GCC contracts a * b + c into a fused multiply-add where the target has one (C++ default
// -ffp-contract=fast), so FMA and non-FMA builds differ in the last bits.
//
// Accuracy (tests/sh/test_eval_batch.cpp), relative to band l's bound sqrt((2l+1)/(4 pi)): double
// within 1e-13 up to 32 bands; float grows as bands^1.5: over 130 000 random directions (GCC 12 with FMA,
// clang 14 without) the worst was 9.4e-8 * bands^1.5 (5.2e-8 at 1 band, 1.6e-6 at 9, 5.0e-6 at 16,
// 1.6e-5 at 32), from the float recurrence and the float input.
#include <cstddef>
#include <cstring>
#include <type_traits>
#include <utility>

// x86 with FMA: madd (below) uses the fused multiply-add intrinsics.
#if (defined(__x86_64__) || defined(__i386__)) && defined(__FMA__)
#define PRT_SH_FMA_INTRINSICS 1
#include <immintrin.h>
#endif

#include "core/constants.h"
#include "sh/basis.h"

// PRT_SH_NO_FORCE_INLINE (set by the sanitizer builds, src/sh/CMakeLists.txt) leaves inlining to the compiler.
#if defined(__GNUC__) && !defined(PRT_SH_NO_FORCE_INLINE)
#define PRT_SH_INLINE inline __attribute__((always_inline))
#define PRT_SH_LAMBDA_INLINE __attribute__((always_inline))
#else
#define PRT_SH_INLINE inline
#define PRT_SH_LAMBDA_INLINE
#endif
#if defined(__GNUC__)
#define PRT_SH_NOINLINE __attribute__((noinline))
#else
#define PRT_SH_NOINLINE
#endif

namespace prt::sh::detail {

// ---------------------------------------------------------------------------------------------
// Vector types: one native register of directions. PRT_SH_VECTOR_BYTES overrides the width (tests
// of the narrower paths); without GNU vector extensions the "vector" is one scalar lane.
#if defined(PRT_SH_VECTOR_BYTES)
#define PRT_SH_VECTOR_BYTES_ PRT_SH_VECTOR_BYTES
#elif defined(__AVX512F__)
#define PRT_SH_VECTOR_BYTES_ 64
#elif defined(__AVX__)
#define PRT_SH_VECTOR_BYTES_ 32
#else
#define PRT_SH_VECTOR_BYTES_ 16
#endif

// PRT_SH_NO_FORCE_INLINE (set by the sanitizer builds, src/sh/CMakeLists.txt) leaves inlining to the compiler.
#if defined(__GNUC__) && !defined(PRT_SH_NO_FORCE_INLINE)
typedef float VecFloat __attribute__((vector_size(PRT_SH_VECTOR_BYTES_)));
typedef double VecDouble __attribute__((vector_size(PRT_SH_VECTOR_BYTES_)));
#else
using VecFloat = float;
using VecDouble = double;
#endif

template <typename T>
struct VectorOf;
template <>
struct VectorOf<float> {
  using type = VecFloat;
};
template <>
struct VectorOf<double> {
  using type = VecDouble;
};
/// The vector type of T and its lane count (directions evaluated per kernel call).
template <typename T>
using Vec = typename VectorOf<T>::type;
template <typename T>
inline constexpr std::size_t kLanes = sizeof(Vec<T>) / sizeof(T);

template <typename V>
struct Pair;
template <typename V>
struct IsPair : std::false_type {};
template <typename V>
struct IsPair<Pair<V>> : std::true_type {};

/// Unaligned load / store of one vector (or scalar, or Pair of vectors) V from / to T values. A Pair moves
/// as its two vectors: one memcpy of the whole struct made GCC assemble it on the stack.
template <typename V, typename T>
PRT_SH_INLINE V load(const T* p) {
  if constexpr (IsPair<V>::value) {
    using H = decltype(V::a);
    return V{load<H>(p), load<H>(p + sizeof(H) / sizeof(T))};
  } else {
    V v;
    std::memcpy(&v, p, sizeof(V));
    return v;
  }
}
template <typename V, typename T>
PRT_SH_INLINE void store(T* p, V v) {
  if constexpr (IsPair<V>::value) {
    store(p, v.a);
    store(p + sizeof(v.a) / sizeof(T), v.b);
  } else {
    std::memcpy(p, &v, sizeof(V));
  }
}
/// V with every lane equal to s (s already of V's element type).
template <typename V, typename T>
PRT_SH_INLINE V splat(T s) {
  return V{} + s;
}

/// Two vectors of directions as one value (kernels see it as one V): the kernels run on both at once,
/// and a store of a Pair writes 2 sizeof(V) contiguous bytes (a whole 64-byte line for 32-byte vectors).
template <typename V>
struct Pair {
  V a, b;
};
template <typename V>
PRT_SH_INLINE Pair<V> operator+(Pair<V> p, Pair<V> q) { return {p.a + q.a, p.b + q.b}; }
template <typename V>
PRT_SH_INLINE Pair<V> operator-(Pair<V> p, Pair<V> q) { return {p.a - q.a, p.b - q.b}; }
template <typename V>
PRT_SH_INLINE Pair<V> operator*(Pair<V> p, Pair<V> q) { return {p.a * q.a, p.b * q.b}; }
template <typename V, typename T>
PRT_SH_INLINE Pair<V> operator*(T t, Pair<V> p) { return {t * p.a, t * p.b}; }
template <typename V, typename T>
PRT_SH_INLINE Pair<V> operator+(Pair<V> p, T t) { return {p.a + t, p.b + t}; }

// ---------------------------------------------------------------------------------------------
// Multiply-adds written out. Left to itself, GCC fuses x * y + v * w into a multiply-add on whichever
// product its passes happen to leave first, and in some loops not at all: eval_batch's column tiles (the
// recurrence stepped across a tile, eval_batch.cpp) came out unfused, or fused the other way in some unrolled
// copies, so a few values differed in the last bit from the direct path's kernel (7 bands and up). So the
// kernels' sums of products are madd(x, y, z): on vectors of directions x * y + z rounded once, by the target's
// fused multiply-add instruction, on x86 with FMA (the one place with intrinsics: a loop of std::fma over the
// lanes, which GCC 12 -O3 turns into one instruction, was miscompiled by its SLP vectoriser inside the column
// tiles); on scalars and elsewhere x * y + z as written, which the compiler may fuse as it sees fit. The order
// is the one GCC chose by itself in the vector kernels, so no bits change (tests/sh, and bench files checked
// bit for bit against the build before).
#if defined(PRT_SH_FMA_INTRINSICS)
inline constexpr bool kHasFma = true;
#if defined(__AVX512F__)
inline constexpr std::size_t kFmaBytes = 64;  // the widest vector one instruction takes
#else
inline constexpr std::size_t kFmaBytes = 32;
#endif
#else
inline constexpr bool kHasFma = false;
inline constexpr std::size_t kFmaBytes = 0;
#endif

/// x * y + z (kSubtract: x * y - z) on vectors of directions, rounded once where kHasFma.
template <bool kSubtract = false, typename V>
PRT_SH_INLINE V madd(V x, V y, V z) {
  if constexpr (IsPair<V>::value) {
    return V{madd<kSubtract>(x.a, y.a, z.a), madd<kSubtract>(x.b, y.b, z.b)};
  } else if constexpr (!kHasFma || std::is_arithmetic_v<V>) {
    if constexpr (kSubtract) return x * y - z;
    else return x * y + z;
#if defined(PRT_SH_FMA_INTRINSICS)
  } else if constexpr (sizeof(V) > kFmaBytes) {
    // Wider than the target's vectors (PRT_SH_VECTOR_BYTES above them): half at a time.
    using E = std::remove_cv_t<std::remove_reference_t<decltype(x[0])>>;
    typedef E Half __attribute__((vector_size(sizeof(V) / 2)));
    Half h[3][2];
    std::memcpy(h[0], &x, sizeof(V));
    std::memcpy(h[1], &y, sizeof(V));
    std::memcpy(h[2], &z, sizeof(V));
    const Half r[2] = {madd<kSubtract>(h[0][0], h[1][0], h[2][0]), madd<kSubtract>(h[0][1], h[1][1], h[2][1])};
    V out;
    std::memcpy(&out, r, sizeof(V));
    return out;
  } else {
    constexpr bool kFloat = std::is_same_v<std::remove_cv_t<std::remove_reference_t<decltype(x[0])>>, float>;
    const V w = kSubtract ? -z : z;  // exact: fma(x, y, -z) is x y - z rounded once
#if defined(__AVX512F__)
    if constexpr (sizeof(V) == 64 && kFloat) return (V)_mm512_fmadd_ps((__m512)x, (__m512)y, (__m512)w);
    if constexpr (sizeof(V) == 64 && !kFloat) return (V)_mm512_fmadd_pd((__m512d)x, (__m512d)y, (__m512d)w);
#endif
    if constexpr (sizeof(V) == 32 && kFloat) return (V)_mm256_fmadd_ps((__m256)x, (__m256)y, (__m256)w);
    if constexpr (sizeof(V) == 32 && !kFloat) return (V)_mm256_fmadd_pd((__m256d)x, (__m256d)y, (__m256d)w);
    if constexpr (sizeof(V) == 16 && kFloat) return (V)_mm_fmadd_ps((__m128)x, (__m128)y, (__m128)w);
    if constexpr (sizeof(V) == 16 && !kFloat) return (V)_mm_fmadd_pd((__m128d)x, (__m128d)y, (__m128d)w);
    static_assert(sizeof(V) == 16 || sizeof(V) == 32 || sizeof(V) == 64, "vectors of 16, 32 or 64 bytes");
#endif
  }
}

/// Whether the kernels' sums of products on V go through madd. Scalars (the single-direction path, which
/// has no column tiles) keep the expressions as written, in that order: GCC fuses by statement order, and
/// products passed as madd's arguments come first (its fusing, and for (C_2, S_2) its x y + y x -> 2 x y,
/// changed with them: other bits in sh::eval and in bakes).
template <typename V>
inline constexpr bool kExplicitMadd = kHasFma && !std::is_arithmetic_v<V>;

/// p2 z^2 + p0 (F_{m+2}^m), as madd(p2, z^2, p0).
template <typename T, typename V>
PRT_SH_INLINE V z2_polynomial(T p2, V z2, T p0) {
  if constexpr (kExplicitMadd<V>) return madd(splat<V>(p2), z2, splat<V>(p0));
  else return p2 * z2 + p0;
}

/// The three-term recurrence F_l = (a z) F_{l-1} + b F_{l-2}, as madd(a z, F_{l-1}, b F_{l-2}).
template <typename T, typename V>
PRT_SH_INLINE V recurrence_step(T a, T b, V z, V f1, V f2) {
  if constexpr (kExplicitMadd<V>) return madd(a * z, f1, b * f2);
  else return (a * z) * f1 + b * f2;
}

// ---------------------------------------------------------------------------------------------
// Recurrence constants (double; the float kernels round each to float once).

/// Square root usable in constant expressions: Newton's iteration in long double, rounded once to
/// double (correctly rounded where long double is wider than double, within 1 ulp otherwise).
constexpr double constexpr_sqrt(double v) {
  if (!(v > 0.0)) return 0.0;
  long double r = v > 1.0 ? v : 1.0;
  for (int i = 0; i < 200; ++i) {
    long double next = 0.5L * (r + v / r);
    if (next == r) break;
    r = next;
  }
  return static_cast<double>(r);
}

struct RecurrenceTables {
  double f_mm[kMaxBands];             // F_m^m
  double f_m1[kMaxBands];             // F_{m+1}^m / z = sqrt(2m+3) F_m^m
  double a[kMaxBands][kMaxBands];     // a_lm at [l][m], l >= m + 2 (zero elsewhere)
  double b[kMaxBands][kMaxBands];     // b_lm at [l][m]
};

constexpr RecurrenceTables make_recurrence_tables() {
  RecurrenceTables t{};
  double product = 1.0;  // prod_{k=1..m} (2k-1)/(2k)
  for (int m = 0; m < kMaxBands; ++m) {
    if (m > 0) product *= (2.0 * m - 1.0) / (2.0 * m);
    double magnitude = constexpr_sqrt((m == 0 ? 1.0 : 2.0) * (2.0 * m + 1.0) / (4.0 * kPi) * product);
    t.f_mm[m] = (m % 2 == 0) ? magnitude : -magnitude;
    t.f_m1[m] = constexpr_sqrt(2.0 * m + 3.0) * t.f_mm[m];
    for (int l = m + 2; l < kMaxBands; ++l) {
      double l2 = double(l) * l, m2 = double(m) * m, lm1 = double(l - 1);
      t.a[l][m] = constexpr_sqrt((4.0 * l2 - 1.0) / (l2 - m2));
      t.b[l][m] = -constexpr_sqrt((lm1 * lm1 - m2) * (2.0 * l + 1.0) / ((2.0 * l - 3.0) * (l2 - m2)));
    }
  }
  return t;
}

inline constexpr RecurrenceTables kRecurrence = make_recurrence_tables();

// ---------------------------------------------------------------------------------------------
// Fixed band count: straight-line code. `put(k, value)` receives coefficient k (a constant after
// inlining) for every k < N^2, each exactly once.
//
// The kernel is a sequence of N (N + 1) / 2 steps, one per (l, m) with 0 <= m <= l < N in column order
// (m ascending, then l ascending); step (l, m) computes F_l^m and emits Y_l,m (and Y_l,-m). The state
// carried from step to step is (C_m, S_m) and the column's last two F, so a run of steps can stop and
// resume later from a saved KernelState (eval_steps): eval_batch's path for crowded strides evaluates
// a few rows at a time for many directions that way.

/// Step e of the N-band kernel as (l, m).
struct KernelStep {
  int l, m;
};
template <int N>
constexpr KernelStep kernel_step(int e) {
  int m = 0;
  while (e >= N - m) e -= N - m++;
  return {m + e, m};
}
/// Steps of the N-band kernel: one per (l, m >= 0).
template <int N>
inline constexpr int kKernelSteps = N * (N + 1) / 2;

/// What one step hands to the next: (C_m, S_m) of the current column, F_{l-1}^m and F_{l-2}^m.
template <typename V>
struct KernelState {
  V c, s, f1, f2;
};

// Emits Y_l,+-m (or Y_l,0) from F_l^m.
template <int L, int M, typename V, typename Put>
PRT_SH_INLINE void emit(V f, V c, V s, Put& put) {
  if constexpr (M == 0) {
    put(index(L, 0), f);
  } else {
    put(index(L, M), f * c);
    put(index(L, -M), f * s);
  }
}

// F_L^M from the column's start values or the three-term recurrence; f1 = F_{L-1}^M, f2 = F_{L-2}^M (read
// only where L >= M + 3).
template <int L, int M, typename T, typename V>
PRT_SH_INLINE V column_value(V z, V z2, V f1, V f2) {
  if constexpr (L == M) {
    return splat<V>(static_cast<T>(kRecurrence.f_mm[M]));
  } else if constexpr (L == M + 1) {
    return static_cast<T>(kRecurrence.f_m1[M]) * z;
  } else if constexpr (L == M + 2) {
    // F_{M+2}^M = a z (f_m1 z) + b f_mm, a polynomial in z^2: one multiply-add.
    constexpr T p2 = static_cast<T>(kRecurrence.a[M + 2][M] * kRecurrence.f_m1[M]);
    constexpr T p0 = static_cast<T>(kRecurrence.b[M + 2][M] * kRecurrence.f_mm[M]);
    return z2_polynomial(p2, z2, p0);
  } else {
    return recurrence_step(static_cast<T>(kRecurrence.a[L][M]), static_cast<T>(kRecurrence.b[L][M]), z, f1, f2);
  }
}

/// (C_m, S_m) -> (C_{m+1}, S_{m+1}) in place: one complex multiplication by (x + i y), each part as
/// madd(x, C or S, -+ y (S or C)).
template <typename V>
PRT_SH_INLINE void advance_cs(V x, V y, V& c, V& s) {
  if constexpr (kExplicitMadd<V>) {
    const V c_next = madd<true>(x, c, y * s);
    s = madd(x, s, y * c);
    c = c_next;
  } else {
    const V c_next = x * c - y * s;
    s = x * s + y * c;
    c = c_next;
  }
}
template <typename V>
PRT_SH_INLINE void advance_cs(V x, V y, KernelState<V>& st) {
  advance_cs(x, y, st.c, st.s);
}

// Step E: F_L^M, with (C, S) advanced by one power of (x + i y) at the start of each column m >= 1
// ((C_1, S_1) = (x, y)).
template <int N, int E, typename T, typename V, typename Put>
PRT_SH_INLINE void kernel_step_at(V x, V y, V z, V z2, KernelState<V>& st, Put& put) {
  constexpr KernelStep step = kernel_step<N>(E);
  constexpr int L = step.l, M = step.m;
  if constexpr (L == M && M == 1) {
    st.c = x;
    st.s = y;
  } else if constexpr (L == M && M > 1) {
    advance_cs(x, y, st);
  }
  const V f = column_value<L, M, T>(z, z2, st.f1, st.f2);
  st.f2 = st.f1;
  st.f1 = f;
  emit<L, M>(f, st.c, st.s, put);
}

template <int M, int L, int L1, typename T, typename V>
PRT_SH_INLINE void replay_column(V z, V z2, KernelState<V>& st) {
  if constexpr (L < L1) {
    const V f = column_value<L, M, T>(z, z2, st.f1, st.f2);
    st.f2 = st.f1;
    st.f1 = f;
    replay_column<M, L + 1, L1, T>(z, z2, st);
  }
}

template <int N, int E0, typename T, typename V, typename Put, int... I>
PRT_SH_INLINE void kernel_steps(V x, V y, V z, V z2, KernelState<V>& st, Put& put,
                                std::integer_sequence<int, I...>) {
  (kernel_step_at<N, E0 + I, T>(x, y, z, z2, st, put), ...);
}

/// Steps E0 <= e < E1 of the N-band kernel at the direction(s) (x, y, z): `put` receives the coefficients
/// of those steps, each once. `st` holds the state after step E0 - 1 on entry (nothing is read from it
/// for E0 = 0) and the state after step E1 - 1 on return. 0 <= E0 < E1 <= kKernelSteps<N>.
template <int N, int E0, int E1, typename T, typename V, typename Put>
PRT_SH_INLINE void eval_steps(V x, V y, V z, KernelState<V>& st, Put& put) {
  static_assert(1 <= N && N <= kMaxBands && 0 <= E0 && E0 < E1 && E1 <= kKernelSteps<N>, "steps out of range");
  kernel_steps<N, E0, T>(x, y, z, z * z, st, put, std::make_integer_sequence<int, E1 - E0>{});
}

/// Resuming step E0 of the N-band kernel in the middle of its column m: st.f1 and st.f2 are set to the F of
/// the column's steps before E0, recomputed by the same arithmetic as eval_steps (so the values resumed
/// from are the bits eval_steps would have carried); st.c and st.s are left as they are and must hold
/// (C_m, S_m). Nothing is done when E0 starts a column.
template <int N, int E0, typename T, typename V>
PRT_SH_INLINE void resume_column(V z, KernelState<V>& st) {
  constexpr KernelStep step = kernel_step<N>(E0);
  if constexpr (step.l > step.m) replay_column<step.m, step.m, step.l, T>(z, z * z, st);
}

/// (C_M, S_M) into st.c, st.s by the kernel's own chain from (C_1, S_1) = (x, y) (the same bits). M >= 1.
template <int M, typename V>
PRT_SH_INLINE void recompute_cs(V x, V y, KernelState<V>& st) {
  st.c = x;
  st.s = y;
  for (int m = 1; m < M; ++m) advance_cs(x, y, st);
}

/// All N^2 basis functions at the direction(s) (x, y, z), N a compile-time band count.
template <int N, typename T, typename V, typename Put>
PRT_SH_INLINE void eval_fixed(V x, V y, V z, Put& put) {
  KernelState<V> st{x, y, x, y};  // nothing of it is read before it is written
  eval_steps<N, 0, kKernelSteps<N>, T>(x, y, z, st, put);
}

// ---------------------------------------------------------------------------------------------
// Any band count: the same recurrence with runtime loops (the reference for speed comparisons and
// the path for bands > kMaxFastBands). `put(k, value)` as above.
template <typename T, typename V, typename Put>
PRT_SH_INLINE void eval_generic(int bands, V x, V y, V z, Put& put) {
  const RecurrenceTables& r = kRecurrence;
  V c = splat<V>(T(1)), s = splat<V>(T(0));  // (C_m, S_m), starting at m = 0
  for (int m = 0; m < bands; ++m) {
    if (m > 0) advance_cs(x, y, c, s);
    V f2 = splat<V>(static_cast<T>(r.f_mm[m]));
    V f1 = f2;
    for (int l = m; l < bands; ++l) {
      V f;
      if (l == m) {
        f = f2;
      } else if (l == m + 1) {
        f = static_cast<T>(r.f_m1[m]) * z;
      } else {
        f = recurrence_step(static_cast<T>(r.a[l][m]), static_cast<T>(r.b[l][m]), z, f1, f2);
      }
      f2 = f1;
      f1 = f;
      if (m == 0) {
        put(index(l, 0), f);
      } else {
        put(index(l, m), f * c);
        put(index(l, -m), f * s);
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Out-of-line entry points (defined in eval_batch.cpp), exposed for the benchmark.

/// eval_batch through eval_generic (runtime loops, vectorised across directions) for any band count
/// 1..kMaxBands; same contract as sh::eval_batch.
void eval_batch_generic(int bands, std::size_t count, const float* x, const float* y, const float* z, float* out,
                        std::size_t out_stride);
void eval_batch_generic(int bands, std::size_t count, const double* x, const double* y, const double* z,
                        double* out, std::size_t out_stride);

/// eval_accumulate through eval_generic (values weighted and added, no rescaled recurrence) for any band
/// count 1..kMaxBands; same contract as sh::eval_accumulate (eval_accumulate.cpp).
void eval_accumulate_generic(int bands, std::size_t count, const float* x, const float* y, const float* z,
                             const float* w, float* sums);
void eval_accumulate_generic(int bands, std::size_t count, const double* x, const double* y, const double* z,
                             const double* w, double* sums);

/// The write order of eval_batch at crowded strides (such as out_stride = count = 1024 floats), for the
/// benchmark's bound: directions per tile for `count` directions (count >= the vector width) of
/// element_bytes (4 or 8), and how many rows are written together along a tile, a vector of directions
/// into each in turn, before the next rows (1: each row's run of the tile at once).
std::size_t staged_tile_directions(int bands, std::size_t count, std::size_t element_bytes);
int staged_pass_rows(int bands);

/// One direction through eval_generic (scalar runtime loops); same contract as sh::eval.
void eval_one_generic(int bands, float x, float y, float z, float* out);
void eval_one_generic(int bands, double x, double y, double z, double* out);

}  // namespace prt::sh::detail
