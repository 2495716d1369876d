#include "sh/basis.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace prt::sh {

int band_of(int i) {
  int l = static_cast<int>(std::sqrt(static_cast<double>(i)));
  while (l * l > i) --l;
  while ((l + 1) * (l + 1) <= i) ++l;
  return l;
}

namespace {

// Associated Legendre P_l^m(x) for m >= 0, including the Condon-Shortley phase (-1)^m,
// by the textbook recurrence in l (Numerical Recipes' plgndr without its normalisation).
double associated_legendre(int l, int m, double x) {
  double pmm = 1.0;
  if (m > 0) {
    double somx2 = std::sqrt((1.0 - x) * (1.0 + x));
    double fact = 1.0;
    for (int i = 1; i <= m; ++i) {
      pmm *= -fact * somx2;
      fact += 2.0;
    }
  }
  if (l == m) return pmm;
  double pmmp1 = x * (2.0 * m + 1.0) * pmm;
  if (l == m + 1) return pmmp1;
  double pll = 0.0;
  for (int ll = m + 2; ll <= l; ++ll) {
    pll = ((2.0 * ll - 1.0) * x * pmmp1 - (ll + m - 1.0) * pmm) / (ll - m);
    pmm = pmmp1;
    pmmp1 = pll;
  }
  return pll;
}

double normalisation(int l, int m) {
  // K_lm = sqrt((2l+1)/(4pi) * (l-|m|)!/(l+|m|)!), with the factorial ratio built by division.
  double ratio = 1.0;
  for (int k = l - m + 1; k <= l + m; ++k) ratio /= k;
  return std::sqrt((2.0 * l + 1.0) / (4.0 * M_PI) * ratio);
}

}  // namespace

double eval_reference(int l, int m, const glm::dvec3& dir) {
  glm::dvec3 d = glm::normalize(dir);
  double theta = std::acos(std::fmin(1.0, std::fmax(-1.0, d.z)));
  double phi = std::atan2(d.y, d.x);
  int am = m < 0 ? -m : m;
  double p = associated_legendre(l, am, std::cos(theta));
  double k = normalisation(l, am);
  if (m == 0) return k * p;
  if (m > 0) return std::sqrt(2.0) * k * p * std::cos(m * phi);
  return std::sqrt(2.0) * k * p * std::sin(am * phi);
}

namespace {

// Generic evaluation by the factored form Y_lm = N_lm Q_l^|m|(z) {C_m | S_m}(x, y), where
// Q_l^m = P_l^m / sin^m(theta) is a polynomial in z, C_m + i S_m = (x + i y)^m, and N_lm folds
// K_lm, sqrt(2) and nothing else. Q follows the same recurrence in l as P_l^m.
template <typename T>
void eval_generic(int bands, T x, T y, T z, T* out) {
  // Column m = 0 first, then each m > 0: Q_m^m = (-1)^m (2m-1)!!, Q_{m+1}^m = (2m+1) z Q_m^m.
  T c_m = 1, s_m = 0;  // (x + i y)^m
  T q_mm = 1;          // Q_m^m
  for (int m = 0; m < bands; ++m) {
    if (m > 0) {
      T c_next = c_m * x - s_m * y;
      s_m = c_m * y + s_m * x;
      c_m = c_next;
      q_mm *= -static_cast<T>(2 * m - 1);
    }
    T q_lm2 = 0, q_lm1 = q_mm;
    for (int l = m; l < bands; ++l) {
      T q;
      if (l == m) {
        q = q_mm;
      } else if (l == m + 1) {
        q = static_cast<T>(2 * m + 1) * z * q_mm;
      } else {
        q = (static_cast<T>(2 * l - 1) * z * q_lm1 - static_cast<T>(l + m - 1) * q_lm2) / static_cast<T>(l - m);
      }
      if (l > m) {
        q_lm2 = q_lm1;
        q_lm1 = q;
      }
      double k = normalisation(l, m);
      if (m == 0) {
        out[index(l, 0)] = static_cast<T>(k) * q;
      } else {
        T n = static_cast<T>(std::sqrt(2.0) * k);
        out[index(l, m)] = n * q * c_m;
        out[index(l, -m)] = n * q * s_m;
      }
    }
  }
}

}  // namespace

void eval(int bands, const glm::dvec3& dir, double* out) { eval_generic<double>(bands, dir.x, dir.y, dir.z, out); }

void eval(int bands, const glm::vec3& dir, float* out) {
  // Accumulate in double: the generic path is the accuracy reference for the float fast path.
  double tmp[kMaxBands * kMaxBands];
  eval_generic<double>(bands, dir.x, dir.y, dir.z, tmp);
  for (int i = 0; i < bands * bands; ++i) out[i] = static_cast<float>(tmp[i]);
}

}  // namespace prt::sh
