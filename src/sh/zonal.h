#pragma once
// Zonal harmonics (functions symmetric about an axis), Funk-Hecke convolution, the clamped cosine
// and irradiance. A zonal function about +z has coefficients only at m = 0; we store those "zonal
// coefficients" z_l = integral of f(d) Y_l0(d) dd, one per band.
#include <glm/vec3.hpp>

#include "sh/coefficients.h"

namespace prt::sh {

/// Funk-Hecke factor of the clamped cosine max(cos theta, 0) for band l >= 0: A_l, such that the
/// irradiance E_lm = A_l L_lm. A_0 = pi, A_1 = 2pi/3, A_2 = pi/4, A_3 = 0, A_4 = -pi/24, odd l > 1 give 0.
/// Closed form for any l (Ramamoorthi and Hanrahan 2001, eq. 8), evaluated without overflow.
double clamped_cosine_factor(int l);

/// Zonal coefficient of max(cos theta, 0) about +z: z_l = sqrt((2l+1)/(4 pi)) * A_l.
double clamped_cosine_zonal(int l);

/// Expands a zonal function with coefficients zonal[0..bands) about `axis` (unit) into full SH:
/// out[index(l, m)] = sqrt(4 pi / (2l+1)) * zonal[l] * Y_lm(axis). `out` holds bands^2 values.
void zonal_to_sh(int bands, const double* zonal, const glm::dvec3& axis, double* out);

/// Funk-Hecke convolution of f (coefficients, bands^2) with a zonal kernel h (zonal[0..bands)):
/// (h * f)_lm = sqrt(4 pi / (2l+1)) h_l f_lm, in place.
void convolve_zonal(int bands, const double* kernel_zonal, double* coefficients);
void convolve_zonal(const double* kernel_zonal, RgbCoefficients& coefficients);

/// Irradiance at unit normal n from radiance coefficients: E(n) = sum_lm A_l L_lm Y_lm(n), in the
/// radiance's units times steradians. Lambert exit radiance is albedo * E / pi.
glm::dvec3 irradiance(const RgbCoefficients& radiance, const glm::dvec3& normal);

}  // namespace prt::sh
