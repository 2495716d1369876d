#pragma once
// The lighting window `--window auto` (the default wherever SH lighting is shaded): the least windowing
// that leaves what the shading integrates non-negative over the sphere. It is Sloan's Laplacian window
// w_l = 1 / (1 + lambda l^2 (l+1)^2) ("Stupid Spherical Harmonics Tricks", 2008; sh/window.h) with the
// smallest lambda >= 0 found per channel on the dense direction grid of sh::nonnegative_laplacian_lambda:
//   diffuse consumers:  the diffuse-convolved lighting (irradiance, A_l c) non-negative:
//                       lambda = lambda_irradiance(A_l c),  A_l = sh::clamped_cosine_factor(l);
//   glossy consumers:   the reconstructed radiance as well (a glossy lobe sees the radiance itself):
//                       lambda = max(lambda_radiance(c), lambda_irradiance(A_l c)).
// lambda = 0 (no window) when that already holds. Why diffuse shading is not held to the radiance
// criterion (measured, docs/conventions.md, "Sun and sky"): once the sun is a disc, the residual sky of
// an outdoor map still rings in radiance (the bright horizon glow beside a dark ground), and the
// Laplacian window that removes that ringing blurs the sky so much that the shaded error against the
// path-traced truth triples, while its irradiance is already non-negative.
#include <string>

#include "sh/coefficients.h"
#include "sh/window.h"

namespace prt::light {

/// A window request: `automatic` (the rule above), or a fixed window and parameter (<= 0: its default).
struct WindowRequest {
  bool automatic = true;
  bool radiance = false;  ///< automatic: also keep the radiance non-negative (glossy consumers)
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

/// The smallest Laplacian lambda of the rule above for `lighting` (0 when it needs none); `radiance`
/// selects the glossy criterion.
double auto_window_lambda(const sh::RgbCoefficients& lighting, bool radiance);

/// Applies `request` to `lighting` in place and says what it applied.
WindowChoice apply_window_request(const WindowRequest& request, sh::RgbCoefficients& lighting);

}  // namespace prt::light
