#pragma once
// Private to rotation.cpp: the zxzxz rotation (see rotation_zxzxz.h) for 4 and 5 bands in 16-lane
// vectors (GCC/Clang vector extensions: one AVX-512 register under an AVX-512 -march, two AVX or
// four SSE registers otherwise).
//
// Layout: a coefficient vector of B bands is held as two vectors P and N with lane
// j(l, m) = l(l+1)/2 + m for 0 <= m <= l (B(B+1)/2 <= 15 lanes): P[j] = c_(l,m), N[j] = c_(l,-m)
// (N's lanes with m = 0 are unused). Then Z(theta) is lane-wise,
//   P' = C P - S N,   N' = S P + C N,   C[j] = cos(m theta), S[j] = sin(m theta),
// and X(+90), whose rows have at most K = (B+1)/2 non-zeros, is K gathers (two-source permutes of
// P and N) times constant vectors per output: out = sum_k D_k * gather_k(P, N).
// The multiples m theta of all three angles are computed together, one lane per (angle, m).
#include <cstring>

#include "sh/rotation_zxzxz.h"

// Every function here is inlined into rotation.cpp, so no vector crosses a call boundary and GCC's
// note that 64-byte vectors change the calling convention without AVX-512 does not apply.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace prt::sh::detail {

typedef float V16 __attribute__((vector_size(64)));
typedef int I16 __attribute__((vector_size(64)));

/// Compile-time tables of the P/N layout for B bands (4 or 5).
template <int B>
struct PnLayout {
  static constexpr int kSlots = (B + 1) / 2;  // most non-zeros in one row of X(+90)
  // Input: P = shuffle(lo, hi, in_p), N = shuffle(lo, hi, in_n), lo = flat coefficients 0..15,
  // hi = flat coefficients B^2-16..B^2-1 (both loads stay inside the array).
  int in_p[16] = {}, in_n[16] = {};
  // Output: flat 0..15 = shuffle(P, N, out_lo), flat B^2-16.. = shuffle(P, N, out_hi).
  int out_lo[16] = {}, out_hi[16] = {};
  // Multiples: lane a*B + m holds angle a's m-th multiple. bit_k: lanes whose m has bit k set.
  int angle_c[16] = {}, angle_s[16] = {}, bit[3][16] = {};
  // Angle a's cos/sin vector in P/N layout = shuffle(multiples, spread[a]).
  int spread[3][16] = {};
  // X(+90): output o (0 = P, 1 = N) = sum_k value[o][k] * shuffle(P, N, source[o][k]).
  int source[2][kSlots][16] = {};
  alignas(64) float value[2][kSlots][16] = {};
};

constexpr int pn_lane(int l, int m) { return l * (l + 1) / 2 + (m < 0 ? -m : m); }

template <int B>
constexpr PnLayout<B> make_pn_layout() {
  static_assert(B * (B + 1) / 2 <= 16 && B * B >= 16 && 3 * B <= 16, "the P/N kernel covers 4 and 5 bands");
  PnLayout<B> t{};
  constexpr int n = B * B, hi_first = n - 16;
  auto source = [](int flat) { return flat < 16 ? flat : 16 + (flat - hi_first); };
  for (int l = 0; l < B; ++l)
    for (int m = 0; m <= l; ++m) {
      t.in_p[pn_lane(l, m)] = source(index(l, m));
      t.in_n[pn_lane(l, m)] = source(index(l, -m));
      for (int a = 0; a < 3; ++a) t.spread[a][pn_lane(l, m)] = a * B + m;
    }
  for (int flat = 0; flat < n; ++flat) {
    int l = 0;
    while ((l + 1) * (l + 1) <= flat) ++l;
    const int m = flat - l * (l + 1);
    const int from = (m < 0 ? 16 : 0) + pn_lane(l, m);
    if (flat < 16) t.out_lo[flat] = from;
    if (flat >= hi_first) t.out_hi[flat - hi_first] = from;
  }
  for (int a = 0; a < 3; ++a)
    for (int m = 0; m < B; ++m) {
      t.angle_c[a * B + m] = 2 * a;
      t.angle_s[a * B + m] = 2 * a + 1;
      for (int k = 0; k < 3; ++k) t.bit[k][a * B + m] = (m >> k) & 1;
    }
  int used[2][16] = {};
  for (int l = 0; l < B; ++l)
    for (const X90SubBlock& b : kX90SubBlocks[l])
      for (int row = 0; row < b.rows; ++row) {
        const int m = b.row_start + row * b.row_step;
        const int o = m < 0, lane = pn_lane(l, m);
        for (int col = 0; col < b.cols; ++col) {
          const int n_in = b.col_start + col * b.col_step;
          const int slot = used[o][lane]++;
          t.source[o][slot][lane] = (n_in < 0 ? 16 : 0) + pn_lane(l, n_in);
          t.value[o][slot][lane] = kX90Values[b.offset + row * b.cols + col];
        }
      }
  return t;
}

template <int B>
inline constexpr PnLayout<B> kPnLayout = make_pn_layout<B>();

