// The float fast paths of sh/rotation.h (rotate, rotate_rgb: closed form up to 3 bands, zxzxz beyond)
// and FloatRotation (sh/rotation_float.h). The double Rotation is in rotation_blocks.cpp.
#include "sh/rotation.h"

#include <cmath>
#include <string>

#include <glm/mat3x3.hpp>

#include "sh/rotation_float.h"
#include "sh/rotation_simd.h"
#include "sh/rotation_zxzxz.h"

namespace prt::sh {

namespace {

bool is_identity(const glm::mat3& r) { return r == glm::mat3(1.0f); }

// Bands 1..3 in closed form. Band 1 is r conjugated by the signed permutation c -> (x, y, z) =
// (-c_1,1, -c_1,-1, c_1,0). Band 2 is a symmetric traceless quadratic form f(d) = d^T Q d, rotated
// as Q' = R Q R^T (f'(d) = f(R^T d)), with Y_2 = (k1 xy, -k1 yz, k2 (2z^2 - x^2 - y^2), -k1 xz,
// k3 (x^2 - y^2)) on the unit sphere.
template <int Channels>
void rotate_closed_form(int bands, const glm::mat3& r, const float* in, float* out) {
  for (int ch = 0; ch < Channels; ++ch) out[ch] = in[ch];
  if (bands < 2) return;
  for (int ch = 0; ch < Channels; ++ch) {
    const float* c = in + ch;
    float* o = out + ch;
    const glm::vec3 a(-c[3 * Channels], -c[1 * Channels], c[2 * Channels]);
    const glm::vec3 ra = r * a;
    o[1 * Channels] = -ra.y;
    o[2 * Channels] = ra.z;
    o[3 * Channels] = -ra.x;
  }
  if (bands < 3) return;
  // Q scaled by 2/k1 for its off-diagonal entries: q_xy = c4, q_yz = -c5, q_xz = -c7, and the
  // diagonal by the same factor: q_xx = (2/k1)(-k2 c6 + k3 c8), q_yy = (2/k1)(-k2 c6 - k3 c8),
  // q_zz = (2/k1) 2 k2 c6. Note 2 k3 / k1 = 1 and 2 k2 / k1 = 1/sqrt(3).
  constexpr float kInvSqrt3 = 0.577350269189625764f;
  for (int ch = 0; ch < Channels; ++ch) {
    const float* c = in + ch;
    float* o = out + ch;
    const float c4 = c[4 * Channels], c5 = c[5 * Channels], c6 = c[6 * Channels], c7 = c[7 * Channels],
                c8 = c[8 * Channels];
    const float d6 = kInvSqrt3 * c6;
    const glm::mat3 q(glm::vec3(c8 - d6, c4, -c7), glm::vec3(c4, -c8 - d6, -c5), glm::vec3(-c7, -c5, 2 * d6));
    const glm::mat3 rq = r * q;
    // Q'_ij = row i of R Q dotted with row j of R, i.e. sum_k rq[k][i] r[k][j].
    auto qp = [&](int i, int j) { return rq[0][i] * r[0][j] + rq[1][i] * r[1][j] + rq[2][i] * r[2][j]; };
    o[4 * Channels] = qp(0, 1);
    o[5 * Channels] = -qp(1, 2);
    o[6 * Channels] = 0.5f * (1.0f / kInvSqrt3) * qp(2, 2);
    o[7 * Channels] = -qp(0, 2);
    o[8 * Channels] = 0.5f * (qp(0, 0) - qp(1, 1));
  }
}

// Bands 6..kMaxFastBands, Channels interleaved floats per coefficient: one zxzxz pass per channel
// sharing the angles.
template <int Channels>
void rotate_zxzxz_channels(int bands, const glm::mat3& r, const float* in, float* out) {
  const detail::ZxzxzAngles z = detail::zxzxz_angles(bands, r);
  if constexpr (Channels == 1) {
    detail::rotate_zxzxz(bands, z, in, out);
  } else {
    const int count = bands * bands;
    float planar_in[kMaxFastBands * kMaxFastBands], planar_out[kMaxFastBands * kMaxFastBands];
    for (int ch = 0; ch < Channels; ++ch) {
      for (int i = 0; i < count; ++i) planar_in[i] = in[i * Channels + ch];
      detail::rotate_zxzxz(bands, z, planar_in, planar_out);
      for (int i = 0; i < count; ++i) out[i * Channels + ch] = planar_out[i];
    }
  }
}

template <int Channels>
void rotate_fast(int bands, const glm::mat3& r, const float* in, float* out) {
  if (bands <= 3) {
    rotate_closed_form<Channels>(bands, r, in, out);
  } else if (bands == 4) {
    detail::rotate_pn<4, Channels>(r, in, out);
  } else if (bands == 5) {
    detail::rotate_pn<5, Channels>(r, in, out);
  } else {
    rotate_zxzxz_channels<Channels>(bands, r, in, out);
  }
}

}  // namespace

void rotate(int bands, const glm::mat3& r, const float* in, float* out) {
  if (is_identity(r)) {
    for (int i = 0; i < bands * bands; ++i) out[i] = in[i];
    return;
  }
  if (bands <= kMaxFastBands) {
    rotate_fast<1>(bands, r, in, out);
    return;
  }
  Rotation(bands, glm::dmat3(r)).apply(in, out);
}

void rotate_rgb(int bands, const glm::mat3& r, const glm::vec3* in, glm::vec3* out) {
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "glm::vec3 must be three packed floats");
  if (is_identity(r)) {
    for (int i = 0; i < bands * bands; ++i) out[i] = in[i];
    return;
  }
  const float* in_floats = &in[0].x;
  float* out_floats = &out[0].x;
  if (bands <= kMaxFastBands) {
    rotate_fast<3>(bands, r, in_floats, out_floats);
    return;
  }
  const Rotation rotation(bands, glm::dmat3(r));
  const int n = bands * bands;
  std::vector<float> channel_in(n), channel_out(n);
  for (int ch = 0; ch < 3; ++ch) {
    for (int i = 0; i < n; ++i) channel_in[i] = in_floats[i * 3 + ch];
    rotation.apply(channel_in.data(), channel_out.data());
    for (int i = 0; i < n; ++i) out_floats[i * 3 + ch] = channel_out[i];
  }
}

}  // namespace prt::sh

