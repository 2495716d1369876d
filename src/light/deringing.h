#pragma once
// The lighting window `--window auto` (the default wherever SH lighting is shaded) windows nothing: the
// SH lighting is shaded as it is and what the shading sees is clamped at zero instead (every negative
// shaded channel becomes 0: light::SceneLighting::clamp_negative, as prt shade applies it,
// shade/scene_shading.h; the renderer clamps where it composites the discs, shaders/prt_sun.frag). Why (issue 36; docs/conventions.md, "Windows (against ringing)"): the true
// radiance t is >= 0, so for any shaded value x, |max(x, 0) - t| <= |x - t|: the clamp never moves a
// value away from the truth, so auto is never worse than `--window none` against it, at every vertex,
// view and channel, diffuse and glossy, and nothing it shades is negative. A window is a blur of the
// whole sky that fixes negative lobes far from where they matter at the price of every bright feature;
// the earlier rule here (the least Laplacian window keeping radiance and irradiance non-negative) raised
// the glossy error on a bright sky from 19.7% (none) to 28.5% against the path-traced truth. Fixed
// windows (hanning, lanczos, laplacian) stay available by name.
#include <string>

#include "sh/coefficients.h"
#include "sh/window.h"

namespace prt::light {

/// A window request: `automatic` (the rule above), or a fixed window and parameter (<= 0: its default).
struct WindowRequest {
  bool automatic = true;
  bool radiance = false;  ///< the consumer is glossy (sees the radiance itself); the rule above treats both alike
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

/// Applies `request` to `lighting` in place and says what it applied.
WindowChoice apply_window_request(const WindowRequest& request, sh::RgbCoefficients& lighting);

}  // namespace prt::light
