#include "sh/rotation.h"

#include <cmath>
#include <string>

#include <glm/mat3x3.hpp>

#include "core/error.h"
#include "sh/rotation_float.h"
#include "sh/rotation_simd.h"
#include "sh/rotation_zxzxz.h"

namespace prt::sh {

namespace {

// cos and sin of an angle in degrees, exact (0, +-1) at multiples of 90 degrees.
void cos_sin_degrees(double degrees, double& c, double& s) {
  if (!std::isfinite(degrees)) fail("rotation angle " + std::to_string(degrees) + " degrees is not finite");
  double reduced = std::fmod(degrees, 360.0);
  double quadrant = std::nearbyint(reduced / 90.0);
  double rest = (reduced - 90.0 * quadrant) * (M_PI / 180.0);
  double c0 = std::cos(rest), s0 = std::sin(rest);
  switch ((static_cast<int>(quadrant) % 4 + 4) % 4) {
    case 0: c = c0, s = s0; break;
    case 1: c = -s0, s = c0; break;
    case 2: c = -c0, s = -s0; break;
    default: c = s0, s = -c0; break;
  }
}

// Row-major element (row, col) of a GLM (column-major) matrix.
double at(const glm::dmat3& r, int row, int col) { return r[col][row]; }

// The nearest rotation to r (its orthogonal polar factor) by Newton's iteration
// Q <- (Q + Q^-T) / 2, which converges quadratically from a nearly orthonormal r and leaves an exactly
// orthonormal one with entries in {0, +-1} untouched.
glm::dmat3 nearest_rotation(const glm::dmat3& r) {
  glm::dmat3 gram = glm::transpose(r) * r;
  double drift = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) drift = std::fmax(drift, std::abs(gram[i][j] - (i == j ? 1.0 : 0.0)));
  double det = glm::determinant(r);
  if (!(drift <= 1e-3) || !(det > 0))
    fail("SH rotation: the matrix is not a rotation (|R^T R - I| = " + std::to_string(drift) +
         ", det = " + std::to_string(det) + ")");
  glm::dmat3 q = r;
  for (int iteration = 0; iteration < 3; ++iteration) q = 0.5 * (q + glm::transpose(glm::inverse(q)));
  return q;
}

bool is_identity(const glm::dmat3& r) { return r == glm::dmat3(1.0); }
bool is_identity(const glm::mat3& r) { return r == glm::mat3(1.0f); }

// Offset of band l's block in the concatenated storage: sum_{k<l} (2k+1)^2 = l(2l-1)(2l+1)/3.
std::size_t block_offset(int l) { return static_cast<std::size_t>(l) * (2 * l - 1) * (2 * l + 1) / 3; }

// Band l >= 2 of the Ivanic-Ruedenberg recursion (J. Phys. Chem. 100, 6342 (1996), Table 2 with
// the errata of J. Phys. Chem. A 102, 9099 (1998)): out = B^l from r1 = band 1 in the paper's basis
// (no Condon-Shortley phase: r1 is R with rows and columns ordered y, z, x) and prev = B^(l-1) WITH
// the phase, all row-major with index (m + l). `root` holds sqrt(k) and `inv_root` 1/sqrt(k) for
// k <= 2l.
//
// The paper's M^l_mn = u U + v V + w W, where U, V, W are sums of P(i, a, n) = r1(i, 0) M^(l-1)_an
// for |n| < l (edge forms for n = +-l), so every row is a sum of at most five scaled rows of M^(l-1)
// plus two edge entries. The factors split as u = u_m / d_n (likewise v, w), d_n = sqrt((l+n)(l-n))
// for |n| < l and sqrt(2l(2l-1)) for |n| = l. The phase (B = S M S, S = diag((-1)^m)) is folded in:
// a term reading row a of the previous band carries (-1)^(m+a), and the edge terms one more -1.
void ivanic_ruedenberg_band(int l, const double* r1, const double* prev, const double* root, const double* inv_root,
                            double* out) {
  const int size = 2 * l + 1, prev_size = 2 * l - 1;
  auto r = [r1](int i, int j) { return r1[(i + 1) * 3 + (j + 1)]; };
  double inv_d[2 * kMaxBands + 1];
  for (int n = -l + 1; n <= l - 1; ++n) inv_d[n + l] = inv_root[l + n] * inv_root[l - n];
  inv_d[0] = inv_d[size - 1] = inv_root[2 * l] * inv_root[2 * l - 1];
  struct Term {
    double coefficient;
    int i, a;  // coefficient * P(i, a, n)
  };
  for (int m = -l; m <= l; ++m) {
    const int am = std::abs(m);
    const double u = root[l + m] * root[l - m];
    const double v = m == 0 ? -root[2] * root[l - 1] * root[l] * 0.5 : root[l + am - 1] * root[l + am] * 0.5;
    const double w = m == 0 || am >= l - 1 ? 0.0 : -root[l - am - 1] * root[l - am] * 0.5;
    Term terms[5];
    int count = 0;
    if (am < l) terms[count++] = {u, 0, m};
    if (m == 0) {
      terms[count++] = {v, 1, 1};
      terms[count++] = {v, -1, -1};
    } else if (m > 0) {
      if (m == 1) {
        terms[count++] = {v * root[2], 1, 0};
      } else {
        terms[count++] = {v, 1, m - 1};
        terms[count++] = {-v, -1, -m + 1};
      }
      if (w != 0) {
        terms[count++] = {w, 1, m + 1};
        terms[count++] = {w, -1, -m - 1};
      }
    } else {
      if (m == -1) {
        terms[count++] = {v * root[2], -1, 0};
      } else {
        terms[count++] = {v, 1, m + 1};
        terms[count++] = {v, -1, -m - 1};
      }
      if (w != 0) {
        terms[count++] = {w, 1, m - 1};
        terms[count++] = {-w, -1, -m + 1};
      }
    }
    // Interior weights and rows (unused slots read row 0 with weight 0), edge sums.
    double weight[5] = {}, edge_plus = 0, edge_minus = 0;
    const double* src[5] = {prev, prev, prev, prev, prev};
    for (int t = 0; t < count; ++t) {
      const double sign = ((m + terms[t].a) & 1) ? -1.0 : 1.0;
      const double c = sign * terms[t].coefficient;
      const int i = terms[t].i;
      src[t] = prev + (terms[t].a + l - 1) * prev_size;
      weight[t] = c * r(i, 0);
      const double first = src[t][0], last = src[t][prev_size - 1];  // B^(l-1)(a, -l+1), (a, l-1)
      edge_plus -= c * (r(i, 1) * last - r(i, -1) * first);
      edge_minus -= c * (r(i, 1) * first + r(i, -1) * last);
    }
    double* row = out + (m + l) * size;
    row[0] = edge_minus * inv_d[0];
    for (int n = 1; n < size - 1; ++n)
      row[n] = (weight[0] * src[0][n - 1] + weight[1] * src[1][n - 1] + weight[2] * src[2][n - 1] +
                weight[3] * src[3][n - 1] + weight[4] * src[4][n - 1]) *
               inv_d[n];
    row[size - 1] = edge_plus * inv_d[size - 1];
  }
}

}  // namespace

