#include "sh/window.h"

#include <algorithm>
#include <cmath>

#include <glm/vec3.hpp>

#include "core/error.h"
#include "sh/basis.h"
#include "sh/zonal.h"

// Default parameters, and why (the numbers quoted are minima of the windowed clamped cosine
// sum_l w_l A_l (2l+1)/(4 pi) P_l(t), whose unwindowed 3-band minimum is -0.0396):
// - Hanning and Lanczos, W = bands + 1. With W = bands the window's first zero falls on the first
//   dropped band, which sounds natural, but at 3 bands Hanning keeps only 1/4 of band 2 and the
//   clamped cosine's back lobe grows (minimum -0.0469). W = bands + 1 (Hanning 3 bands: 1, 0.85, 0.5)
//   moves every minimum toward zero for all band counts 2..32 (3 bands: -0.0224 Hanning, -0.0192
//   Lanczos) and shrinks a directional light's negative lobes (relative to its peak) 1.4x to 6x.
// - Laplacian, lambda = 1 / (bands (bands+1))^2: the penalty lambda l^2 (l+1)^2 is the squared
//   Laplacian eigenvalue; this lambda makes w_l = 1 / (1 + (l(l+1) / (bands(bands+1)))^2), the same
//   profile in l / bands for every band count, and halves the first dropped band (w_bands = 1/2). It
//   is the mildest of the three (3 bands: 1, 0.973, 0.8; clamped cosine minimum -0.0328).
//   Non-negativity needs a much larger lambda that hardly depends on the band count (~0.18 for the
//   clamped cosine, ~1/3 for a directional light), i.e. a blur to about 2 bands, so it is a
//   per-function choice: nonnegative_laplacian_lambda*() find it.

