#pragma once
// Windowing against ringing: per-band weights w_l multiply every coefficient of band l. A window is a
// zonal convolution (a blur), so it trades ringing (negative lobes next to bright, sharp features)
// for resolution. The defaults below are chosen so that each window, at every band count 2..32,
// brings the minimum of the band-limited clamped cosine closer to zero and shrinks the negative lobes
// of a band-limited directional light (tests/sh/test_window.cpp checks both).
#include <string>
#include <vector>

#include "sh/coefficients.h"

namespace prt::sh {

enum class Window {
  none,       ///< w_l = 1.
  hanning,    ///< w_l = (1 + cos(pi l / W)) / 2 for l < W, 0 for l >= W. Param W > 0, default bands + 1.
  lanczos,    ///< w_l = sin(pi l / W) / (pi l / W) for 0 < l < W, 0 for l >= W. Param W > 0, default bands + 1.
  laplacian,  ///< Sloan's Laplacian penalty: w_l = 1 / (1 + lambda l^2 (l+1)^2). Param lambda > 0,
              ///< default 1 / (bands (bands+1))^2, i.e. w_l = 1 / (1 + (l(l+1) / (bands(bands+1)))^2).
};

/// Parses "none", "hanning", "lanczos" or "laplacian"; throws prt::Error naming the bad value.
Window parse_window(const std::string& name);
const char* window_name(Window w);

/// The parameter `param` <= 0 stands for: W = bands + 1 (hanning, lanczos), lambda =
/// 1 / (bands (bands+1))^2 (laplacian), ignored (none).
double default_window_param(Window window, int bands);

/// Per-band weights w_0..w_(bands-1). `param` <= 0 selects the window's default. w_0 = 1 always;
/// the weights never increase with l. Precondition: 1 <= bands <= kMaxBands.
std::vector<double> window_weights(Window window, int bands, double param = 0.0);

/// Multiplies every coefficient of band l by weights[l] (weights.size() >= bands), in place.
void apply_window(const std::vector<double>& weights, RgbCoefficients& coefficients);
void apply_window(const std::vector<double>& weights, int bands, double* coefficients);

/// The smallest lambda >= 0 for which the Laplacian-windowed reconstruction of the function with
/// coefficients[0..bands^2) is non-negative over the sphere (0 when it already is). The minimum is
/// taken over a fixed grid of (8 bands) x (16 bands) directions, uniform in theta and phi, so the
/// reconstruction may still dip below zero between grid points by a small fraction of its range.
/// Found by doubling then bisection to a relative 1e-9. Throws prt::Error when no lambda can work
/// (the mean, coefficient 0, is <= 0 while the function is negative somewhere).
double nonnegative_laplacian_lambda(int bands, const double* coefficients);

/// The largest of the three channels' lambdas: one window keeps every channel non-negative.
double nonnegative_laplacian_lambda(const RgbCoefficients& coefficients);

/// Same for a zonal function (zonal[0..bands), see sh/zonal.h), minimised over 64 bands + 1 angles
/// uniform in [0, pi] (both ends included). E.g. with clamped_cosine_zonal: the smallest lambda whose windowed irradiance
/// kernel is non-negative, so that the irradiance of any non-negative radiance stays non-negative
/// (about 0.178 for 3 bands, 0.25 for 2; it barely changes with the band count).
double nonnegative_laplacian_lambda_zonal(int bands, const double* zonal);

}  // namespace prt::sh
