#pragma once
// Windowing against ringing: per-band weights w_l multiply every coefficient of band l.
#include <string>
#include <vector>

#include "sh/coefficients.h"

namespace prt::sh {

enum class Window {
  none,       ///< w_l = 1.
  hanning,    ///< w_l = (1 + cos(pi l / W)) / 2 for l < W, 0 beyond; param W > 0 (default: bands).
  lanczos,    ///< w_l = sinc(pi l / W) = sin(pi l / W) / (pi l / W) for l < W, 0 beyond; param W (default: bands).
  laplacian,  ///< Sloan's Laplacian penalty: w_l = 1 / (1 + lambda l^2 (l+1)^2); param lambda >= 0
              ///< (default: documented in window.cpp and docs/conventions.md).
};

/// Parses "none", "hanning", "lanczos" or "laplacian"; throws prt::Error naming the bad value.
Window parse_window(const std::string& name);
const char* window_name(Window w);

/// Per-band weights w_0..w_(bands-1). `param` <= 0 selects the window's default. w_0 = 1 always.
std::vector<double> window_weights(Window window, int bands, double param = 0.0);

/// Multiplies every coefficient of band l by weights[l] (weights.size() >= bands), in place.
void apply_window(const std::vector<double>& weights, RgbCoefficients& coefficients);

}  // namespace prt::sh
