#pragma once
// Projection of environment images into SH and reconstruction back into images.
#include "image/image.h"
#include "light/environment.h"
#include "sh/coefficients.h"

namespace prt::light {

/// Projects an equirect radiance image (any 2:1 size) to `bands` bands. Every texel is weighted by its
/// exact solid angle (the integral of sin(theta) over its row times its phi width). Uses the separable
/// structure: associated Legendre factors per row and Fourier sums per row, then one pass over rows.
/// Deterministic for any thread count; `threads` <= 0 uses all cores.
sh::RgbCoefficients project_equirect(const image::Image& equirect, int bands, int threads = 0);

/// Projects six cube faces (OpenGL orientation) to `bands` bands, each texel weighted by its exact
/// solid angle.
sh::RgbCoefficients project_cube(const std::array<image::Image, 6>& faces, int bands, int threads = 0);

/// Dispatches on the environment's layout.
sh::RgbCoefficients project(const Environment& environment, int bands, int threads = 0);

/// Renders SH lighting back into an equirect image (width x height, width = 2 height for a 2:1 map),
/// evaluating the SH at each pixel centre's direction. Linear radiance.
image::Image render_equirect(const sh::RgbCoefficients& coefficients, int width, int height);

}  // namespace prt::light
