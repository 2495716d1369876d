#pragma once
// The lighting window `--window auto` (the default wherever SH lighting is shaded): the least
// windowing that leaves the reconstructed radiance AND the diffuse-convolved lighting (irradiance)
// non-negative over the sphere. It is Sloan's Laplacian window w_l = 1 / (1 + lambda l^2 (l+1)^2)
// ("Stupid Spherical Harmonics Tricks", 2008; sh/window.h) with the smallest lambda >= 0 that makes
// both non-negative on the dense direction grid of sh::nonnegative_laplacian_lambda, found per channel:
//   lambda = max(lambda_radiance(c), lambda_irradiance(A_l c)),  A_l = sh::clamped_cosine_factor(l).
// lambda = 0 (no window) when both already are. docs/conventions.md, "Sun and sky".
#include <string>

#include "sh/coefficients.h"
#include "sh/window.h"

namespace prt::light {

/// A window request: `automatic` (the rule above), or a fixed window and parameter (<= 0: its default).
struct WindowRequest {
  bool automatic = true;
  sh::Window window = sh::Window::none;
  double param = 0.0;
};

/// Parses "auto", "none", "hanning", "lanczos", "laplacian" with an optional parameter (> 0 finite, or
/// <= 0 for the window's default). Throws prt::Error("--window: ...") naming the bad value.
WindowRequest parse_window_request(const std::string& name, double param = 0.0);

/// What was applied: the window, its parameter and its description for files and summaries, e.g.
/// "none", "laplacian(0.0012)", "hanning(6)".
struct WindowChoice {
  sh::Window window = sh::Window::none;
  double param = 0.0;
  std::string description = "none";
};

/// The smallest Laplacian lambda of the rule above for `lighting` (0 when it needs none).
double auto_window_lambda(const sh::RgbCoefficients& lighting);

/// Applies `request` to `lighting` in place and says what it applied.
WindowChoice apply_window_request(const WindowRequest& request, sh::RgbCoefficients& lighting);

}  // namespace prt::light
