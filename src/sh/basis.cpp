#include "sh/basis.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

#include <glm/geometric.hpp>

#include "sh/eval_kernels.h"

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

// One direction: the straight-line kernel for bands <= kMaxFastBands (dispatched through a table of
// instantiations), the runtime-loop recurrence beyond. Both read the compile-time constant tables of
// eval_kernels.h; nothing is recomputed per call.
template <typename T>
using OneFunction = void (*)(T, T, T, T*);

template <int N, typename T>
void eval_one_fixed(T x, T y, T z, T* out) {
  auto put = [out](int k, T v) { out[k] = v; };
  detail::eval_fixed<N, T>(x, y, z, put);
}

template <typename T, int... I>
constexpr auto make_one_table(std::integer_sequence<int, I...>) {
  return std::array<OneFunction<T>, sizeof...(I)>{&eval_one_fixed<I + 1, T>...};
}

template <typename T>
void eval_one(int bands, T x, T y, T z, T* out) {
  static constexpr auto kFixed = make_one_table<T>(std::make_integer_sequence<int, kMaxFastBands>{});
  if (bands >= 1 && bands <= kMaxFastBands) {
    kFixed[static_cast<std::size_t>(bands - 1)](x, y, z, out);
  } else {
    detail::eval_one_generic(bands, x, y, z, out);
  }
}

}  // namespace

void eval(int bands, const glm::dvec3& dir, double* out) { eval_one<double>(bands, dir.x, dir.y, dir.z, out); }

void eval(int bands, const glm::vec3& dir, float* out) { eval_one<float>(bands, dir.x, dir.y, dir.z, out); }

}  // namespace prt::sh
