#pragma once
// Projection of environment images into SH and reconstruction back into images.
//
// Every texel stands for the radiance at its centre and is weighted by its exact solid angle, so the
// projection is c_i = sum over texels of L(texel) Y_i(centre) Omega(texel). For an equirect map that is
// the midpoint rule in phi, exact for trigonometric polynomials of degree < width (every band-limited
// function, in phi), and in theta a midpoint rule whose weights integrate sin(theta) over the row
// exactly: a constant map gives c_0 = 2 sqrt(pi) L exactly; the other coefficients carry an error of
// order (pi / height)^2 / 12 times the radiance (a constant map L, 9 bands: at most 6e-5 L at 512x256,
// 4e-6 L at 2048x1024; the derivation is in tests/light/test_projection.cpp).
// Images must be finite and non-negative for the result to mean radiance (load_environment ensures it);
// the projection itself computes the sums as given.
#include <array>

#include "image/image.h"
#include "light/environment.h"
#include "sh/coefficients.h"

namespace prt::light {

/// Solid angle (steradians) of one texel of row `row` (0 = top) of an equirect map width x height:
/// (cos(theta_top) - cos(theta_bottom)) * 2 pi / width. The texels sum to 4 pi.
double equirect_texel_solid_angle(int row, int width, int height);

/// Solid angle of texel (i, j) of an n x n cube face, by the atan area formula: with
/// A(a, b) = atan2(a b, sqrt(a^2 + b^2 + 1)) on face coordinates a, b in [-1, 1], the texel
/// [a0, a1] x [b0, b1] subtends A(a0, b0) - A(a0, b1) - A(a1, b0) + A(a1, b1). A face sums to 4 pi / 6.
double cube_texel_solid_angle(int i, int j, int n);

/// Projects an equirect radiance image (any 2:1 size, >= 3 channels, the first three used) to `bands`
/// bands. Uses the separable structure of a lat-long grid: per row, Fourier sums of the pixels
/// (folded around the centre column, phi -> -phi); per column of the coefficient triangle, normalised
/// associated Legendre factors of each row's cos(theta), summed over rows in order; this gives the
/// coefficients in a frame whose polar axis is world +Y, which a fixed rotation, Rx(90 degrees), takes
/// to the SH frame (polar axis +Z, sh/basis.h). Cost O(width height bands) plus O(height bands^2).
/// Deterministic for any thread count; `threads` <= 0 uses all cores.
/// Throws prt::Error if the image is not 2:1 or has < 3 channels, or if bands is outside 1..kMaxBands.
sh::RgbCoefficients project_equirect(const image::Image& equirect, int bands, int threads = 0);

/// The same sum as project_equirect, computed texel by texel (direction, sh::eval in double of every
/// basis function, solid angle) in double on one thread: slow and obviously correct, the reference
/// that tests and benchmarks compare the separable projection against.
sh::RgbCoefficients project_equirect_reference(const image::Image& equirect, int bands);

/// Projects six square cube faces of equal size (OpenGL orientation, see environment.h) to `bands`
/// bands, each texel weighted by cube_texel_solid_angle. Deterministic for any thread count.
/// Throws prt::Error for faces that are not square and equal, or bands outside 1..kMaxBands.
sh::RgbCoefficients project_cube(const std::array<image::Image, 6>& faces, int bands, int threads = 0);

/// Dispatches on the environment's layout.
sh::RgbCoefficients project(const Environment& environment, int bands, int threads = 0);

/// Renders SH lighting back into an equirect image of width x height pixels (any size >= 1; use
/// width = 2 height for a 2:1 map) by evaluating the SH at each pixel centre's direction (equirect
/// convention of environment.h). Linear radiance, 3 channels; no clamping (ringing may go negative).
image::Image render_equirect(const sh::RgbCoefficients& coefficients, int width, int height, int threads = 0);

}  // namespace prt::light
