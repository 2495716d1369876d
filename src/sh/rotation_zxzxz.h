#pragma once
// Private to rotation.cpp: the float fast paths of prt::sh::rotate and rotate_rgb.
//
// zxzxz (Sloan, "Stupid Spherical Harmonics Tricks", GDC 2008; Pinchon & Hoggan, J. Phys. A 40, 1597
// (2007)): with R = Rz(alpha) Ry(beta) Rz(gamma) and Ry(beta) = Rx(-90) Rz(beta) Rx(+90),
//   Rot(R) = Z(alpha) X(-90) Z(beta) X(+90) Z(gamma) = Z(alpha + pi) X(+90) Z(beta + pi) X(+90) Z(gamma),
// using Rx(-90) = Rz(pi) Rx(+90) Rz(pi). Z(theta) only mixes the pair (m, -m) of each band:
//   c'_m = cos(m theta) c_m - sin(m theta) c_-m,   c'_-m = sin(m theta) c_m + cos(m theta) c_-m,
// and X(+90) is the fixed sparse table of rotation_x90_table.h, applied band by band through one
// fully unrolled function per band (its entries become constants).
//
// The Euler angles never appear: their cosines and sines come from R's entries by square roots, and
// the multiples m theta by complex multiplication. Near gimbal lock (sin beta ~ 0) gamma (read from
// R's last row) is poorly defined; alpha is then derived from the well-defined alpha + gamma (or
// alpha - gamma near beta = pi), so that the composed rotation stays accurate to float precision
// whatever gamma's error: Rz(s - g') Ry(beta) Rz(g') differs from the exact one by O(|g' - g| beta).
#include <array>
#include <cmath>
#include <utility>

#include <glm/mat3x3.hpp>

#include "sh/basis.h"
#include "sh/rotation_x90_table.h"