[[gnu::always_inline]] inline V16 load16(const float* p) {
  V16 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

[[gnu::always_inline]] inline void store16(float* p, const V16& v) { std::memcpy(p, &v, sizeof v); }

[[gnu::always_inline]] inline I16 indices(const int (&i)[16]) {
  I16 v;
  std::memcpy(&v, i, sizeof v);
  return v;
}

/// Lanes of a (indices 0..15) and b (16..31) picked by idx: a two-source permute.
[[gnu::always_inline]] inline V16 shuffle(const V16& a, const V16& b, const I16& idx) {
#if defined(__clang__)
  V16 r;
  for (int i = 0; i < 16; ++i) r[i] = idx[i] < 16 ? a[idx[i]] : b[idx[i] - 16];
  return r;
#else
  return __builtin_shuffle(a, b, idx);
#endif
}

/// cos(m theta) (c) and sin(m theta) (s) in P/N layout for the three angles gamma, beta + pi,
/// alpha + pi of r's ZYZ decomposition.
struct PnAngles {
  V16 c[3], s[3];
};

template <int B>
[[gnu::always_inline]] inline PnAngles pn_angles(const glm::mat3& r) {
  const PnLayout<B>& t = kPnLayout<B>;
  const EulerZyz e = euler_zyz(r);
  // (-z)^m = (-1)^m z^m: the angle plus pi.
  const V16 pairs = {e.gamma.c, e.gamma.s, -e.beta.c, -e.beta.s, -e.alpha.c, -e.alpha.s};
  const V16 zc = shuffle(pairs, pairs, indices(t.angle_c));
  const V16 zs = shuffle(pairs, pairs, indices(t.angle_s));
  const V16 one = V16{} + 1.0f, zero = V16{};
  // z^m as the product of z^(2^k) over the bits k of m.
  V16 re = indices(t.bit[0]) != 0 ? zc : one;
  V16 im = indices(t.bit[0]) != 0 ? zs : zero;
  V16 pc = zc, ps = zs;
  for (int k = 1; (1 << k) < B; ++k) {
    const V16 square_c = pc * pc - ps * ps, square_s = 2.0f * pc * ps;
    pc = square_c;
    ps = square_s;
    const V16 fc = indices(t.bit[k]) != 0 ? pc : one;
    const V16 fs = indices(t.bit[k]) != 0 ? ps : zero;
    const V16 new_re = re * fc - im * fs;
    im = re * fs + im * fc;
    re = new_re;
  }
  PnAngles out;
  for (int a = 0; a < 3; ++a) {
    out.c[a] = shuffle(re, re, indices(t.spread[a]));
    out.s[a] = shuffle(im, im, indices(t.spread[a]));
  }
  return out;
}

[[gnu::always_inline]] inline void pn_apply_z(const V16& c, const V16& s, V16& p, V16& n) {
  const V16 new_p = c * p - s * n;
  n = s * p + c * n;
  p = new_p;
}

template <int B>
[[gnu::always_inline]] inline void pn_apply_x90(V16& p, V16& n) {
  const PnLayout<B>& t = kPnLayout<B>;
  V16 out[2];
  for (int o = 0; o < 2; ++o) {
    out[o] = load16(t.value[o][0]) * shuffle(p, n, indices(t.source[o][0]));
    for (int k = 1; k < PnLayout<B>::kSlots; ++k)
      out[o] += load16(t.value[o][k]) * shuffle(p, n, indices(t.source[o][k]));
  }
  p = out[0];
  n = out[1];
}

/// One channel of B bands: out = Z(alpha+pi) X Z(beta+pi) X Z(gamma) in. in and out must not alias.
template <int B>
[[gnu::always_inline]] inline void pn_rotate(const PnAngles& z, const float* in, float* out) {
  const PnLayout<B>& t = kPnLayout<B>;
  constexpr int hi_first = B * B - 16;
  const V16 lo = load16(in), hi = load16(in + hi_first);
  V16 p = shuffle(lo, hi, indices(t.in_p));
  V16 n = shuffle(lo, hi, indices(t.in_n));
  pn_apply_z(z.c[0], z.s[0], p, n);
  pn_apply_x90<B>(p, n);
  pn_apply_z(z.c[1], z.s[1], p, n);
  pn_apply_x90<B>(p, n);
  pn_apply_z(z.c[2], z.s[2], p, n);
  store16(out + hi_first, shuffle(p, n, indices(t.out_hi)));
  store16(out, shuffle(p, n, indices(t.out_lo)));
}

/// rotate / rotate_rgb for 4 and 5 bands: Channels interleaved floats per coefficient.
template <int B, int Channels>
void rotate_pn(const glm::mat3& r, const float* in, float* out) {
  const PnAngles z = pn_angles<B>(r);
  if constexpr (Channels == 1) {
    pn_rotate<B>(z, in, out);
  } else {
    // De-interleave all channels in one pass, rotate each, re-interleave.
    float planar_in[Channels][B * B], planar_out[Channels][B * B];
    for (int i = 0; i < B * B; ++i)
      for (int ch = 0; ch < Channels; ++ch) planar_in[ch][i] = in[i * Channels + ch];
    for (int ch = 0; ch < Channels; ++ch) pn_rotate<B>(z, planar_in[ch], planar_out[ch]);
    for (int i = 0; i < B * B; ++i)
      for (int ch = 0; ch < Channels; ++ch) out[i * Channels + ch] = planar_out[ch][i];
  }
}

}  // namespace prt::sh::detail

#pragma GCC diagnostic pop