// ---------------------------------------------------------------------------------------------------
// FloatRotation (rotation_float.h)

namespace prt::sh {

namespace {

// out[m] = sum_k block[m * W + k] in[k] for one band of width W (compile-time: fully unrolled).
template <int W, typename V>
inline void apply_band(const float* block, const V* in, V* out) {
  for (int m = 0; m < W; ++m) {
    V sum = block[m * W] * in[0];
    for (int k = 1; k < W; ++k) sum += block[m * W + k] * in[k];
    out[m] = sum;
  }
}

// Bands of any width: each row's sum in 8 interleaved partial sums (independent chains the compiler can
// keep in one vector register; one chain of 2l + 1 dependent multiply-adds made 16 bands 2x slower than
// the double Rotation::apply), added in a fixed order.
template <typename V>
inline void apply_band_any(int w, const float* block, const V* in, V* out) {
  constexpr int kPartial = 8;
  for (int m = 0; m < w; ++m) {
    const float* row = block + m * w;
    V s[kPartial] = {};
    int k = 0;
    for (; k + kPartial <= w; k += kPartial)
      for (int j = 0; j < kPartial; ++j) s[j] += row[k + j] * in[k + j];
    for (; k < w; ++k) s[0] += row[k] * in[k];
    out[m] = ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
  }
}

template <typename V>
void apply_float_blocks(int bands, const float* blocks, const V* in, V* out) {
  for (int l = 0; l < bands; ++l) {
    const int w = 2 * l + 1, first = l * l;
    const float* block = blocks + static_cast<std::size_t>(l) * (2 * l - 1) * (2 * l + 1) / 3;
    switch (l) {
      case 0: out[0] = in[0]; break;
      case 1: apply_band<3>(block, in + first, out + first); break;
      case 2: apply_band<5>(block, in + first, out + first); break;
      case 3: apply_band<7>(block, in + first, out + first); break;
      case 4: apply_band<9>(block, in + first, out + first); break;
      default: apply_band_any(w, block, in + first, out + first); break;
    }
  }
}

}  // namespace

FloatRotation::FloatRotation(const Rotation& rotation) : bands_(rotation.bands()) {
  for (int l = 0; l < bands_; ++l) {
    const int w = 2 * l + 1;
    const double* block = rotation.block(l);
    for (int i = 0; i < w * w; ++i) blocks_.push_back(static_cast<float>(block[i]));
  }
}

void FloatRotation::apply(const float* in, float* out) const { apply_float_blocks(bands_, blocks_.data(), in, out); }

void FloatRotation::apply_rgb(const glm::vec3* in, glm::vec3* out) const {
  apply_float_blocks(bands_, blocks_.data(), in, out);
}

}  // namespace prt::sh
