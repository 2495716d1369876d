// The double-precision Rotation (sh/rotation.h): Ivanic-Ruedenberg blocks, their application, and the
// CLI's yaw-pitch-roll convention. The float fast paths are in rotation.cpp.
//
// BITS ACROSS CPUS. This file is compiled without floating-point contraction (src/sh/CMakeLists.txt:
// -ffp-contract=off) and writes every multiply-add it wants fused as std::fma. With contraction on,
// GCC fuses a * b + c differently in the vectorised body of a loop and in its scalar remainder, and
// which elements each one handles depends on the target's vector width: an AVX-512 build then rotated
// one lighting coefficient of `prt light` one bit away from an AVX2 build's. Without contraction the
// blocks and every apply give the same bits on any x86-64 target (tests/light/test_sun_cli.cpp, golden
// files; docs/conventions.md, "Determinism").
#include "sh/rotation.h"

#include <cmath>
#include <string>

#include <glm/mat3x3.hpp>

#include "core/error.h"

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
      edge_plus = std::fma(-c, std::fma(r(i, 1), last, -(r(i, -1) * first)), edge_plus);
      edge_minus = std::fma(-c, std::fma(r(i, 1), first, r(i, -1) * last), edge_minus);
    }
    double* row = out + (m + l) * size;
    row[0] = edge_minus * inv_d[0];
    for (int n = 1; n < size - 1; ++n) {
      double sum = weight[0] * src[0][n - 1];
      for (int t = 1; t < 5; ++t) sum = std::fma(weight[t], src[t][n - 1], sum);
      row[n] = sum * inv_d[n];
    }
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

// sum_k a[k] x[k] in eight interleaved partial sums (independent chains of fused multiply-adds, which the
// compiler may keep in one vector register), added pairwise in a fixed order.
double dot(const double* a, const double* x, int n) {
  constexpr int kPartial = 8;
  double s[kPartial] = {};
  int k = 0;
  for (; k + kPartial <= n; k += kPartial)
    for (int j = 0; j < kPartial; ++j) s[j] = std::fma(a[k + j], x[k + j], s[j]);
  for (; k < n; ++k) s[0] = std::fma(a[k], x[k], s[0]);
  return ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
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
      for (int k = 0; k < size; ++k)
        for (int c = 0; c < 3; ++c) sum[c] = std::fma(b[i * size + k], in.values[first + k][c], sum[c]);
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

}  // namespace prt::sh