namespace prt::sh {

Window parse_window(const std::string& name) {
  if (name == "none") return Window::none;
  if (name == "hanning") return Window::hanning;
  if (name == "lanczos") return Window::lanczos;
  if (name == "laplacian") return Window::laplacian;
  fail("unknown window '" + name + "' (expected none, hanning, lanczos or laplacian)");
}

const char* window_name(Window w) {
  switch (w) {
    case Window::none: return "none";
    case Window::hanning: return "hanning";
    case Window::lanczos: return "lanczos";
    case Window::laplacian: return "laplacian";
  }
  return "none";
}

double default_window_param(Window window, int bands) {
  switch (window) {
    case Window::hanning:
    case Window::lanczos: return bands + 1.0;
    case Window::laplacian: {
      const double n = static_cast<double>(bands) * (bands + 1.0);
      return 1.0 / (n * n);
    }
    case Window::none: break;
  }
  return 0.0;
}

namespace {

std::vector<double> laplacian_weights(int bands, double lambda) {
  std::vector<double> w(static_cast<std::size_t>(bands));
  for (int l = 0; l < bands; ++l) {
    const double eigen = static_cast<double>(l) * (l + 1.0);
    w[l] = 1.0 / (1.0 + lambda * eigen * eigen);
  }
  return w;
}

}  // namespace

std::vector<double> window_weights(Window window, int bands, double param) {
  if (param <= 0.0) param = default_window_param(window, bands);
  std::vector<double> w(static_cast<std::size_t>(bands), 1.0);
  switch (window) {
    case Window::none: break;
    case Window::hanning:
      for (int l = 1; l < bands; ++l) w[l] = l < param ? 0.5 * (1.0 + std::cos(M_PI * l / param)) : 0.0;
      break;
    case Window::lanczos:
      for (int l = 1; l < bands; ++l) {
        const double x = M_PI * l / param;
        w[l] = l < param ? std::sin(x) / x : 0.0;
      }
      break;
    case Window::laplacian: w = laplacian_weights(bands, param); break;
  }
  return w;
}

void apply_window(const std::vector<double>& weights, RgbCoefficients& coefficients) {
  for (int l = 0; l < coefficients.bands; ++l)
    for (int i = l * l; i < (l + 1) * (l + 1); ++i) coefficients.values[i] *= weights[l];
}

void apply_window(const std::vector<double>& weights, int bands, double* coefficients) {
  for (int l = 0; l < bands; ++l)
    for (int i = l * l; i < (l + 1) * (l + 1); ++i) coefficients[i] *= weights[l];
}

namespace {

// Per-band partial sums S_l(d) of a function at check points d, stored point-major
// (sums[p * bands + l]); the windowed reconstruction at d is sum_l w_l S_l(d).
struct BandSums {
  int bands = 0;
  std::vector<double> sums;
};

double windowed_minimum(const BandSums& table, double lambda) {
  const std::vector<double> w = laplacian_weights(table.bands, lambda);
  double minimum = INFINITY;
  for (std::size_t p = 0; p < table.sums.size(); p += static_cast<std::size_t>(table.bands)) {
    double value = 0.0;
    for (int l = 0; l < table.bands; ++l) value += w[l] * table.sums[p + l];
    minimum = std::min(minimum, value);
  }
  return minimum;
}

// Smallest lambda with a non-negative minimum: doubling to bracket it, then bisection.
double smallest_nonnegative_lambda(const BandSums& table, double mean_coefficient) {
  if (windowed_minimum(table, 0.0) >= 0.0) return 0.0;
  if (!(mean_coefficient > 0.0))
    fail("laplacian window: the function is negative somewhere and its mean is not positive, so no lambda "
         "makes it non-negative");
  double lo = 0.0, hi = 1e-8;
  for (int doubling = 0; windowed_minimum(table, hi) < 0.0; ++doubling) {
    if (doubling > 300) fail("laplacian window: no lambda below 1e82 makes the function non-negative");
    lo = hi;
    hi *= 2.0;
  }
  while (hi - lo > 1e-9 * hi) {
    const double mid = 0.5 * (lo + hi);
    (windowed_minimum(table, mid) < 0.0 ? lo : hi) = mid;
  }
  return hi;
}

// Band sums of every channel at the (8 bands + 1) x (16 bands) theta-phi grid. The basis at
// (theta, phi) is the basis at (theta, 0) times cos(m phi) (m > 0) or sin(|m| phi) (m < 0), so one
// basis evaluation per row suffices.
std::vector<BandSums> grid_band_sums(int bands, const std::vector<const double*>& functions) {
  const int rows = 8 * bands + 1, columns = 16 * bands;
  std::vector<BandSums> tables(functions.size());
  for (auto& t : tables) {
    t.bands = bands;
    t.sums.reserve(static_cast<std::size_t>(rows) * columns * bands);
  }
  std::vector<double> cos_m(static_cast<std::size_t>(columns) * bands), sin_m(cos_m.size());
  for (int j = 0; j < columns; ++j) {
    const double phi = 2.0 * M_PI * j / columns;
    for (int m = 0; m < bands; ++m) {
      cos_m[static_cast<std::size_t>(j) * bands + m] = std::cos(m * phi);
      sin_m[static_cast<std::size_t>(j) * bands + m] = std::sin(m * phi);
    }
  }
  std::vector<double> row_basis(static_cast<std::size_t>(bands) * bands);
  for (int i = 0; i < rows; ++i) {
    const double theta = M_PI * i / (rows - 1);
    eval(bands, glm::dvec3(std::sin(theta), 0.0, std::cos(theta)), row_basis.data());
    for (int j = 0; j < columns; ++j) {
      const double* c = &cos_m[static_cast<std::size_t>(j) * bands];
      const double* s = &sin_m[static_cast<std::size_t>(j) * bands];
      for (std::size_t f = 0; f < functions.size(); ++f) {
        const double* coefficients = functions[f];
        for (int l = 0; l < bands; ++l) {
          double sum = row_basis[index(l, 0)] * coefficients[index(l, 0)];
          for (int m = 1; m <= l; ++m) {
            sum += row_basis[index(l, m)] * (c[m] * coefficients[index(l, m)] +
                                             s[m] * coefficients[index(l, -m)]);
          }
          tables[f].sums.push_back(sum);
        }
      }
    }
  }
  return tables;
}

}  // namespace

double nonnegative_laplacian_lambda(int bands, const double* coefficients) {
  const auto tables = grid_band_sums(bands, {coefficients});
  return smallest_nonnegative_lambda(tables[0], coefficients[0]);
}

double nonnegative_laplacian_lambda(const RgbCoefficients& coefficients) {
  std::vector<double> channels[3];
  for (int channel = 0; channel < 3; ++channel)
    for (const glm::dvec3& v : coefficients.values) channels[channel].push_back(v[channel]);
  const auto tables =
      grid_band_sums(coefficients.bands, {channels[0].data(), channels[1].data(), channels[2].data()});
  double lambda = 0.0;
  for (int channel = 0; channel < 3; ++channel)
    lambda = std::max(lambda, smallest_nonnegative_lambda(tables[channel], channels[channel][0]));
  return lambda;
}

double nonnegative_laplacian_lambda_zonal(int bands, const double* zonal) {
  const int points = 64 * bands + 1;
  BandSums table;
  table.bands = bands;
  table.sums.reserve(static_cast<std::size_t>(points) * bands);
  for (int i = 0; i < points; ++i) {
    const double t = std::cos(M_PI * i / (points - 1));
    double p_prev = 0.0, p = 1.0;
    for (int l = 0; l < bands; ++l) {
      table.sums.push_back(zonal[l] * std::sqrt((2.0 * l + 1.0) / (4.0 * M_PI)) * p);
      const double p_next = ((2.0 * l + 1.0) * t * p - l * p_prev) / (l + 1.0);
      p_prev = p;
      p = p_next;
    }
  }
  return smallest_nonnegative_lambda(table, zonal[0]);
}

}  // namespace prt::sh
