#include "sh/zonal.h"

#include <array>
#include <cmath>

#include "sh/basis.h"

namespace prt::sh {

double legendre(int l, double x) {
  if (l == 0) return 1.0;
  double p_prev = 1.0, p = x;
  for (int k = 1; k < l; ++k) {
    double p_next = ((2.0 * k + 1.0) * x * p - k * p_prev) / (k + 1.0);
    p_prev = p;
    p = p_next;
  }
  return p;
}

double legendre_derivative(int l, double x) {
  // P_l' = sum of (2k+1) P_k over k = l-1, l-3, ... >= 0: one pass of the P recurrence.
  double derivative = 0.0;
  double p_prev = 0.0, p = 1.0;  // P_(k-1), P_k for k = 0
  for (int k = 0; k < l; ++k) {
    if ((l - 1 - k) % 2 == 0) derivative += (2.0 * k + 1.0) * p;
    double p_next = ((2.0 * k + 1.0) * x * p - k * p_prev) / (k + 1.0);
    p_prev = p;
    p = p_next;
  }
  return derivative;
}

double clamped_cosine_factor(int l) {
  if (l == 0) return M_PI;
  if (l == 1) return 2.0 * M_PI / 3.0;
  if (l % 2 == 1) return 0.0;
  // Central binomial term l! / (2^l ((l/2)!)^2) as a product of ratios below 1: no overflow.
  double central = 1.0;
  for (int k = 1; k <= l / 2; ++k) central *= (2.0 * k - 1.0) / (2.0 * k);
  const double sign = (l / 2 - 1) % 2 == 0 ? 1.0 : -1.0;
  return 2.0 * M_PI * sign / ((l + 2.0) * (l - 1.0)) * central;
}

double clamped_cosine_zonal(int l) { return std::sqrt((2.0 * l + 1.0) / (4.0 * M_PI)) * clamped_cosine_factor(l); }

double zonal_value(int bands, const double* zonal, double cos_gamma) {
  double sum = 0.0;
  double p_prev = 0.0, p = 1.0;
  for (int l = 0; l < bands; ++l) {
    sum += zonal[l] * std::sqrt((2.0 * l + 1.0) / (4.0 * M_PI)) * p;
    double p_next = ((2.0 * l + 1.0) * cos_gamma * p - l * p_prev) / (l + 1.0);
    p_prev = p;
    p = p_next;
  }
  return sum;
}

void zonal_to_sh(int bands, const double* zonal, const glm::dvec3& axis, double* out) {
  eval(bands, axis, out);
  for (int l = 0; l < bands; ++l) {
    const double scale = std::sqrt(4.0 * M_PI / (2.0 * l + 1.0)) * zonal[l];
    for (int m = -l; m <= l; ++m) out[index(l, m)] *= scale;
  }
}

void convolve_zonal(int bands, const double* kernel_zonal, double* coefficients) {
  for (int l = 0; l < bands; ++l) {
    const double scale = std::sqrt(4.0 * M_PI / (2.0 * l + 1.0)) * kernel_zonal[l];
    for (int m = -l; m <= l; ++m) coefficients[index(l, m)] *= scale;
  }
}

void convolve_zonal(const double* kernel_zonal, RgbCoefficients& coefficients) {
  for (int l = 0; l < coefficients.bands; ++l) {
    const double scale = std::sqrt(4.0 * M_PI / (2.0 * l + 1.0)) * kernel_zonal[l];
    for (int m = -l; m <= l; ++m) coefficients.values[index(l, m)] *= scale;
  }
}

namespace {

// A_l for every band prt supports, computed once (a constant table).
const std::array<double, kMaxBands>& clamped_cosine_factors() {
  static const std::array<double, kMaxBands> table = [] {
    std::array<double, kMaxBands> a{};
    for (int l = 0; l < kMaxBands; ++l) a[l] = clamped_cosine_factor(l);
    return a;
  }();
  return table;
}

// Up to 3 bands: A_l times the closed-form basis (sh/basis.h's table), no basis evaluation.
//   Y_0 = k0, Y_1..3 = k1 (-y, z, -x), Y_4..8 = (k2 xy, -k2 yz, k3 (3z^2 - 1), -k2 xz, k4 (x^2 - y^2)).
template <typename T>
T irradiance_low_bands(int bands, const T* radiance, const glm::dvec3& n) {
  constexpr double k0 = 0.28209479177387814;  // 1 / (2 sqrt(pi))
  constexpr double k1 = 0.48860251190291992;  // sqrt(3 / (4 pi))
  constexpr double k2 = 1.0925484305920792;   // sqrt(15 / pi) / 2
  constexpr double k3 = 0.31539156525252005;  // sqrt(5 / pi) / 4
  constexpr double k4 = 0.54627421529603959;  // sqrt(15 / pi) / 4
  constexpr double a0 = M_PI * k0;
  constexpr double a1 = 2.0 * M_PI / 3.0 * k1;
  constexpr double a2 = M_PI / 4.0;
  const double x = n.x, y = n.y, z = n.z;
  T e = a0 * radiance[0];
  if (bands >= 2) e += a1 * (z * radiance[2] - y * radiance[1] - x * radiance[3]);
  if (bands >= 3) {
    e += (a2 * k2) * (x * y * radiance[4] - y * z * radiance[5] - x * z * radiance[7]) +
         (a2 * k3) * (3.0 * z * z - 1.0) * radiance[6] + (a2 * k4) * (x * x - y * y) * radiance[8];
  }
  return e;
}

}  // namespace

glm::dvec3 irradiance(const RgbCoefficients& radiance, const glm::dvec3& normal) {
  const int bands = radiance.bands;
  if (bands <= 3) return irradiance_low_bands(bands, radiance.values.data(), normal);
  double basis[kMaxBands * kMaxBands];
  eval(bands, normal, basis);
  const auto& a = clamped_cosine_factors();
  glm::dvec3 e(0.0);
  for (int l = 0; l < bands; ++l) {
    if (a[l] == 0.0) continue;
    glm::dvec3 band(0.0);
    for (int i = l * l; i < (l + 1) * (l + 1); ++i) band += basis[i] * radiance.values[i];
    e += a[l] * band;
  }
  return e;
}

double irradiance(int bands, const double* radiance, const glm::dvec3& normal) {
  if (bands <= 3) return irradiance_low_bands(bands, radiance, normal);
  double basis[kMaxBands * kMaxBands];
  eval(bands, normal, basis);
  const auto& a = clamped_cosine_factors();
  double e = 0.0;
  for (int l = 0; l < bands; ++l) {
    if (a[l] == 0.0) continue;
    double band = 0.0;
    for (int i = l * l; i < (l + 1) * (l + 1); ++i) band += basis[i] * radiance[i];
    e += a[l] * band;
  }
  return e;
}

}  // namespace prt::sh