glm::dmat3 rotation_from_yaw_pitch_roll(double yaw_degrees, double pitch_degrees, double roll_degrees) {
  double cy, sy, cp, sp, cr, sr;
  cos_sin_degrees(yaw_degrees, cy, sy);
  cos_sin_degrees(pitch_degrees, cp, sp);
  cos_sin_degrees(roll_degrees, cr, sr);
  // GLM constructors take columns.
  glm::dmat3 ry(glm::dvec3(cy, 0, -sy), glm::dvec3(0, 1, 0), glm::dvec3(sy, 0, cy));
  glm::dmat3 rx(glm::dvec3(1, 0, 0), glm::dvec3(0, cp, sp), glm::dvec3(0, -sp, cp));
  glm::dmat3 rz(glm::dvec3(cr, sr, 0), glm::dvec3(-sr, cr, 0), glm::dvec3(0, 0, 1));
  return ry * rx * rz;
}

Rotation::Rotation(int bands, const glm::dmat3& r) : bands_(bands) {
  if (bands < 1 || bands > kMaxBands)
    fail("SH rotation: band count " + std::to_string(bands) + " is outside 1.." + std::to_string(kMaxBands));
  const glm::dmat3 q = nearest_rotation(r);
  blocks_.assign(block_offset(bands), 0.0);
  if (is_identity(q)) {
    for (int l = 0; l < bands; ++l)
      for (int m = 0; m < 2 * l + 1; ++m) blocks_[block_offset(l) + m * (2 * l + 1) + m] = 1.0;
    return;
  }
  blocks_[0] = 1.0;
  if (bands == 1) return;
  // Band 1 in the paper's basis (Y_1,-1 ~ y, Y_1,0 ~ z, Y_1,1 ~ x): q with rows and columns ordered
  // (y, z, x). With the phase, the entries with m + n odd change sign.
  static constexpr int kAxis[3] = {1, 2, 0};
  double r1[9];
  double* b1 = blocks_.data() + block_offset(1);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      r1[i * 3 + j] = at(q, kAxis[i], kAxis[j]);
      b1[i * 3 + j] = ((i + j) & 1) ? -r1[i * 3 + j] : r1[i * 3 + j];
    }
  double root[2 * kMaxBands + 1], inv_root[2 * kMaxBands + 1];
  for (int k = 0; k <= 2 * bands; ++k) {
    root[k] = std::sqrt(double(k));
    inv_root[k] = k > 0 ? 1.0 / root[k] : 0.0;
  }
  for (int l = 2; l < bands; ++l)
    ivanic_ruedenberg_band(l, r1, blocks_.data() + block_offset(l - 1), root, inv_root,
                           blocks_.data() + block_offset(l));
}