namespace prt::sh::detail {

static_assert(kX90Bands == kMaxFastBands, "regenerate rotation_x90_table.h for kMaxFastBands");

/// cos and sin of one angle and of its multiples.
struct CosSin {
  float c = 1, s = 0;
};

/// Cosines and sines of the ZYZ Euler angles of r: r = Rz(alpha) Ry(beta) Rz(gamma), beta in [0, pi].
struct EulerZyz {
  CosSin alpha, beta, gamma;
};

inline CosSin normalised(float c, float s) {
  const float inv = 1.0f / std::sqrt(c * c + s * s);
  return {c * inv, s * inv};
}

/// Precondition: r orthonormal with det +1 to float precision. r[col][row] as in GLM.
inline EulerZyz euler_zyz(const glm::mat3& r) {
  // Entries named by (row, col) of the column-vector matrix.
  const float r00 = r[0][0], r01 = r[1][0];
  const float r10 = r[0][1], r11 = r[1][1];
  const float r20 = r[0][2], r21 = r[1][2], r22 = r[2][2];
  // Row 2 is (-sin beta cos gamma, sin beta sin gamma, cos beta). gamma is needed first (Z(gamma)
  // is applied first), so it comes straight from r; alpha follows from gamma below.
  const float sin_beta_sq = r20 * r20 + r21 * r21;
  const float sin_beta = std::sqrt(sin_beta_sq);
  const float inv_row = 1.0f / std::sqrt(sin_beta_sq + r22 * r22);
  EulerZyz e;
  e.beta = {r22 * inv_row, sin_beta * inv_row};
  if (sin_beta > 1e-18f) {
    const float inv_sin_beta = 1.0f / sin_beta;
    e.gamma = {-r20 * inv_sin_beta, r21 * inv_sin_beta};
  }
  // The upper-left 2x2 block gives alpha + gamma with weight (1 + cos beta) and alpha - gamma with
  // weight (1 - cos beta); use whichever weight is at least 1, so that alpha absorbs gamma's error
  // when sin beta is small.
  if (r22 >= 0) {
    const CosSin sum = normalised(r00 + r11, r10 - r01);  // alpha + gamma
    e.alpha = {sum.c * e.gamma.c + sum.s * e.gamma.s, sum.s * e.gamma.c - sum.c * e.gamma.s};
  } else {
    const CosSin diff = normalised(r11 - r00, -(r10 + r01));  // alpha - gamma
    e.alpha = {diff.c * e.gamma.c - diff.s * e.gamma.s, diff.s * e.gamma.c + diff.c * e.gamma.s};
  }
  return e;
}

/// cos(m theta), sin(m theta) for m < count, times (-1)^m when `add_pi` (the angle theta + pi).
/// Each multiple is a product of two earlier ones, so dependency chains stay short.
inline void multiples(int count, CosSin a, bool add_pi, float* cos_m, float* sin_m) {
  cos_m[0] = 1;
  sin_m[0] = 0;
  if (count > 1) {
    cos_m[1] = add_pi ? -a.c : a.c;  // (-z)^m = (-1)^m z^m
    sin_m[1] = add_pi ? -a.s : a.s;
  }
  for (int m = 2; m < count; ++m) {
    const int i = (m + 1) / 2, j = m / 2;
    cos_m[m] = cos_m[i] * cos_m[j] - sin_m[i] * sin_m[j];
    sin_m[m] = sin_m[i] * cos_m[j] + cos_m[i] * sin_m[j];
  }
}

/// out = Z(theta) in for bands 0..bands-1, from the tables of multiples. in and out must not alias.
inline void apply_z(int bands, const float* __restrict cos_m, const float* __restrict sin_m,
                    const float* __restrict in, float* __restrict out) {
  out[0] = in[0];
  for (int l = 1; l < bands; ++l) {
    const int centre = l * (l + 1);
    out[centre] = in[centre];
    for (int m = 1; m <= l; ++m) {
      const float pos = in[centre + m], neg = in[centre - m];
      out[centre + m] = cos_m[m] * pos - sin_m[m] * neg;
      out[centre - m] = sin_m[m] * pos + cos_m[m] * neg;
    }
  }
}

/// X(+90) on sub-block S of band L: `in` and `out` point at the band's first coefficient
/// (index(L, -L)). Fully unrolled, the table's entries become constants. in and out must not alias.
template <int L, int S>
[[gnu::always_inline]] inline void apply_x90_sub_block(const float* in, float* out) {
  constexpr X90SubBlock b = kX90SubBlocks[L][S];
#pragma GCC unroll 16
  for (int i = 0; i < b.rows; ++i) {
    const float* values = kX90Values + b.offset + i * b.cols;
    float sum = values[0] * in[L + b.col_start];
#pragma GCC unroll 16
    for (int k = 1; k < b.cols; ++k) sum += values[k] * in[L + b.col_start + k * b.col_step];
    out[L + b.row_start + i * b.row_step] = sum;
  }
}

template <int L>
void apply_x90_band(const float* in, float* out) {
  apply_x90_sub_block<L, 0>(in, out);
  apply_x90_sub_block<L, 1>(in, out);
  apply_x90_sub_block<L, 2>(in, out);
  apply_x90_sub_block<L, 3>(in, out);
}

using X90BandFunction = void (*)(const float* in, float* out);

template <int... L>
constexpr std::array<X90BandFunction, sizeof...(L)> x90_band_functions(std::integer_sequence<int, L...>) {
  return {&apply_x90_band<L>...};
}

/// apply_x90_band<l> for every l < kX90Bands.
inline constexpr std::array<X90BandFunction, kX90Bands> kX90BandFunctions =
    x90_band_functions(std::make_integer_sequence<int, kX90Bands>());

/// cos and sin of m gamma, m (beta + pi), m (alpha + pi) for m < kMaxFastBands.
struct ZxzxzAngles {
  float cos_g[kMaxFastBands], sin_g[kMaxFastBands];
  float cos_b[kMaxFastBands], sin_b[kMaxFastBands];
  float cos_a[kMaxFastBands], sin_a[kMaxFastBands];
};

inline ZxzxzAngles zxzxz_angles(int bands, const glm::mat3& r) {
  const EulerZyz e = euler_zyz(r);
  ZxzxzAngles z;
  multiples(bands, e.gamma, false, z.cos_g, z.sin_g);
  multiples(bands, e.beta, true, z.cos_b, z.sin_b);
  multiples(bands, e.alpha, true, z.cos_a, z.sin_a);
  return z;
}

/// One channel of `bands` bands (1 <= bands <= kMaxFastBands): out = Z(alpha+pi) X Z(beta+pi) X Z(gamma) in.
/// in and out must not alias.
inline void rotate_zxzxz(int bands, const ZxzxzAngles& z, const float* in, float* out) {
  float t0[kMaxFastBands * kMaxFastBands], t1[kMaxFastBands * kMaxFastBands];
  apply_z(bands, z.cos_g, z.sin_g, in, t0);
  for (int l = 0; l < bands; ++l) kX90BandFunctions[l](t0 + l * l, t1 + l * l);
  apply_z(bands, z.cos_b, z.sin_b, t1, t0);
  for (int l = 0; l < bands; ++l) kX90BandFunctions[l](t0 + l * l, t1 + l * l);
  apply_z(bands, z.cos_a, z.sin_a, t1, out);
}

}  // namespace prt::sh::detail
