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
//   instead of by a script). Used for 1 <= bands <= kMaxFastBands.
// - eval_generic: runtime loops over the same tables; for any band count up to kMaxBands.
// Both are written over a value type V that is either a scalar (float, double) or a GCC/Clang vector
// extension type holding several directions (one per lane), so one source gives the single-direction
// path and the path vectorised across directions. The arithmetic is plain + and *; GCC contracts
// a * b + c into a fused multiply-add where the target has one (C++ default -ffp-contract=fast), so FMA
// and non-FMA builds differ in the last bits.
//
// Accuracy (tests/sh/test_eval_batch.cpp), relative to band l's bound sqrt((2l+1)/(4 pi)): double
// within 1e-13 up to 32 bands; float grows as bands^1.5: over 130 000 random directions (GCC 12 with FMA,
// clang 14 without) the worst was 9.4e-8 * bands^1.5 (5.2e-8 at 1 band, 1.6e-6 at 9, 5.0e-6 at 16,
// 1.6e-5 at 32), from the float recurrence and the float input.
#include <cstddef>
#include <cstring>
#include <type_traits>

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

namespace prt::sh::detail {

// ---------------------------------------------------------------------------------------------
// Vector types: one native register of directions; without GNU vector extensions, and in the sanitizer
// builds, the "vector" is one scalar lane.
#if defined(__AVX512F__)
#define PRT_SH_VECTOR_BYTES_ 64
#elif defined(__AVX__)
#define PRT_SH_VECTOR_BYTES_ 32
#else
#define PRT_SH_VECTOR_BYTES_ 16
#endif
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
/// The three-term recurrence F_l = (a z) F_{l-1} + b F_{l-2}.
template <typename T, typename V>
PRT_SH_INLINE V recurrence_step(T a, T b, V z, V f1, V f2) {
  return (a * z) * f1 + b * f2;
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
// inlining) for every k < N^2, each exactly once, column by column (m ascending, then l ascending).

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
    return p2 * z2 + p0;
  } else {
    return recurrence_step(static_cast<T>(kRecurrence.a[L][M]), static_cast<T>(kRecurrence.b[L][M]), z, f1, f2);
  }
}

/// (C_m, S_m) -> (C_{m+1}, S_{m+1}) in place: one complex multiplication by (x + i y).
template <typename V>
PRT_SH_INLINE void advance_cs(V x, V y, V& c, V& s) {
  const V c_next = x * c - y * s;
  s = x * s + y * c;
  c = c_next;
}

// Rows L..N-1 of column M, given F_{L-1}^M (f1) and F_{L-2}^M (f2) and the column's (C_M, S_M).
template <int N, int M, int L, typename T, typename V, typename Put>
PRT_SH_INLINE void eval_column(V z, V z2, V c, V s, V f1, V f2, Put& put) {
  if constexpr (L < N) {
    const V f = column_value<L, M, T>(z, z2, f1, f2);
    emit<L, M>(f, c, s, put);
    eval_column<N, M, L + 1, T>(z, z2, c, s, f, f1, put);
  }
}

// Columns M..N-1, given (C_{M-1}, S_{M-1}) (anything for M <= 1: (C_1, S_1) = (x, y)).
template <int N, int M, typename T, typename V, typename Put>
PRT_SH_INLINE void eval_columns(V x, V y, V z, V z2, V c, V s, Put& put) {
  if constexpr (M < N) {
    if constexpr (M == 1) {
      c = x;
      s = y;
    } else if constexpr (M > 1) {
      advance_cs(x, y, c, s);
    }
    eval_column<N, M, M, T>(z, z2, c, s, c, s, put);  // the column's first two values read no f1, f2
    eval_columns<N, M + 1, T>(x, y, z, z2, c, s, put);
  }
}

/// All N^2 basis functions at the direction(s) (x, y, z), N a compile-time band count.
template <int N, typename T, typename V, typename Put>
PRT_SH_INLINE void eval_fixed(V x, V y, V z, Put& put) {
  static_assert(1 <= N && N <= kMaxBands, "band count out of range");
  eval_columns<N, 0, T>(x, y, z, z * z, x, y, put);
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
// Out-of-line entry points (defined in eval_batch.cpp), exposed for the tests and the benchmark.

/// eval_batch through eval_generic (runtime loops, vectorised across directions) for any band count
/// 1..kMaxBands; same contract as sh::eval_batch.
void eval_batch_generic(int bands, std::size_t count, const float* x, const float* y, const float* z, float* out,
                        std::size_t out_stride);
void eval_batch_generic(int bands, std::size_t count, const double* x, const double* y, const double* z,
                        double* out, std::size_t out_stride);

/// One direction through eval_generic (scalar runtime loops); same contract as sh::eval.
void eval_one_generic(int bands, float x, float y, float z, float* out);
void eval_one_generic(int bands, double x, double y, double z, double* out);

}  // namespace prt::sh::detail