const double* Rotation::block(int l) const { return blocks_.data() + block_offset(l); }

namespace {

// sum_k a[k] x[k] with four interleaved partial sums (independent dependency chains the compiler
// can keep in one vector register), added in a fixed order.
double dot(const double* a, const double* x, int n) {
  double s[4] = {0, 0, 0, 0};
  int k = 0;
  for (; k + 4 <= n; k += 4)
    for (int j = 0; j < 4; ++j) s[j] += a[k + j] * x[k + j];
  for (; k < n; ++k) s[0] += a[k] * x[k];
  return (s[0] + s[1]) + (s[2] + s[3]);
}

}  // namespace

void Rotation::apply(const double* in, double* out) const {
  if (bands_ == 0) return;
  out[0] = in[0];
  for (int l = 1; l < bands_; ++l) {
    const int size = 2 * l + 1, first = l * l;
    const double* b = block(l);
    for (int i = 0; i < size; ++i) out[first + i] = dot(b + i * size, in + first, size);
  }
}

void Rotation::apply(const float* in, float* out) const {
  if (bands_ == 0) return;
  out[0] = in[0];
  double band_in[2 * kMaxBands - 1];
  for (int l = 1; l < bands_; ++l) {
    const int size = 2 * l + 1, first = l * l;
    const double* b = block(l);
    for (int k = 0; k < size; ++k) band_in[k] = in[first + k];
    for (int i = 0; i < size; ++i) out[first + i] = static_cast<float>(dot(b + i * size, band_in, size));
  }
}

RgbCoefficients Rotation::apply(const RgbCoefficients& in) const {
  if (in.bands != bands_)
    fail("SH rotation: coefficients have " + std::to_string(in.bands) + " bands, the rotation " +
         std::to_string(bands_));
  RgbCoefficients out(bands_);
  if (bands_ == 0) return out;
  out.values[0] = in.values[0];
  for (int l = 1; l < bands_; ++l) {
    const int size = 2 * l + 1, first = l * l;
    const double* b = block(l);
    for (int i = 0; i < size; ++i) {
      glm::dvec3 sum(0.0);
      for (int k = 0; k < size; ++k) sum += b[i * size + k] * in.values[first + k];
      out.values[first + i] = sum;
    }
  }
  return out;
}

Rotation Rotation::inverse() const {
  Rotation t = *this;
  for (int l = 1; l < bands_; ++l) {
    const int size = 2 * l + 1;
    const double* b = block(l);
    double* bt = t.blocks_.data() + block_offset(l);
    for (int i = 0; i < size; ++i)
      for (int k = 0; k < size; ++k) bt[k * size + i] = b[i * size + k];
  }
  return t;
}

// ---- float fast paths ----------------------------------------------------------------------------

namespace {

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
